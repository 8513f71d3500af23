/* Whole-file reading for the library's input parsers (stack files, node tables, boundaries).
 * Not part of the public API. */
#ifndef BIREF_IO_TEXTFILE_H
#define BIREF_IO_TEXTFILE_H

#include <stddef.h>

#include "biref/common.h"

/* Reads path into a malloc'ed buffer (*len bytes, NUL-terminated). At most max_bytes.
 * BIREF_ERR_IO / BIREF_ERR_NOMEM with "cannot read: reason" in msg. */
biref_status biref_read_text(const char *path, size_t max_bytes, char **text, size_t *len, char *msg, size_t msg_len);

#endif
