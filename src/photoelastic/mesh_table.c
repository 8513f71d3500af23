/* Node tables from finite-element exports: a header naming the columns, one row per node, stated
 * units; coincident nodes merged (docs/PHOTOELASTICITY.md, "Stress from FEA nodes"). The nodes are
 * then triangulated (mesh_delaunay.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "optics/validate.h"
#include "photoelastic/mesh_internal.h"
#include "photoelastic/textfile.h"

#define MAX_FIELDS 256

enum { ROLE_X, ROLE_Y, ROLE_SXX, ROLE_SYY, ROLE_TXY, NROLE };
static const char *const ROLE[NROLE] = {"x", "y", "sxx", "syy", "txy"};

void biref_pe_node_format_default(biref_pe_node_format *f)
{
    f->x = "x";
    f->y = "y";
    f->sxx = "sxx";
    f->syy = "syy";
    f->txy = "txy";
    f->length_m = 1e-3;
    f->stress_pa = 1e6;
}

static int name_is(const char *b, const char *e, const char *name)
{
    if (e - b >= 2 && (*b == '"' || *b == '\'') && e[-1] == *b) {
        b++;
        e--;
    }
    return (size_t)(e - b) == strlen(name) && !strncasecmp(b, name, (size_t)(e - b));
}

/* "syy (S22)" or "syy". */
static void column_label(char *out, size_t n, int role, const char *name)
{
    if (!strcasecmp(name, ROLE[role]))
        snprintf(out, n, "%s", name);
    else
        snprintf(out, n, "%s (%s)", name, ROLE[role]);
}

/* The header line [b, e): the column of each role (col), its label for messages, the field
 * delimiter (',' or ';' if present, else blanks) and the column count. */
static biref_status map_header(const char *b, const char *e, long line, const char *const names[NROLE], int col[NROLE],
                               char label[NROLE][80], char *delim, int *ncol, char *msg, size_t msg_len)
{
    *delim = memchr(b, ',', (size_t)(e - b)) ? ',' : memchr(b, ';', (size_t)(e - b)) ? ';' : ' ';
    const char *hb[MAX_FIELDS], *he[MAX_FIELDS];
    *ncol = pe_split_fields(b, e, *delim, hb, he, MAX_FIELDS);
    if (*ncol > MAX_FIELDS) return biref_fail(msg, msg_len, "line %ld: more than %d columns", line, MAX_FIELDS);
    for (int r = 0; r < NROLE; r++) {
        col[r] = -1;
        column_label(label[r], 80, r, names[r]);
        for (int i = 0; i < *ncol; i++)
            if (name_is(hb[i], he[i], names[r])) {
                if (col[r] >= 0)
                    return biref_fail(msg, msg_len, "line %ld: column %s appears twice in the header", line, names[r]);
                col[r] = i;
            }
        if (col[r] < 0) {
            if (pe_looks_numeric(hb[0], he[0]))
                return biref_fail(msg, msg_len,
                                  "line %ld: expected a header naming the columns (%s, %s, %s, %s, %s) before the data",
                                  line, names[0], names[1], names[2], names[3], names[4]);
            int w = (int)(e - b) > 80 ? 80 : (int)(e - b);
            return biref_fail(msg, msg_len, "line %ld: the header has no column '%s' for %s (header: %.*s%s; map columns "
                              "with --columns)", line, names[r], ROLE[r], w, b, (int)(e - b) > 80 ? "..." : "");
        }
    }
    return BIREF_OK;
}

/* One node row: position and stress in the file's units scaled to metres and pascals, each within
 * PE_MAX_COORD_M / PE_MAX_STRESS_PA. */
static biref_status parse_node(const char *const db[], const char *const de[], const int col[NROLE],
                               const char label[NROLE][80], const biref_pe_node_format *fmt, long line, pe_node_row *nr,
                               char *msg, size_t msg_len)
{
    double v[NROLE];
    for (int r = 0; r < NROLE; r++) {
        char show[48];
        int why = pe_parse_number(db[col[r]], de[col[r]], &v[r], show);
        const double scale = r < 2 ? fmt->length_m : fmt->stress_pa, lim = r < 2 ? PE_MAX_COORD_M : PE_MAX_STRESS_PA;
        if (why == PE_NUM_EMPTY) return biref_fail(msg, msg_len, "line %ld, column %s: empty field", line, label[r]);
        if (why == PE_NUM_NAN) return biref_fail(msg, msg_len, "line %ld, column %s: not a number: '%s'", line, label[r], show);
        if (why == PE_NUM_INF)
            return biref_fail(msg, msg_len, "line %ld, column %s: not a finite number: '%s'", line, label[r], show);
        if (why == PE_NUM_RANGE || !(fabs(v[r] * scale) <= lim))
            return biref_fail(msg, msg_len, "line %ld, column %s: %s is out of range (|%s| at most %g %s)", line,
                              label[r], show, r < 2 ? "coordinate" : "stress", r < 2 ? lim : lim,
                              r < 2 ? "m" : "Pa");
        v[r] *= scale;
    }
    nr->x = v[ROLE_X];
    nr->y = v[ROLE_Y];
    nr->s[0] = v[ROLE_SXX];
    nr->s[1] = v[ROLE_SYY];
    nr->s[2] = v[ROLE_TXY];
    nr->line = line;
    return BIREF_OK;
}

