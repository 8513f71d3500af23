/* Whole-file reading for the photoelastic input parsers: the library's one text-file reader. */
#include "photoelastic/textfile.h"

#include "io/text_file.h"

biref_status biref_pe_read_text(const char *path, size_t max_bytes, char **text, size_t *len, char *msg,
                                size_t msg_len)
{
    return biref_text_file_read(path, max_bytes, text, len, msg, msg_len);
}
