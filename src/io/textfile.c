/* Whole text files with a size limit (textfile.h). */
#include "io/textfile.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* "16 MiB", "64 KiB" or "100 bytes". */
static void size_text(size_t n, char *buf, size_t len)
{
    if (n >= (1u << 20) && n % (1u << 20) == 0)
        snprintf(buf, len, "%zu MiB", n >> 20);
    else if (n >= 1024 && n % 1024 == 0)
        snprintf(buf, len, "%zu KiB", n >> 10);
    else
        snprintf(buf, len, "%zu bytes", n);
}

/* Reads f into *buf (capacity *cap, grown up to max_bytes). Returns NULL or the reason. */
static const char *read_all(FILE *f, size_t max_bytes, char **buf, size_t *cap, size_t *n, biref_status *s)
{
    for (;;) {
        if (*n == *cap) {
            if (*cap >= max_bytes) { /* exactly max_bytes is allowed: is there a byte more? */
                char more;
                if (fread(&more, 1, 1, f) == 0) return ferror(f) ? (*s = BIREF_ERR_IO, strerror(errno)) : NULL;
                return *s = BIREF_ERR_INVALID, "too large";
            }
            size_t grown = *cap > max_bytes / 2 ? max_bytes : 2 * *cap;
            char *nb = realloc(*buf, grown + 1);
            if (!nb) return *s = BIREF_ERR_NOMEM, "out of memory";
            *buf = nb;
            *cap = grown;
        }
        size_t got = fread(*buf + *n, 1, *cap - *n, f);
        /* Text has no NUL byte: /dev/zero or a binary file stops here, not at the limit. */
        if (got && memchr(*buf + *n, '\0', got)) return *s = BIREF_ERR_INVALID, "not a text file (it holds a NUL byte)";
        *n += got;
        if (got == 0) return ferror(f) ? (*s = BIREF_ERR_IO, strerror(errno)) : NULL;
    }
}

biref_status biref_read_text(const char *path, size_t max_bytes, char **text, size_t *len, char *msg,
                        size_t msg_len)
{
    *text = NULL;
    *len = 0;
    char limit[32];
    size_text(max_bytes, limit, sizeof limit);
    FILE *f = fopen(path, "rb");
    if (!f) {
        if (msg && msg_len) snprintf(msg, msg_len, "cannot read: %s", strerror(errno));
        return BIREF_ERR_IO;
    }
    struct stat st;
    size_t cap = 1 << 16;
    if (fstat(fileno(f), &st) == 0) {
        const char *why = S_ISDIR(st.st_mode) ? "is a directory, not a file"
                          : S_ISREG(st.st_mode) && (unsigned long long)st.st_size > max_bytes ? "too large"
                                                                                             : NULL;
        if (why) {
            fclose(f);
            if (msg && msg_len && !strcmp(why, "too large"))
                snprintf(msg, msg_len, "file too large (%lld bytes; the limit is %s)", (long long)st.st_size, limit);
            else if (msg && msg_len)
                snprintf(msg, msg_len, "%s", why);
            return BIREF_ERR_INVALID;
        }
        /* A regular file is read in one block of its size (and a byte more, to see its end). */
        if (S_ISREG(st.st_mode) && (size_t)st.st_size >= cap) cap = (size_t)st.st_size + 1;
        if (cap > max_bytes) cap = max_bytes;
    }
    size_t n = 0;
    char *buf = malloc(cap + 1);
    biref_status s = BIREF_OK;
    const char *why = buf ? read_all(f, max_bytes, &buf, &cap, &n, &s) : (s = BIREF_ERR_NOMEM, "out of memory");
    fclose(f);
    if (why) {
        free(buf);
        if (msg && msg_len && !strcmp(why, "too large"))
            snprintf(msg, msg_len, "file too large (over %s)", limit);
        else if (msg && msg_len)
            snprintf(msg, msg_len, "cannot read: %s", why);
        return s;
    }
    buf[n] = '\0';
    *text = buf;
    *len = n;
    return BIREF_OK;
}
