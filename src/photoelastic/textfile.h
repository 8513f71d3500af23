/* Whole-file reading for the photoelastic input parsers (the library's reader, io/textfile.h), and the
 * line/field/number scanning they share (text_scan.c: node tables, boundaries, CalculiX results). */
#ifndef BIREF_PHOTOELASTIC_TEXTFILE_H
#define BIREF_PHOTOELASTIC_TEXTFILE_H

#include "io/textfile.h"

static inline biref_status biref_pe_read_text(const char *path, size_t max_bytes, char **text, size_t *len,
                                              char *msg, size_t msg_len)
{
    return biref_read_text(path, max_bytes, text, len, msg, msg_len);
}

/* Lines of a text buffer, numbered from 1. */
typedef struct {
    const char *p, *end;
    long line;
    int last; /* the line just returned ended the file without '\n' */
} pe_line_reader;

/* Next non-blank line not starting with '#', trimmed, as [*b, *e); 0 at the end. Blank lines
 * passed over are counted in *blank when it is not NULL (the boundary's polygon separators). */
int pe_next_line(pe_line_reader *r, const char **b, const char **e, int *blank);
/* Next raw line (no trimming, no skipping, CR stripped); 0 at the end. */
int pe_next_raw_line(pe_line_reader *r, const char **b, const char **e);
/* Splits [b, e) at delim (' ' = runs of blanks and tabs), each field trimmed. Returns the field
 * count, which may exceed cap (only the first cap are stored). */
int pe_split_fields(const char *b, const char *e, char delim, const char *fb[], const char *fe[], int cap);

/* What pe_parse_number found. */
enum { PE_NUM_OK = 0, PE_NUM_EMPTY, PE_NUM_NAN /* not a number */, PE_NUM_INF /* not finite */,
       PE_NUM_RANGE /* beyond the double range */ };
/* Strict number: the whole field [b, e), any length. show receives the field for messages
 * (at most 40 characters, "..." appended when cut). */
int pe_parse_number(const char *b, const char *e, double *out, char show[48]);
/* 1 if the field reads as a number. */
int pe_looks_numeric(const char *b, const char *e);
/* The line number of the first NUL byte in text[0, len), 0 if there is none. */
long pe_nul_line(const char *text, size_t len);

#endif
