/* Whole text files read for the input parsers (scenes, stress grids, node tables, boundaries),
 * with a size limit applied before the memory is taken.
 *
 * Not part of the public API: compiled into the library. Re-entrant. */
#ifndef BIREF_IO_TEXT_FILE_H
#define BIREF_IO_TEXT_FILE_H

#include <stddef.h>

#include "biref/common.h"

/* Reads PATH into a malloc'ed, NUL-terminated buffer of *len bytes. Refused before reading on:
 * a directory; a regular file over max_bytes (its size is known first). While reading (pipes,
 * devices): more than max_bytes, or a NUL byte (not text, e.g. /dev/zero), within the first
 * block that shows it. BIREF_ERR_INVALID for those (bad input), BIREF_ERR_IO when the file
 * cannot be opened or read, BIREF_ERR_NOMEM; msg says which in one line. */
biref_status biref_text_file_read(const char *path, size_t max_bytes, char **text, size_t *len, char *msg,
                                  size_t msg_len);

#endif
