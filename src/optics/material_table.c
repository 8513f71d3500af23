/* Tabulated materials (material.h): samples (λ, n_o, n_e) interpolated by monotone cubic Hermite
 * splines with Fritsch–Carlson slopes (no overshoot between samples, a continuous dn/dλ for the
 * group index), continued linearly with the end slopes outside the table; and their CSV files. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "optics/material_internal.h"

enum { TABLE_MAX_ROWS = 100000, LINE_MAX_CHARS = 1024 };

static double sign(double v) { return (v > 0.0) - (v < 0.0); }

void biref_table_slopes(size_t n, const double *x, const double *y, double *m)
{
    if (n == 2) {
        m[0] = m[1] = (y[1] - y[0]) / (x[1] - x[0]);
        return;
    }
    for (size_t k = 1; k + 1 < n; k++) {
        const double h0 = x[k] - x[k - 1], h1 = x[k + 1] - x[k];
        const double d0 = (y[k] - y[k - 1]) / h0, d1 = (y[k + 1] - y[k]) / h1;
        if (d0 * d1 <= 0.0) {
            m[k] = 0.0; /* a local extremum of the data: flat, so the curve cannot overshoot */
            continue;
        }
        const double w1 = 2.0 * h1 + h0, w2 = h1 + 2.0 * h0; /* weighted harmonic mean */
        m[k] = (w1 + w2) / (w1 / d0 + w2 / d1);
    }
    /* Ends: the three-point slope, limited so that the end segment stays monotone. */
    for (int end = 0; end < 2; end++) {
        const size_t a = end ? n - 1 : 0, b = end ? n - 2 : 1, c = end ? n - 3 : 2;
        const double h0 = fabs(x[b] - x[a]), h1 = fabs(x[c] - x[b]);
        const double d0 = (y[b] - y[a]) / (x[b] - x[a]), d1 = (y[c] - y[b]) / (x[c] - x[b]);
        double s = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
        if (sign(s) != sign(d0))
            s = 0.0;
        else if (sign(d0) != sign(d1) && fabs(s) > 3.0 * fabs(d0))
            s = 3.0 * d0;
        m[a] = s;
    }
}

void biref_table_eval(const biref_material *m, int column, double l, double *n, double *dn_dl)
{
    const double *x = m->lambda_nm, *y = m->column[column].n, *s = m->column[column].slope;
    const size_t last = m->n_rows - 1;
    if (l <= x[0] || l >= x[last]) {
        const size_t k = l <= x[0] ? 0 : last;
        *dn_dl = s[k];
        *n = y[k] + s[k] * (l - x[k]);
        return;
    }
    size_t lo = 0, hi = last; /* x[lo] <= l < x[hi] */
    while (hi - lo > 1) {
        const size_t mid = lo + (hi - lo) / 2;
        if (x[mid] <= l)
            lo = mid;
        else
            hi = mid;
    }
    const double h = x[hi] - x[lo], t = (l - x[lo]) / h, t2 = t * t, t3 = t2 * t;
    *n = (2 * t3 - 3 * t2 + 1) * y[lo] + (t3 - 2 * t2 + t) * h * s[lo] + (-2 * t3 + 3 * t2) * y[hi] +
         (t3 - t2) * h * s[hi];
    *dn_dl = (6 * t2 - 6 * t) * (y[lo] - y[hi]) / h + (3 * t2 - 4 * t + 1) * s[lo] + (3 * t2 - 2 * t) * s[hi];
}

static biref_status check_rows(size_t n, const double *lambda_nm, const double *n_o, const double *n_e, char *msg,
                               size_t msg_len)
{
    if (n < 2 || n > TABLE_MAX_ROWS)
        return biref_fail(msg, msg_len, "a table needs 2 to %d rows (got %zu)", TABLE_MAX_ROWS, n);
    for (size_t i = 0; i < n; i++) {
        if (!(isfinite(lambda_nm[i]) && lambda_nm[i] > 0.0))
            return biref_fail(msg, msg_len, "row %zu: wavelength %g nm must be positive and finite", i + 1, lambda_nm[i]);
        if (i && !(lambda_nm[i] > lambda_nm[i - 1]))
            return biref_fail(msg, msg_len, "row %zu: wavelengths must increase (%g nm after %g nm)", i + 1,
                              lambda_nm[i], lambda_nm[i - 1]);
        for (int c = 0; c < (n_e ? 2 : 1); c++) {
            const double v = c ? n_e[i] : n_o[i];
            if (!(isfinite(v) && v > 1.0))
                return biref_fail(msg, msg_len, "row %zu: index %g must be finite and > 1", i + 1, v);
        }
    }
    return BIREF_OK;
}

