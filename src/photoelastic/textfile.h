/* Whole-file reading for the photoelastic input parsers (node tables, boundaries). */
#ifndef BIREF_PHOTOELASTIC_TEXTFILE_H
#define BIREF_PHOTOELASTIC_TEXTFILE_H

#include <stddef.h>

#include "biref/common.h"

/* Reads path into a malloc'ed buffer (*len bytes, NUL-terminated), at most max_bytes: see
 * biref_text_file_read (io/text_file.h) for what is refused before reading. */
biref_status biref_pe_read_text(const char *path, size_t max_bytes, char **text, size_t *len, char *msg,
                                size_t msg_len);

#endif
