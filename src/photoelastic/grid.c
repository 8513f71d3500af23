/* A user-supplied plane-stress field on a regular grid: CSV parsing with line-numbered errors
 * and bilinear interpolation (docs/PHOTOELASTICITY.md, "Stress from a file"). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "biref/photoelastic.h"
#include "optics/validate.h"
#include "photoelastic/textfile.h"

struct biref_pe_grid {
    int nx, ny;
    double x0, dx, y0, dy; /* metres */
    double *v;             /* [ny][nx][3]: sxx, syy, txy in Pa */
};

enum { COL_X, COL_Y, COL_SXX, COL_SYY, COL_TXY, NCOL };
static const char *const COL_NAMES[NCOL] = {"x_mm", "y_mm", "sxx_MPa", "syy_MPa", "txy_MPa"};
#define HEADER_TEXT "x_mm,y_mm,sxx_MPa,syy_MPa,txy_MPa"
#define GRID_MAX_VALUE 1e6 /* mm and MPa */
/* Refuse absurd files before allocating for them. */
#define MAX_ROWS 50000000L
#define MAX_FILE_BYTES (1L << 31)

typedef struct {
    double v[NCOL];
    long line;
} row;

/* Trims spaces and tabs in place: [*b, *e). */
static void trim(const char **b, const char **e)
{
    while (*b < *e && (**b == ' ' || **b == '\t')) (*b)++;
    while (*e > *b && ((*e)[-1] == ' ' || (*e)[-1] == '\t')) (*e)--;
}

/* Splits [b, e) at commas into at most cap fields; returns the field count (may exceed cap:
 * counting continues so that "too many fields" can be reported). */
