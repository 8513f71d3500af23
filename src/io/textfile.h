/* Whole text files read for the library's input parsers (scenes, stack files, stress grids, node
 * tables, boundaries), with a size limit applied before the memory is taken.
 * Not part of the public API. Re-entrant. */
#ifndef BIREF_IO_TEXTFILE_H
#define BIREF_IO_TEXTFILE_H

#include <stddef.h>

#include "biref/common.h"

/* Reads path into a malloc'ed, NUL-terminated buffer of *len bytes. Refused before reading: a
 * directory; a regular file over max_bytes (its size is known first). While reading (pipes,
 * devices): more than max_bytes, or a NUL byte (not text, e.g. /dev/zero), at the first block that
 * shows it. BIREF_ERR_INVALID for those (bad input), BIREF_ERR_IO when the file cannot be opened
 * or read, BIREF_ERR_NOMEM; msg says which in one line. */
biref_status biref_read_text(const char *path, size_t max_bytes, char **text, size_t *len, char *msg, size_t msg_len);

#endif
