/* Strict JSON parsing shared by every input-file loader (json_strict.h). */
#include "io/json_strict.h"

#include <stdio.h>
#include <string.h>

/* Byte offset -> "line L, column C" for parse errors. */
static void line_col(const char *text, size_t off, int *line, int *col)
{
    *line = 1;
    *col = 1;
    for (size_t i = 0; i < off; i++) {
        if (text[i] == '\n') {
            (*line)++;
            *col = 1;
        } else {
            (*col)++;
        }
    }
}

/* RFC 8259: a string holds no raw control character (U+0000 to U+001F, escaped as \t, \u0001, ...),
 * which cJSON accepts. The offset of the first one in a string, or len if there is none. */
static size_t raw_control_in_string(const char *text, size_t len)
{
    int in_string = 0;
    for (size_t i = 0; i < len; i++) {
        const unsigned char c = (unsigned char)text[i];
        if (!in_string) {
            in_string = c == '"';
        } else if (c < 0x20) {
            return i;
        } else if (c == '\\') {
            if (i + 1 < len && (unsigned char)text[i + 1] < 0x20) return i + 1;
            i++; /* the escaped character */
        } else if (c == '"') {
            in_string = 0;
        }
    }
    return len;
}

cJSON *biref_json_parse_strict(const char *text, size_t len, char *msg, size_t msg_len)
{
    if (!text) {
        if (msg && msg_len) snprintf(msg, msg_len, "no input");
        return NULL;
    }
    int line, col;
    const size_t ctrl = raw_control_in_string(text, len);
    if (ctrl < len) {
        line_col(text, ctrl, &line, &col);
        if (msg && msg_len)
            snprintf(msg, msg_len, "malformed JSON at line %d, column %d: a raw control character (byte 0x%02x) in a string",
                     line, col, (unsigned)(unsigned char)text[ctrl]);
        return NULL;
    }
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithLengthOpts(text, len, &end, 0);
    if (!root) {
        /* cJSON reports where it stopped; a truncated file stops at its end. */
        size_t off = end && end >= text && end <= text + len ? (size_t)(end - text) : len;
        line_col(text, off, &line, &col);
        if (msg && msg_len) {
            if (off >= len)
                snprintf(msg, msg_len, "malformed JSON: unexpected end of file (truncated?)");
            else
                snprintf(msg, msg_len, "malformed JSON at line %d, column %d", line, col);
        }
        return NULL;
    }
    /* Anything but whitespace after the value is garbage (e.g. two objects pasted together). */
    size_t off = end ? (size_t)(end - text) : len;
    while (off < len && (text[off] == ' ' || text[off] == '\t' || text[off] == '\n' || text[off] == '\r')) off++;
    if (off < len && text[off] != '\0') {
        line_col(text, off, &line, &col);
        if (msg && msg_len) snprintf(msg, msg_len, "malformed JSON: extra text at line %d, column %d", line, col);
        cJSON_Delete(root);
        return NULL;
    }
    return root;
}

const char *biref_json_bad_key(const cJSON *obj, const char *const *allowed, int *twice)
{
    for (const cJSON *it = obj->child; it; it = it->next) {
        const char *k = it->string ? it->string : "";
        if (!strcmp(k, "comment") || k[0] == '_') continue;
        int known = 0;
        for (const char *const *a = allowed; *a; a++)
            if (!strcmp(*a, k)) known = 1;
        *twice = 0;
        if (!known) return k;
        *twice = 1;
        for (const cJSON *jt = obj->child; jt != it; jt = jt->next)
            if (jt->string && !strcmp(jt->string, k)) return k;
    }
    return NULL;
}
