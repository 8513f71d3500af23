/* Whole-file reading for the library's input parsers (io/textfile.h). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/textfile.h"

biref_status biref_read_text(const char *path, size_t max_bytes, char **text, size_t *len, char *msg,
                                size_t msg_len)
{
    *text = NULL;
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f) {
        if (msg && msg_len) snprintf(msg, msg_len, "cannot read: %s", strerror(errno));
        return BIREF_ERR_IO;
    }
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap + 1);
    const char *why = buf ? NULL : "out of memory";
    while (!why) {
        if (n == cap) {
            if (cap >= max_bytes) {
                why = "file too large";
                break;
            }
            char *nb = realloc(buf, 2 * cap + 1);
            if (!nb) {
                why = "out of memory";
                break;
            }
            buf = nb;
            cap *= 2;
        }
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0) {
            if (ferror(f)) why = strerror(errno);
            break;
        }
    }
    fclose(f);
    if (why) {
        free(buf);
        if (msg && msg_len) snprintf(msg, msg_len, "cannot read: %s", why);
        return strcmp(why, "out of memory") ? BIREF_ERR_IO : BIREF_ERR_NOMEM;
    }
    buf[n] = '\0';
    *text = buf;
    *len = n;
    return BIREF_OK;
}