static int split(const char *b, const char *e, const char *fb[], const char *fe[], int cap)
{
    int n = 0;
    const char *s = b;
    for (const char *p = b;; p++) {
        if (p == e || *p == ',') {
            if (n < cap) {
                fb[n] = s;
                fe[n] = p;
                trim(&fb[n], &fe[n]);
            }
            n++;
            if (p == e) break;
            s = p + 1;
        }
    }
    return n;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Distinct values of v (n > 0, sorted copy in tmp) merged within tol; returns their count and
 * the smallest gap between consecutive distinct values. */
static int distinct(const double *v, long n, double *tmp, double tol, double *min_gap)
{
    memcpy(tmp, v, (size_t)n * sizeof *tmp);
    qsort(tmp, (size_t)n, sizeof *tmp, cmp_double);
    int count = 1;
    double last = tmp[0];
    *min_gap = INFINITY;
    for (long i = 1; i < n; i++)
        if (tmp[i] - last > tol) {
            if (tmp[i] - last < *min_gap) *min_gap = tmp[i] - last;
            last = tmp[i];
            if (count < 0x7fffffff) count++;
        }
    return count;
}

/* Checks one axis of the grid: every value on lo + k * step. Reports the first offending row. */
static biref_status axis_fit(const row *rows, long n, int col, double lo, double hi, double *tmp, int *count,
                             double *step, char *msg, size_t msg_len)
{
    const char *name = COL_NAMES[col];
    for (long i = 0; i < n; i++) tmp[i] = rows[i].v[col];
    double span = hi - lo;
    /* Values within 1e-6 of the extent are one node: CSV writers round, and the same node may
     * be printed slightly differently in different rows. */
    double tol = 1e-6 * fmax(span, 1e-9 * fmax(fabs(lo), fabs(hi)));
    double *work = tmp + n, gap;
    int distinct_n = distinct(tmp, n, work, tol, &gap);
    if (distinct_n < 2)
        return biref_fail(msg, msg_len, "all rows have %s = %g: a grid needs at least 2 distinct values of %s and of %s",
                     name, lo, COL_NAMES[COL_X], COL_NAMES[COL_Y]);
    /* The node spacing is the smallest gap; every value must sit on lo + k * gap. */
    double k_max = span / gap;
    if (k_max + 1.0 > (double)n) {
        /* More lattice nodes than rows: the grid cannot be complete. Blame the value that made
         * the smallest gap (typically a stray value next to a regular one). */
        double prev = work[0], blame = work[0], before = work[0], g_min = INFINITY;
        for (long i = 1; i < n; i++)
            if (work[i] - prev > tol) {
                if (work[i] - prev < g_min) {
                    g_min = work[i] - prev;
                    blame = work[i];
                    before = prev;
                }
                prev = work[i];
            }
        for (long i = 0; i < n; i++)
            if (fabs(rows[i].v[col] - blame) <= tol)
                return biref_fail(msg, msg_len,
                             "line %ld: %s = %g is not on a regular grid (only %g from the neighbouring value %g)",
                             rows[i].line, name, rows[i].v[col], g_min, before);
    }
    long nodes = lround(k_max) + 1;
    double d = span / (double)(nodes - 1);
    for (long i = 0; i < n; i++) {
        double k = (rows[i].v[col] - lo) / d;
        if (fabs(k - nearbyint(k)) > 1e-3) /* 0.1 % of the spacing: rounding, not a stray node */
            return biref_fail(msg, msg_len,
                         "line %ld: %s = %g is not on a regular grid (the values of %s run from %g to %g in steps "
                         "of %g)",
                         rows[i].line, name, rows[i].v[col], name, lo, hi, gap);
    }
    if (nodes != distinct_n) {
        /* Every value is on the lattice but some lattice values never occur: a wider gap. Blame
         * the first row with the value after the first such gap. */
        double prev = work[0];
        for (long j = 1; j < n; j++) {
            if (work[j] - prev <= tol) continue;
            if (work[j] - prev > 1.5 * d)
                for (long i = 0; i < n; i++)
                    if (fabs(rows[i].v[col] - work[j]) <= tol)
                        return biref_fail(msg, msg_len,
                                     "line %ld: %s = %g follows %g with a gap of %g, but other values are %g apart: "
                                     "not a regular grid",
                                     rows[i].line, name, rows[i].v[col], prev, work[j] - prev, d);
            prev = work[j];
        }
        return biref_fail(msg, msg_len, "%s: not a regular grid", name); /* not reached */
    }
    *count = (int)nodes;
    *step = d;
    return BIREF_OK;
}

/* The header line: which file column holds each named column. */
static biref_status parse_header(const char *fb[], const char *fe[], int nf, long line, int col_of[NCOL], char *msg,
                                 size_t msg_len)
{
    int seen[NCOL] = {0};
    if (nf > NCOL)
        return biref_fail(msg, msg_len, "line %ld: header has %d columns; expected the 5 columns " HEADER_TEXT, line, nf);
    for (int i = 0; i < nf; i++) {
        int which = -1;
        /* Accept quoted column names ("x_mm"), as some spreadsheets write them. */
        if (fe[i] - fb[i] >= 2 && *fb[i] == '"' && fe[i][-1] == '"') {
            fb[i]++;
            fe[i]--;
        }
        for (int c = 0; c < NCOL; c++)
            if ((size_t)(fe[i] - fb[i]) == strlen(COL_NAMES[c]) && !memcmp(fb[i], COL_NAMES[c], strlen(COL_NAMES[c])))
                which = c;
        if (which < 0) {
            char *endp = NULL;
            (void)strtod(fb[i], &endp);
            if (i == 0 && endp != fb[i])
                return biref_fail(msg, msg_len, "line %ld: expected the header " HEADER_TEXT " before the data", line);
            return biref_fail(msg, msg_len, "line %ld: unknown column '%.*s' in the header (expected " HEADER_TEXT ")",
                              line, (int)(fe[i] - fb[i]) > 40 ? 40 : (int)(fe[i] - fb[i]), fb[i]);
        }
        if (seen[which])
            return biref_fail(msg, msg_len, "line %ld: column %s appears twice in the header", line, COL_NAMES[which]);
        seen[which] = 1;
        col_of[which] = i;
    }
    for (int c = 0; c < NCOL; c++)
        if (!seen[c])
            return biref_fail(msg, msg_len, "line %ld: the header lacks column %s (expected " HEADER_TEXT ")", line,
                              COL_NAMES[c]);
    return BIREF_OK;
}

/* One data row's five numbers, each finite and within GRID_MAX_VALUE. */
static biref_status parse_row(const char *const fb[], const char *const fe[], const int col_of[NCOL], long line, row *r,
                              char *msg, size_t msg_len)
{
    r->line = line;
    for (int c = 0; c < NCOL; c++) {
        const char *s = fb[col_of[c]], *e = fe[col_of[c]];
        int w = (int)(e - s) > 40 ? 40 : (int)(e - s);
        if (s == e) return biref_fail(msg, msg_len, "line %ld, column %s: empty field", line, COL_NAMES[c]);
        char buf[64];
        if ((size_t)(e - s) >= sizeof buf)
            return biref_fail(msg, msg_len, "line %ld, column %s: a field of %ld characters is too long for a number: '%.*s...'",
                              line, COL_NAMES[c], (long)(e - s), w, s);
        memcpy(buf, s, (size_t)(e - s));
        buf[e - s] = '\0';
        char *endp = NULL;
        errno = 0;
        double v = strtod(buf, &endp);
        if (endp == buf || *endp != '\0')
            return biref_fail(msg, msg_len, "line %ld, column %s: not a number: '%s'", line, COL_NAMES[c], buf);
        if (!isfinite(v) || errno == ERANGE)
            return biref_fail(msg, msg_len, "line %ld, column %s: not a finite number: '%s'", line, COL_NAMES[c], buf);
        /* A kilometre and a terapascal are far beyond any plate in a polariscope; within
         * them, spans, spacings and fringe orders stay finite. */
        if (fabs(v) > GRID_MAX_VALUE)
            return biref_fail(msg, msg_len, "line %ld, column %s: %s is out of range (at most %g in magnitude)", line,
                              COL_NAMES[c], buf, GRID_MAX_VALUE);
        r->v[c] = v;
    }
    return BIREF_OK;
}

/* Room for one more row (doubling), refusing files of more than MAX_ROWS rows. */
static biref_status reserve_row(row **rows, long *cap, long n, long line, char *msg, size_t msg_len)
{
    if (n < *cap) return BIREF_OK;
    if (n >= MAX_ROWS) return biref_fail(msg, msg_len, "line %ld: more than %ld rows", line, MAX_ROWS);
    long ncap = *cap ? 2 * *cap : 1024;
    row *nr = realloc(*rows, (size_t)ncap * sizeof **rows);
    if (!nr) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    *rows = nr;
    *cap = ncap;
    return BIREF_OK;
}

/* Reads the header and the data rows (comments and blank lines skipped) into *rows_out;
 * at least 4 rows. */
static biref_status read_rows(const char *text, size_t len, row **rows_out, long *n_out, char *msg, size_t msg_len)
{
    int col_of[NCOL]; /* position in the file of each named column */
    int have_header = 0;
    long line = 0, cap = 0, n = 0;
    row *rows = NULL;
    biref_status st = BIREF_OK;
    const char *p = text, *end = text + len;
    /* Spreadsheets often start a UTF-8 CSV with a byte-order mark. */
    if (len >= 3 && !memcmp(text, "\xEF\xBB\xBF", 3)) p += 3;
    while (p < end && st == BIREF_OK) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        int complete = nl != NULL; /* a line without '\n' ends the file */
        const char *le = nl ? nl : end;
        const char *b = p;
        p = nl ? nl + 1 : end;
        line++;
        if (le > b && le[-1] == '\r') le--;
        const char *tb = b, *te = le;
        trim(&tb, &te);
        if (tb == te || *tb == '#') continue;
        if (memchr(b, '\0', (size_t)(le - b))) {
            st = biref_fail(msg, msg_len, "line %ld: contains a NUL byte (not a text file?)", line);
            break;
        }
        const char *fb[NCOL], *fe[NCOL];
        int nf = split(b, le, fb, fe, NCOL);
        if (!have_header) {
            st = parse_header(fb, fe, nf, line, col_of, msg, msg_len);
            have_header = 1;
        } else if (nf != NCOL) {
            if (!complete && nf < NCOL)
                st = biref_fail(msg, msg_len, "line %ld: truncated row (%d of %d fields, and the file ends there)", line,
                                nf, NCOL);
            else
                st = biref_fail(msg, msg_len, "line %ld: expected %d comma-separated fields, got %d", line, NCOL, nf);
        } else {
            st = reserve_row(&rows, &cap, n, line, msg, msg_len);
            if (st == BIREF_OK) st = parse_row(fb, fe, col_of, line, &rows[n++], msg, msg_len);
        }
    }
    if (st == BIREF_OK && !have_header)
        st = biref_fail(msg, msg_len, "empty file: expected the header " HEADER_TEXT " and at least 4 rows");
    if (st == BIREF_OK && n < 4)
        st = biref_fail(msg, msg_len, "line %ld: the file ends after %ld data row%s; a grid needs at least 2 x 2 nodes",
                        line, n, n == 1 ? "" : "s");
    if (st != BIREF_OK) {
        free(rows);
        return st;
    }
    *rows_out = rows;
    *n_out = n;
    return BIREF_OK;
}