/* Counts the data rows after the header so that a table beyond the node limit is refused before
 * anything is allocated for it. */
static biref_status count_rows(pe_line_reader rd, size_t *n, char *msg, size_t msg_len)
{
    const char *b, *e;
    *n = 0;
    while (pe_next_line(&rd, &b, &e, NULL))
        if (++*n > (size_t)PE_MAX_TABLE_NODES)
            return biref_fail(msg, msg_len, "line %ld: more than %ld node rows (the limit of a node table, which is "
                              "triangulated; a solver's own elements allow more: --fea)", rd.line, PE_MAX_TABLE_NODES);
    return BIREF_OK;
}

/* The data rows after the header (ncol fields each); at least 3. */
static biref_status read_nodes(pe_line_reader *rd, char delim, int ncol, const int col[NROLE],
                               const char label[NROLE][80], const biref_pe_node_format *fmt, pe_node_row **rows_out,
                               size_t *n_out, char *msg, size_t msg_len)
{
    size_t cap = 0, n = 0;
    biref_status st = count_rows(*rd, &cap, msg, msg_len);
    if (st != BIREF_OK) return st;
    pe_node_row *rows = malloc((cap ? cap : 1) * sizeof *rows);
    if (!rows) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory for %zu node rows", cap);
    const char *b, *e, *db[MAX_FIELDS], *de[MAX_FIELDS];
    while (st == BIREF_OK && n < cap && pe_next_line(rd, &b, &e, NULL)) {
        int nf = pe_split_fields(b, e, delim, db, de, MAX_FIELDS);
        if (nf != ncol) {
            if (rd->last && nf < ncol)
                st = biref_fail(msg, msg_len, "line %ld: truncated row (%d of %d fields, and the file ends there)",
                                rd->line, nf, ncol);
            else
                st = biref_fail(msg, msg_len, "line %ld: expected %d fields as in the header, got %d", rd->line, ncol, nf);
            break;
        }
        st = parse_node(db, de, col, label, fmt, rd->line, &rows[n], msg, msg_len);
        if (st == BIREF_OK) n++;
    }
    if (st == BIREF_OK && n < 3)
        st = biref_fail(msg, msg_len, "line %ld: the file ends after %zu data row%s; a triangulation needs at least 3 "
                        "nodes", rd->line, n, n == 1 ? "" : "s");
    if (st != BIREF_OK) {
        free(rows);
        return st;
    }
    *rows_out = rows;
    *n_out = n;
    return BIREF_OK;
}

biref_status biref_pe_mesh_parse(const char *text, size_t len, const biref_pe_node_format *fmt, biref_pe_mesh **out,
                                 char *msg, size_t msg_len)
{
    if (!out) return biref_fail(msg, msg_len, "no output");
    *out = NULL;
    if (!text || !fmt) return biref_fail(msg, msg_len, "no text or format");
    if (!(isfinite(fmt->length_m) && fmt->length_m > 0 && isfinite(fmt->stress_pa) && fmt->stress_pa > 0))
        return biref_fail(msg, msg_len, "length and stress units must be positive");
    const char *names[NROLE] = {fmt->x, fmt->y, fmt->sxx, fmt->syy, fmt->txy};
    for (int r = 0; r < NROLE; r++)
        if (!names[r] || !*names[r]) return biref_fail(msg, msg_len, "no column name for %s", ROLE[r]);
    pe_line_reader rd = {text, text + len, 0, 0};
    if (len >= 3 && !memcmp(text, "\xEF\xBB\xBF", 3)) rd.p += 3;
    long nul = pe_nul_line(text, len);
    if (nul) return biref_fail(msg, msg_len, "line %ld: contains a NUL byte (not a text file?)", nul);
    const char *b, *e;
    if (!pe_next_line(&rd, &b, &e, NULL))
        return biref_fail(msg, msg_len, "empty file: expected a header naming the columns %s, %s, %s, %s, %s", names[0],
                          names[1], names[2], names[3], names[4]);
    int col[NROLE], ncol;
    char label[NROLE][80], delim;
    biref_status st = map_header(b, e, rd.line, names, col, label, &delim, &ncol, msg, msg_len);
    if (st != BIREF_OK) return st;
    pe_node_row *rows = NULL;
    size_t n = 0;
    st = read_nodes(&rd, delim, ncol, col, (const char(*)[80])label, fmt, &rows, &n, msg, msg_len);
    if (st != BIREF_OK) return st;
    biref_pe_mesh *m = calloc(1, sizeof *m);
    st = m ? pe_mesh_nodes_from_rows(m, rows, n, msg, msg_len)
           : biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    free(rows);
    if (st == BIREF_OK) st = pe_mesh_triangulate(m, msg, msg_len);
    if (st != BIREF_OK) {
        biref_pe_mesh_destroy(m);
        return st;
    }
    *out = m;
    return BIREF_OK;
}

biref_status biref_pe_mesh_load(const char *path, const biref_pe_node_format *fmt, biref_pe_mesh **out, char *msg,
                                size_t msg_len)
{
    if (out) *out = NULL;
    char *text;
    size_t len;
    biref_status st = biref_pe_read_text(path, PE_MAX_FILE_BYTES, &text, &len, msg, msg_len);
    if (st != BIREF_OK) return st;
    st = biref_pe_mesh_parse(text, len, fmt, out, msg, msg_len);
    free(text);
    return st;
}
