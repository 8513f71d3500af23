/* Line, field and number scanning shared by the photoelastic input parsers (node tables,
 * boundaries, CalculiX result files); see textfile.h. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "photoelastic/textfile.h"

int pe_next_raw_line(pe_line_reader *r, const char **b, const char **e)
{
    if (r->p >= r->end) return 0;
    const char *nl = memchr(r->p, '\n', (size_t)(r->end - r->p));
    const char *lb = r->p, *le = nl ? nl : r->end;
    r->p = nl ? nl + 1 : r->end;
    r->last = nl == NULL;
    r->line++;
    if (le > lb && le[-1] == '\r') le--;
    *b = lb;
    *e = le;
    return 1;
}

int pe_next_line(pe_line_reader *r, const char **b, const char **e, int *blank)
{
    const char *lb, *le;
    while (pe_next_raw_line(r, &lb, &le)) {
        while (lb < le && isspace((unsigned char)*lb)) lb++;
        while (le > lb && isspace((unsigned char)le[-1])) le--;
        if (lb == le) {
            if (blank) (*blank)++;
            continue;
        }
        if (*lb == '#') continue;
        *b = lb;
        *e = le;
        return 1;
    }
    return 0;
}

int pe_split_fields(const char *b, const char *e, char delim, const char *fb[], const char *fe[], int cap)
{
    int n = 0;
    const char *p = b;
    for (;;) {
        const char *s = p;
        if (delim == ' ') {
            while (p < e && *p != ' ' && *p != '\t') p++;
        } else {
            while (p < e && *p != delim) p++;
        }
        const char *tb = s, *te = p;
        while (tb < te && isspace((unsigned char)*tb)) tb++;
        while (te > tb && isspace((unsigned char)te[-1])) te--;
        if (n < cap) {
            fb[n] = tb;
            fe[n] = te;
        }
        n++;
        if (p >= e) break;
        p++;
        if (delim == ' ')
            while (p < e && (*p == ' ' || *p == '\t')) p++;
    }
    return n;
}

int pe_parse_number(const char *b, const char *e, double *out, char show[48])
{
    const size_t n = (size_t)(e - b);
    if (n > 40) {
        memcpy(show, b, 37);
        strcpy(show + 37, "...");
    } else {
        memcpy(show, b, n);
        show[n] = '\0';
    }
    if (n == 0) return PE_NUM_EMPTY;
    /* Long fields (a number written with thousands of digits is still a number) get a heap copy. */
    char stack[64], *buf = n < sizeof stack ? stack : malloc(n + 1);
    if (!buf) return PE_NUM_NAN;
    memcpy(buf, b, n);
    buf[n] = '\0';
    char *endp = NULL;
    errno = 0;
    double v = strtod(buf, &endp);
    int why = PE_NUM_OK;
    if (endp == buf || *endp != '\0')
        why = PE_NUM_NAN;
    else if (!isfinite(v)) /* "inf", "nan", or beyond the double range (ERANGE) */
        why = errno == ERANGE ? PE_NUM_RANGE : PE_NUM_INF;
    if (buf != stack) free(buf);
    if (why == PE_NUM_OK) *out = v;
    return why;
}

int pe_looks_numeric(const char *b, const char *e)
{
    char show[48];
    double v;
    return e > b && pe_parse_number(b, e, &v, show) != PE_NUM_NAN;
}

long pe_nul_line(const char *text, size_t len)
{
    const char *z = memchr(text, '\0', len);
    if (!z) return 0;
    long ln = 1;
    for (const char *q = text; q < z; q++) ln += *q == '\n';
    return ln;
}