/* Puts every row's stress (MPa -> Pa) at its node of the lattice lo + (ix dxm, iy dym); every
 * node exactly once. */
static biref_status place_nodes(biref_pe_grid *g, const row *rows, long n, const double lo[2], double dxm, double dym,
                                char *msg, size_t msg_len)
{
    if ((long)g->nx * g->ny > MAX_ROWS)
        return biref_fail(msg, msg_len, "the grid would have %ld nodes (more than %ld)", (long)g->nx * g->ny, MAX_ROWS);
    /* Every node once: fewer rows than nodes is irregular. Far fewer is refused before the lattice
     * is allocated (a few rows whose x and y values fit a fine lattice would otherwise ask for
     * gigabytes); a few missing nodes are named below, at a cost bounded by the rows'. */
    if ((long)g->nx * g->ny > 2 * n + 1024)
        return biref_fail(msg, msg_len, "irregular grid: %ld rows, but their x and y values span %d x %d nodes", n,
                          g->nx, g->ny);
    g->v = malloc((size_t)g->nx * g->ny * 3 * sizeof *g->v);
    long *owner = malloc((size_t)g->nx * g->ny * sizeof *owner);
    if (!g->v || !owner) {
        free(owner);
        return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    }
    biref_status st = BIREF_OK;
    for (long k = 0; k < (long)g->nx * g->ny; k++) owner[k] = 0;
    for (long i = 0; i < n && st == BIREF_OK; i++) {
        long ix = lround((rows[i].v[COL_X] - lo[0]) / dxm), iy = lround((rows[i].v[COL_Y] - lo[1]) / dym);
        long k = iy * g->nx + ix;
        if (owner[k]) {
            st = biref_fail(msg, msg_len, "line %ld: node x_mm = %g, y_mm = %g repeats line %ld", rows[i].line,
                            rows[i].v[COL_X], rows[i].v[COL_Y], owner[k]);
            break;
        }
        owner[k] = rows[i].line;
        g->v[3 * k + 0] = rows[i].v[COL_SXX] * 1e6;
        g->v[3 * k + 1] = rows[i].v[COL_SYY] * 1e6;
        g->v[3 * k + 2] = rows[i].v[COL_TXY] * 1e6;
    }
    for (long k = 0; k < (long)g->nx * g->ny && st == BIREF_OK; k++)
        if (!owner[k])
            st = biref_fail(msg, msg_len, "irregular grid: no row for the node x_mm = %g, y_mm = %g (%d x %d nodes)",
                            lo[0] + (double)(k % g->nx) * dxm, lo[1] + (double)(k / g->nx) * dym, g->nx, g->ny);
    free(owner);
    return st;
}

