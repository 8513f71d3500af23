/* Whole-file reading for the photoelastic input parsers: the library's reader (io/textfile.h). */
#ifndef BIREF_PHOTOELASTIC_TEXTFILE_H
#define BIREF_PHOTOELASTIC_TEXTFILE_H

#include "io/textfile.h"

static inline biref_status biref_pe_read_text(const char *path, size_t max_bytes, char **text, size_t *len,
                                              char *msg, size_t msg_len)
{
    return biref_read_text(path, max_bytes, text, len, msg, msg_len);
}

#endif