biref_status biref_material_from_table(const char *name, size_t n, const double *lambda_nm, const double *n_o,
                                       const double *n_e, biref_material **out, char *msg, size_t msg_len)
{
    if (!out) return biref_fail(msg, msg_len, "no output");
    *out = NULL;
    if (!lambda_nm || !n_o) return biref_fail(msg, msg_len, "no table");
    biref_status s = check_rows(n, lambda_nm, n_o, n_e, msg, msg_len);
    if (s != BIREF_OK) return s;
    biref_material *m = calloc(1, sizeof *m);
    if (!m) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    snprintf(m->name_buf, sizeof m->name_buf, "%s", name && *name ? name : "table");
    m->name = m->name_buf;
    m->owned = 1;
    m->description = "tabulated indices (monotone cubic interpolation)";
    m->source = "user table";
    m->kind = MATERIAL_TABLE;
    m->isotropic = n_e == NULL;
    m->has_range = 1;
    m->range_nm[0] = lambda_nm[0];
    m->range_nm[1] = lambda_nm[n - 1];
    m->n_rows = n;
    m->lambda_nm = malloc(n * sizeof *m->lambda_nm);
    int ok = m->lambda_nm != NULL;
    for (int c = 0; c < (n_e ? 2 : 1); c++) {
        m->column[c].n = malloc(n * sizeof(double));
        m->column[c].slope = malloc(n * sizeof(double));
        ok = ok && m->column[c].n && m->column[c].slope;
    }
    if (!ok) {
        biref_material_destroy(m);
        return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    }
    memcpy(m->lambda_nm, lambda_nm, n * sizeof *lambda_nm);
    for (int c = 0; c < (n_e ? 2 : 1); c++) {
        memcpy(m->column[c].n, c ? n_e : n_o, n * sizeof(double));
        biref_table_slopes(n, m->lambda_nm, m->column[c].n, m->column[c].slope);
    }
    *out = m;
    return BIREF_OK;
}

/* Splits a CSV row into at most 3 numbers; returns the count, or -1 if a field is not a number. */
static int parse_row(char *line, double v[3])
{
    int k = 0;
    for (char *p = line;;) {
        char *end;
        errno = 0;
        const double x = strtod(p, &end);
        if (end == p || errno == ERANGE || !isfinite(x) || k == 3) return -1;
        v[k++] = x;
        while (*end == ' ' || *end == '\t' || *end == '\r' || *end == '\n') end++;
        if (!*end) return k;
        if (*end != ',') return -1;
        p = end + 1;
    }
}

typedef struct {
    size_t n, cap;
    double *col[3];
} rows;

static int rows_push(rows *r, const double v[3], int cols)
{
    if (r->n == r->cap) {
        const size_t cap = r->cap ? 2 * r->cap : 64;
        for (int c = 0; c < cols; c++) {
            double *p = realloc(r->col[c], cap * sizeof(double));
            if (!p) return -1;
            r->col[c] = p;
        }
        r->cap = cap;
    }
    for (int c = 0; c < cols; c++) r->col[c][r->n] = v[c];
    r->n++;
    return 0;
}

/* Reads the rows of an open CSV file. */
static biref_status read_rows(FILE *f, const char *path, rows *r, int *cols, char *msg, size_t msg_len)
{
    char line[LINE_MAX_CHARS];
    size_t lineno = 0;
    int header_allowed = 1;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        if (!strchr(line, '\n') && !feof(f))
            return biref_fail(msg, msg_len, "%s:%zu: line longer than %d characters", path, lineno, LINE_MAX_CHARS - 2);
        const char *p = line + strspn(line, " \t\r\n");
        if (!*p || *p == '#') continue;
        double v[3];
        const int k = parse_row(line, v);
        if (k < 0 && header_allowed) { /* a header row: "lambda_nm,n_o,n_e" */
            header_allowed = 0;
            continue;
        }
        header_allowed = 0;
        if (k < 2)
            return biref_fail(msg, msg_len, "%s:%zu: expected lambda_nm,n_o,n_e (or lambda_nm,n), comma-separated numbers",
                              path, lineno);
        if (*cols && k != *cols)
            return biref_fail(msg, msg_len, "%s:%zu: %d columns after rows of %d", path, lineno, k, *cols);
        *cols = k;
        if (r->n >= TABLE_MAX_ROWS) return biref_fail(msg, msg_len, "%s: more than %d rows", path, TABLE_MAX_ROWS);
        if (rows_push(r, v, k)) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    }
    if (ferror(f)) return biref_fail_status(BIREF_ERR_IO, msg, msg_len, "%s: read error", path);
    return BIREF_OK;
}

biref_status biref_material_load_csv(const char *path, biref_material **out, char *msg, size_t msg_len)
{
    if (!out) return biref_fail(msg, msg_len, "no output");
    *out = NULL;
    if (!path) return biref_fail(msg, msg_len, "no file name");
    FILE *f = fopen(path, "r");
    if (!f) return biref_fail_status(BIREF_ERR_IO, msg, msg_len, "cannot read %s: %s", path, strerror(errno));
    rows r = {0};
    int cols = 0;
    biref_status s = read_rows(f, path, &r, &cols, msg, msg_len);
    fclose(f);
    if (s == BIREF_OK && r.n < 2) s = biref_fail(msg, msg_len, "%s: a table needs at least 2 rows (got %zu)", path, r.n);
    if (s == BIREF_OK) {
        char why[BIREF_MSG_SIZE];
        const char *base = strrchr(path, '/');
        s = biref_material_from_table(base ? base + 1 : path, r.n, r.col[0], r.col[1], cols == 3 ? r.col[2] : NULL, out, why, sizeof why);
        if (s != BIREF_OK) biref_fail_status(s, msg, msg_len, "%s: %s", path, why);
    }
    for (int c = 0; c < 3; c++) free(r.col[c]);
    return s;
}