/* Regularity: the x values and the y values each on an evenly spaced lattice, and every
 * (x, y) node present exactly once. Fills g (sizes in metres). */
static biref_status build_grid(biref_pe_grid *g, const row *rows, long n, char *msg, size_t msg_len)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (long i = 0; i < n; i++)
        for (int c = 0; c < 2; c++) {
            lo[c] = fmin(lo[c], rows[i].v[c]);
            hi[c] = fmax(hi[c], rows[i].v[c]);
        }
    double *tmp = malloc((size_t)n * 2 * sizeof *tmp);
    if (!tmp) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    double dxm = 0, dym = 0;
    biref_status st = axis_fit(rows, n, COL_X, lo[0], hi[0], tmp, &g->nx, &dxm, msg, msg_len);
    if (st == BIREF_OK) st = axis_fit(rows, n, COL_Y, lo[1], hi[1], tmp, &g->ny, &dym, msg, msg_len);
    free(tmp);
    if (st == BIREF_OK) st = place_nodes(g, rows, n, lo, dxm, dym, msg, msg_len);
    if (st != BIREF_OK) return st;
    /* mm -> m. */
    g->x0 = lo[0] * 1e-3;
    g->dx = dxm * 1e-3;
    g->y0 = lo[1] * 1e-3;
    g->dy = dym * 1e-3;
    return BIREF_OK;
}

biref_status biref_pe_grid_parse(const char *text, size_t len, biref_pe_grid **out, char *msg, size_t msg_len)
{
    if (!out) return biref_fail(msg, msg_len, "no output");
    *out = NULL;
    if (!text) return biref_fail(msg, msg_len, "no text");
    row *rows = NULL;
    long n = 0;
    biref_status st = read_rows(text, len, &rows, &n, msg, msg_len);
    if (st != BIREF_OK) return st;
    biref_pe_grid *g = calloc(1, sizeof *g);
    st = g ? build_grid(g, rows, n, msg, msg_len) : biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    free(rows);
    if (st != BIREF_OK) {
        biref_pe_grid_destroy(g);
        return st;
    }
    *out = g;
    return BIREF_OK;
}

biref_status biref_pe_grid_load(const char *path, biref_pe_grid **out, char *msg, size_t msg_len)
{
    if (out) *out = NULL;
    char *buf;
    size_t len;
    biref_status st = biref_pe_read_text(path, (size_t)MAX_FILE_BYTES, &buf, &len, msg, msg_len);
    if (st != BIREF_OK) return st;
    st = biref_pe_grid_parse(buf, len, out, msg, msg_len);
    free(buf);
    return st;
}

void biref_pe_grid_destroy(biref_pe_grid *g)
{
    if (!g) return;
    free(g->v);
    free(g);
}

void biref_pe_grid_bounds(const biref_pe_grid *g, double b[4])
{
    b[0] = g->x0;
    b[1] = g->x0 + (g->nx - 1) * g->dx;
    b[2] = g->y0;
    b[3] = g->y0 + (g->ny - 1) * g->dy;
}

void biref_pe_grid_size(const biref_pe_grid *g, int *nx, int *ny)
{
    *nx = g->nx;
    *ny = g->ny;
}

int biref_pe_grid_stress(const biref_pe_grid *g, double x, double y, biref_pe_stress *out)
{
    double fx = (x - g->x0) / g->dx, fy = (y - g->y0) / g->dy;
    /* A sliver of tolerance keeps the frame's own edges inside. */
    const double eps = 1e-9;
    if (!(fx >= -eps && fx <= g->nx - 1 + eps && fy >= -eps && fy <= g->ny - 1 + eps)) return 0;
    int i = (int)floor(fx), j = (int)floor(fy);
    if (i < 0) i = 0;
    if (j < 0) j = 0;
    if (i > g->nx - 2) i = g->nx - 2;
    if (j > g->ny - 2) j = g->ny - 2;
    double t = fx - i, u = fy - j;
    const double *a = g->v + 3 * ((size_t)j * g->nx + i), *b = a + 3, *c = a + 3 * (size_t)g->nx, *d = c + 3;
    double w00 = (1 - t) * (1 - u), w10 = t * (1 - u), w01 = (1 - t) * u, w11 = t * u;
    out->sxx = w00 * a[0] + w10 * b[0] + w01 * c[0] + w11 * d[0];
    out->syy = w00 * a[1] + w10 * b[1] + w01 * c[1] + w11 * d[1];
    out->txy = w00 * a[2] + w10 * b[2] + w01 * c[2] + w11 * d[2];
    return 1;
}
