/* Stress from finite-element node exports: a node table with named columns and stated units,
 * merged coincident nodes, a Delaunay triangulation by qhull, linear interpolation in each
 * triangle, and an optional boundary (even-odd polygons) outside which there is no material
 * (docs/PHOTOELASTICITY.md, "Stress from FEA nodes"). */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <libqhull_r/qhull_ra.h>

#include "biref/photoelastic.h"
#include "optics/validate.h"
#include "photoelastic/textfile.h"

#define MAX_FILE_BYTES ((size_t)1 << 31)
#define MAX_FIELDS 256
#define MAX_NODES 20000000L

typedef struct {
    double x0, y0;       /* first vertex */
    double a, b, c, d;   /* inverse of [x1-x0 x2-x0; y1-y0 y2-y0]: barycentrics l1, l2 */
    int v[3];
} tri;

struct biref_pe_mesh {
    size_t rows, n;
    double *xy;  /* [n][2] m */
    double *s;   /* [n][3] Pa */
    size_t ntri;
    tri *t;
    double box[4]; /* triangulation: xmin, xmax, ymin, ymax */
    /* Triangle buckets on a gx x gy grid over box (CSR). */
    int gx, gy;
    double cw, ch;
    size_t *cell_start;
    int *cell_tri;
    /* Boundary: loops of vertices, even-odd. */
    size_t nloops, nverts;
    size_t *loop_start; /* nloops + 1 */
    double *loop_xy;
    /* Per bucket cell: 1 all inside the boundary, 0 all outside, 2 crossed by it (test points). */
    unsigned char *cell_in;
};

static int inside_boundary(const biref_pe_mesh *m, double x, double y);

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

/* ------------------------------------------------------------------------ */
/* Lines and fields                                                          */
/* ------------------------------------------------------------------------ */

typedef struct {
    const char *p, *end;
    long line;
    int last; /* the line just returned ended the file without '\n' */
} line_reader;

/* Next non-blank, non-comment line [*b, *e), trimmed; 0 at the end. Blank lines are counted in
 * *blank (for the boundary's loop separators). */
static int next_line(line_reader *r, const char **b, const char **e, int *blank)
{
    while (r->p < r->end) {
        const char *nl = memchr(r->p, '\n', (size_t)(r->end - r->p));
        const char *lb = r->p, *le = nl ? nl : r->end;
        r->p = nl ? nl + 1 : r->end;
        r->last = nl == NULL;
        r->line++;
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

/* Splits at delim (' ' = runs of blanks); fields trimmed. Returns the count (may exceed cap). */
static int split_fields(const char *b, const char *e, char delim, const char *fb[], const char *fe[], int cap)
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

/* Strict number: the whole field, times scale, at most max in magnitude (1 km, 1 TPa: beyond any
 * part in a polariscope; within them spans, areas and fringe orders stay finite). 0 ok, else WHY's index. */
static const char *const WHY[] = {"", "empty field", "not a number", "not a finite number", "too long for a number",
                                  "out of range (beyond 1 km, 1 TPa)"};
static int parse_number(const char *b, const char *e, double scale, double max, double *out, char buf[64])
{
    size_t n = (size_t)(e - b);
    if (n == 0) return 1;
    if (n >= 64) n = 40;
    memcpy(buf, b, n);
    buf[n] = '\0';
    if ((size_t)(e - b) >= 64) return 4;
    char *endp = NULL;
    errno = 0;
    double v = strtod(buf, &endp);
    if (endp == buf || *endp != '\0') return 2;
    if (!isfinite(v) || errno == ERANGE) return 3;
    *out = v * scale;
    return fabs(*out) <= max ? 0 : 5;
}

static int name_is(const char *b, const char *e, const char *name)
{
    if (e - b >= 2 && (*b == '"' || *b == '\'') && e[-1] == *b) {
        b++;
        e--;
    }
    return (size_t)(e - b) == strlen(name) && !strncasecmp(b, name, (size_t)(e - b));
}

static int looks_numeric(const char *b, const char *e)
{
    char buf[64];
    double v;
    const int why = parse_number(b, e, 1.0, INFINITY, &v, buf);
    return why != 2 && why != 4 && e > b;
}

/* "syy (S22)" or "syy". */
static void column_label(char *out, size_t n, int role, const char *name)
{
    if (!strcasecmp(name, ROLE[role]))
        snprintf(out, n, "%s", name);
    else
        snprintf(out, n, "%s (%s)", name, ROLE[role]);
}

/* ------------------------------------------------------------------------ */
/* Triangulation                                                             */
/* ------------------------------------------------------------------------ */

typedef struct {
    double x, y, s[3];
    long line;
} node_row;

static int cmp_row(const void *pa, const void *pb)
{
    const node_row *a = pa, *b = pb;
    if (a->x != b->x) return a->x < b->x ? -1 : 1;
    if (a->y != b->y) return a->y < b->y ? -1 : 1;
    return (a->line > b->line) - (a->line < b->line);
}

/* Merges nodes at the same position (within tol) into their first row, stresses averaged.
 * rows sorted by x; returns the distinct count (rows compacted). */
static size_t merge_coincident(node_row *r, size_t n, double tol)
{
    char *gone = calloc(n ? n : 1, 1);
    if (!gone) return 0;
    size_t out = 0;
    for (size_t i = 0; i < n; i++) {
        if (gone[i]) continue;
        double acc[3] = {r[i].s[0], r[i].s[1], r[i].s[2]};
        int cnt = 1;
        for (size_t j = i + 1; j < n && r[j].x - r[i].x <= tol; j++)
            if (!gone[j] && fabs(r[j].y - r[i].y) <= tol) {
                for (int k = 0; k < 3; k++) acc[k] += r[j].s[k];
                cnt++;
                gone[j] = 1;
            }
        node_row m = r[i];
        for (int k = 0; k < 3; k++) m.s[k] = acc[k] / cnt;
        r[out++] = m;
    }
    free(gone);
    return out;
}

/* The Delaunay triangles qhull found (pts: the nodes in qhull's coordinates), each with the
 * inverse of its edge matrix; zero-area triangles (Qt's) are dropped. */
static biref_status collect_triangles(qhT *qh, biref_pe_mesh *m, double area_tol, char *msg, size_t msg_len)
{
    const size_t n = m->n;
    size_t cap = 0;
    facetT *facet;
    vertexT *vertex, **vertexp;
    FORALLfacets {
        if (!facet->upperdelaunay) cap++;
    }
    m->t = malloc((cap ? cap : 1) * sizeof *m->t);
    if (!m->t) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    FORALLfacets {
        if (facet->upperdelaunay) continue;
        int v[3], k = 0, ok = 1;
        FOREACHvertex_(facet->vertices) {
            int id = qh_pointid(qh, vertex->point);
            if (k < 3 && id >= 0 && (size_t)id < n)
                v[k] = id;
            else
                ok = 0;
            k++;
        }
        if (!ok || k != 3) continue;
        const double *p0 = m->xy + 2 * v[0], *p1 = m->xy + 2 * v[1], *p2 = m->xy + 2 * v[2];
        double ax = p1[0] - p0[0], bx = p2[0] - p0[0], ay = p1[1] - p0[1], by = p2[1] - p0[1];
        double det = ax * by - bx * ay;
        if (!(fabs(det) > area_tol)) continue; /* Qt's zero-area triangles */
        tri *t = &m->t[m->ntri++];
        t->x0 = p0[0];
        t->y0 = p0[1];
        t->a = by / det;
        t->b = -bx / det;
        t->c = -ay / det;
        t->d = ax / det;
        memcpy(t->v, v, sizeof v);
    }
    if (m->ntri == 0) return biref_fail(msg, msg_len, "the nodes do not span an area (all on one line?)");
    return BIREF_OK;
}

/* Delaunay triangulation of the nodes (bounding box lo, hi) by qhull. */
static biref_status delaunay(biref_pe_mesh *m, const double lo[2], const double hi[2], char *msg, size_t msg_len)
{
    const size_t n = m->n;
    /* qhull works best on coordinates of order one. */
    const double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
    const double sc = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(sc > 0)) return biref_fail(msg, msg_len, "all nodes are at one point");
    coordT *pts = malloc(n * 2 * sizeof *pts);
    if (!pts) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    for (size_t i = 0; i < n; i++) {
        pts[2 * i] = (m->xy[2 * i] - cx) / sc;
        pts[2 * i + 1] = (m->xy[2 * i + 1] - cy) / sc;
    }
    char *errbuf = NULL;
    size_t errlen = 0;
    FILE *errf = open_memstream(&errbuf, &errlen);
    if (!errf) {
        free(pts);
        return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    }
    qhT qh_qh;
    qhT *qh = &qh_qh;
    qh_zero(qh, errf);
    /* d: Delaunay; Qt: triangulated output; Qbb: scale the paraboloid; Qc: keep coplanar points;
     * Qz: a point at infinity, for the cocircular nodes every round part has. */
    char flags[] = "qhull d Qt Qbb Qc Qz Q12";
    int code = qh_new_qhull(qh, 2, (int)n, pts, False, flags, NULL, errf);
    biref_status st;
    if (code == qh_ERRmem)
        st = biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory in the triangulation (qhull)");
    else if (code)
        st = biref_fail(msg, msg_len, "cannot triangulate the nodes (qhull error %d%s)", code,
                        code == qh_ERRsingular || code == qh_ERRprec ? ": they do not span an area, all on one line?" : "");
    else
        st = collect_triangles(qh, m, 1e-14 * (hi[0] - lo[0]) * (hi[1] - lo[1]) + 1e-300, msg, msg_len);
    qh_freeqhull(qh, !qh_ALL);
    int curlong, totlong;
    qh_memfreeshort(qh, &curlong, &totlong);
    fclose(errf);
    free(errbuf);
    free(pts);
    return st;
}

/* Buckets for the point location: about two triangles per cell of a grid over the box, each
 * triangle listed in every cell its bounding box touches (CSR). */
static biref_status bucket_triangles(biref_pe_mesh *m, const double lo[2], const double hi[2], char *msg, size_t msg_len)
{
    m->box[0] = lo[0];
    m->box[1] = hi[0];
    m->box[2] = lo[1];
    m->box[3] = hi[1];
    double w = hi[0] - lo[0], h = hi[1] - lo[1];
    double cells = fmax(1.0, (double)m->ntri / 2.0);
    double side = sqrt(w * h / cells);
    if (!(side > 0)) side = fmax(w, h);
    m->gx = (int)fmin(4096, fmax(1, ceil(w / side)));
    m->gy = (int)fmin(4096, fmax(1, ceil(h / side)));
    m->cw = w / m->gx;
    m->ch = h / m->gy;
    if (!(m->cw > 0)) m->cw = 1;
    if (!(m->ch > 0)) m->ch = 1;
    size_t ncell = (size_t)m->gx * m->gy;
    m->cell_start = calloc(ncell + 1, sizeof *m->cell_start);
    if (!m->cell_start) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    for (int pass = 0; pass < 2; pass++) {
        size_t *fill = NULL;
        if (pass == 1) {
            for (size_t c = 0; c < ncell; c++) m->cell_start[c + 1] += m->cell_start[c];
            m->cell_tri = malloc((m->cell_start[ncell] ? m->cell_start[ncell] : 1) * sizeof *m->cell_tri);
            fill = malloc(ncell * sizeof *fill);
            if (!m->cell_tri || !fill) {
                free(fill);
                return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
            }
            memcpy(fill, m->cell_start, ncell * sizeof *fill);
        }
        for (size_t i = 0; i < m->ntri; i++) {
            double tx0 = INFINITY, tx1 = -INFINITY, ty0 = INFINITY, ty1 = -INFINITY;
            for (int k = 0; k < 3; k++) {
                const double *p = m->xy + 2 * m->t[i].v[k];
                tx0 = fmin(tx0, p[0]);
                tx1 = fmax(tx1, p[0]);
                ty0 = fmin(ty0, p[1]);
                ty1 = fmax(ty1, p[1]);
            }
            int i0 = (int)floor((tx0 - lo[0]) / m->cw), i1 = (int)floor((tx1 - lo[0]) / m->cw);
            int j0 = (int)floor((ty0 - lo[1]) / m->ch), j1 = (int)floor((ty1 - lo[1]) / m->ch);
            i0 = i0 < 0 ? 0 : i0 >= m->gx ? m->gx - 1 : i0;
            i1 = i1 < 0 ? 0 : i1 >= m->gx ? m->gx - 1 : i1;
            j0 = j0 < 0 ? 0 : j0 >= m->gy ? m->gy - 1 : j0;
            j1 = j1 < 0 ? 0 : j1 >= m->gy ? m->gy - 1 : j1;
            for (int j = j0; j <= j1; j++)
                for (int ii = i0; ii <= i1; ii++) {
                    size_t c = (size_t)j * m->gx + ii;
                    if (pass == 0)
                        m->cell_start[c + 1]++;
                    else
                        m->cell_tri[fill[c]++] = (int)i;
                }
        }
        free(fill);
    }
    return BIREF_OK;
}

static biref_status triangulate(biref_pe_mesh *m, char *msg, size_t msg_len)
{
    const size_t n = m->n;
    if (n < 3) return biref_fail(msg, msg_len, "%zu distinct node%s: a triangulation needs at least 3", n, n == 1 ? "" : "s");
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 2; c++) {
            lo[c] = fmin(lo[c], m->xy[2 * i + c]);
            hi[c] = fmax(hi[c], m->xy[2 * i + c]);
        }
    biref_status st = delaunay(m, lo, hi, msg, msg_len);
    if (st != BIREF_OK) return st;
    return bucket_triangles(m, lo, hi, msg, msg_len);
}

/* ------------------------------------------------------------------------ */
/* Node table                                                                */
/* ------------------------------------------------------------------------ */

/* The header line [b, e): the column of each role (col), its label for messages, the field
 * delimiter (',' or ';' if present, else blanks) and the column count. */
static biref_status map_header(const char *b, const char *e, long line, const char *const names[NROLE], int col[NROLE],
                               char label[NROLE][80], char *delim, int *ncol, char *msg, size_t msg_len)
{
    *delim = memchr(b, ',', (size_t)(e - b)) ? ',' : memchr(b, ';', (size_t)(e - b)) ? ';' : ' ';
    const char *hb[MAX_FIELDS], *he[MAX_FIELDS];
    *ncol = split_fields(b, e, *delim, hb, he, MAX_FIELDS);
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
            if (looks_numeric(hb[0], he[0]))
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

/* One node row: position and stress in the file's units scaled to metres and pascals. */
static biref_status parse_node(const char *const db[], const char *const de[], const int col[NROLE],
                               const char label[NROLE][80], const biref_pe_node_format *fmt, long line, node_row *nr,
                               char *msg, size_t msg_len)
{
    double v[NROLE];
    for (int r = 0; r < NROLE; r++) {
        char buf[64];
        int why = parse_number(db[col[r]], de[col[r]], r < 2 ? fmt->length_m : fmt->stress_pa,
                               r < 2 ? 1e3 : 1e12, &v[r], buf);
        if (why) /* "line 7, column syy (S22): not a number: 'abc'" */
            return biref_fail(msg, msg_len, "line %ld, column %s: %s%s%s%s", line, label[r], WHY[why], why > 1 ? ": '" : "",
                              why > 1 ? buf : "", why == 4 ? "...'" : why > 1 ? "'" : "");
    }
    nr->x = v[ROLE_X];
    nr->y = v[ROLE_Y];
    nr->s[0] = v[ROLE_SXX];
    nr->s[1] = v[ROLE_SYY];
    nr->s[2] = v[ROLE_TXY];
    nr->line = line;
    return BIREF_OK;
}

/* The data rows after the header (ncol fields each); at least 3. */
static biref_status read_nodes(line_reader *rd, char delim, int ncol, const int col[NROLE], const char label[NROLE][80],
                               const biref_pe_node_format *fmt, node_row **rows_out, size_t *n_out, char *msg,
                               size_t msg_len)
{
    size_t cap = 0, n = 0;
    node_row *rows = NULL;
    biref_status st = BIREF_OK;
    const char *b, *e, *db[MAX_FIELDS], *de[MAX_FIELDS];
    while (st == BIREF_OK && next_line(rd, &b, &e, NULL)) {
        int nf = split_fields(b, e, delim, db, de, MAX_FIELDS);
        if (nf != ncol) {
            if (rd->last && nf < ncol)
                st = biref_fail(msg, msg_len, "line %ld: truncated row (%d of %d fields, and the file ends there)",
                                rd->line, nf, ncol);
            else
                st = biref_fail(msg, msg_len, "line %ld: expected %d fields as in the header, got %d", rd->line, ncol, nf);
            break;
        }
        if (n == cap) {
            if ((long)n >= MAX_NODES) {
                st = biref_fail(msg, msg_len, "line %ld: more than %ld nodes", rd->line, MAX_NODES);
                break;
            }
            size_t nc = cap ? 2 * cap : 1024;
            node_row *nr = realloc(rows, nc * sizeof *rows);
            if (!nr) {
                st = biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
                break;
            }
            rows = nr;
            cap = nc;
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

/* The mesh's nodes: rows sorted, coincident ones merged. */
static biref_status mesh_nodes(biref_pe_mesh *m, node_row *rows, size_t n, char *msg, size_t msg_len)
{
    qsort(rows, n, sizeof *rows, cmp_row);
    double ext = 0;
    for (size_t i = 0; i < n; i++) ext = fmax(ext, fmax(fabs(rows[i].x), fabs(rows[i].y)));
    m->rows = n;
    m->n = merge_coincident(rows, n, 1e-12 * ext);
    m->xy = malloc(m->n * 2 * sizeof *m->xy);
    m->s = malloc(m->n * 3 * sizeof *m->s);
    if (!m->n || !m->xy || !m->s) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    for (size_t i = 0; i < m->n; i++) {
        m->xy[2 * i] = rows[i].x;
        m->xy[2 * i + 1] = rows[i].y;
        memcpy(m->s + 3 * i, rows[i].s, sizeof rows[i].s);
    }
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
    line_reader rd = {text, text + len, 0, 0};
    if (len >= 3 && !memcmp(text, "\xEF\xBB\xBF", 3)) rd.p += 3;
    if (memchr(text, '\0', len)) {
        /* Report the line of the first NUL. */
        const char *z = memchr(text, '\0', len);
        long ln = 1;
        for (const char *q = text; q < z; q++) ln += *q == '\n';
        return biref_fail(msg, msg_len, "line %ld: contains a NUL byte (not a text file?)", ln);
    }
    const char *b, *e;
    if (!next_line(&rd, &b, &e, NULL))
        return biref_fail(msg, msg_len, "empty file: expected a header naming the columns %s, %s, %s, %s, %s", names[0],
                          names[1], names[2], names[3], names[4]);
    int col[NROLE], ncol;
    char label[NROLE][80], delim;
    biref_status st = map_header(b, e, rd.line, names, col, label, &delim, &ncol, msg, msg_len);
    if (st != BIREF_OK) return st;
    node_row *rows = NULL;
    size_t n = 0;
    st = read_nodes(&rd, delim, ncol, col, (const char(*)[80])label, fmt, &rows, &n, msg, msg_len);
    if (st != BIREF_OK) return st;
    biref_pe_mesh *m = calloc(1, sizeof *m);
    st = m ? mesh_nodes(m, rows, n, msg, msg_len) : biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    free(rows);
    if (st == BIREF_OK) st = triangulate(m, msg, msg_len);
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
    biref_status st = biref_pe_read_text(path, MAX_FILE_BYTES, &text, &len, msg, msg_len);
    if (st != BIREF_OK) return st;
    st = biref_pe_mesh_parse(text, len, fmt, out, msg, msg_len);
    free(text);
    return st;
}

/* ------------------------------------------------------------------------ */
/* Boundary                                                                  */
/* ------------------------------------------------------------------------ */

/* Per bucket cell: 2 if a boundary edge may touch it (its points are tested one by one), else
 * wholly inside (1) or outside (0) the boundary, as its centre. */
static void classify_cells(biref_pe_mesh *m)
{
    const size_t ncell = (size_t)m->gx * m->gy, nl = m->nloops, *starts = m->loop_start;
    const double *xy = m->loop_xy;
    unsigned char *cin = m->cell_in;
    memset(cin, 0, ncell);
    for (size_t l = 0; l < nl; l++)
        for (size_t i = starts[l], j = starts[l + 1] - 1; i < starts[l + 1]; j = i++) {
            const double x0 = fmin(xy[2 * i], xy[2 * j]), x1 = fmax(xy[2 * i], xy[2 * j]);
            const double y0 = fmin(xy[2 * i + 1], xy[2 * j + 1]), y1 = fmax(xy[2 * i + 1], xy[2 * j + 1]);
            double fi0 = floor((x0 - m->box[0]) / m->cw) - 1, fi1 = floor((x1 - m->box[0]) / m->cw) + 1;
            double fj0 = floor((y0 - m->box[2]) / m->ch) - 1, fj1 = floor((y1 - m->box[2]) / m->ch) + 1;
            if (fi1 < 0 || fj1 < 0 || fi0 >= m->gx || fj0 >= m->gy) continue;
            int i0 = fi0 < 0 ? 0 : (int)fi0, i1 = fi1 >= m->gx ? m->gx - 1 : (int)fi1;
            int j0 = fj0 < 0 ? 0 : (int)fj0, j1 = fj1 >= m->gy ? m->gy - 1 : (int)fj1;
            for (int jj = j0; jj <= j1; jj++)
                for (int ii = i0; ii <= i1; ii++) cin[(size_t)jj * m->gx + ii] = 2;
        }
    for (int jj = 0; jj < m->gy; jj++)
        for (int ii = 0; ii < m->gx; ii++) {
            unsigned char *c = &cin[(size_t)jj * m->gx + ii];
            if (*c != 2) *c = (unsigned char)inside_boundary(m, m->box[0] + (ii + 0.5) * m->cw, m->box[2] + (jj + 0.5) * m->ch);
        }
}

biref_status biref_pe_mesh_boundary_parse(biref_pe_mesh *m, const char *text, size_t len, double length_m, char *msg,
                                          size_t msg_len)
{
    if (!m || !text) return biref_fail(msg, msg_len, "no mesh or text");
    if (!(isfinite(length_m) && length_m > 0)) return biref_fail(msg, msg_len, "the length unit must be positive");
    if (memchr(text, '\0', len)) return biref_fail(msg, msg_len, "contains a NUL byte (not a text file?)");
    line_reader rd = {text, text + len, 0, 0};
    if (len >= 3 && !memcmp(text, "\xEF\xBB\xBF", 3)) rd.p += 3;
    size_t cap = 0, nv = 0, lcap = 0, nl = 0;
    double *xy = NULL;
    size_t *starts = NULL; /* start of each loop */
    long *loop_line = NULL;
    biref_status st = BIREF_OK;
    const char *b, *e;
    int blank = 0, first = 1;
    while (st == BIREF_OK) {
        blank = 0;
        if (!next_line(&rd, &b, &e, &blank)) break;
        const char *fb[3], *fe[3];
        char delim = memchr(b, ',', (size_t)(e - b)) ? ',' : memchr(b, ';', (size_t)(e - b)) ? ';' : ' ';
        int nf = split_fields(b, e, delim, fb, fe, 3);
        if (first && nf >= 1 && !looks_numeric(fb[0], fe[0])) { /* a header */
            first = 0;
            continue;
        }
        first = 0;
        if (nf != 2) {
            st = biref_fail(msg, msg_len, "line %ld: expected two fields x,y, got %d", rd.line, nf);
            break;
        }
        double v[2];
        for (int c = 0; c < 2 && st == BIREF_OK; c++) {
            char buf[64];
            int why = parse_number(fb[c], fe[c], length_m, 1e3, &v[c], buf);
            if (why)
                st = biref_fail(msg, msg_len, "line %ld, column %s: %s: '%s%s'", rd.line, c ? "y" : "x", WHY[why], buf,
                                why == 4 ? "..." : "");
        }
        if (st != BIREF_OK) break;
        if (nl == 0 || blank) {
            if (nl == lcap) {
                lcap = lcap ? 2 * lcap : 8;
                size_t *ns = realloc(starts, (lcap + 1) * sizeof *ns);
                long *nll = realloc(loop_line, lcap * sizeof *nll);
                if (ns) starts = ns;
                if (nll) loop_line = nll;
                if (!ns || !nll) {
                    st = BIREF_ERR_NOMEM;
                    break;
                }
            }
            starts[nl] = nv;
            loop_line[nl] = rd.line;
            nl++;
        }
        if (nv == cap) {
            cap = cap ? 2 * cap : 256;
            double *nx = realloc(xy, cap * 2 * sizeof *nx);
            if (!nx) {
                st = BIREF_ERR_NOMEM;
                break;
            }
            xy = nx;
        }
        xy[2 * nv] = v[0];
        xy[2 * nv + 1] = v[1];
        nv++;
    }
    if (st == BIREF_ERR_NOMEM) biref_fail(msg, msg_len, "out of memory");
    if (st == BIREF_OK && nl == 0) st = biref_fail(msg, msg_len, "no boundary vertices (expected lines x,y)");
    for (size_t l = 0; st == BIREF_OK && l < nl; l++) {
        size_t cnt = (l + 1 < nl ? starts[l + 1] : nv) - starts[l];
        if (cnt < 3)
            st = biref_fail(msg, msg_len, "line %ld: a boundary polygon needs at least 3 vertices, this one has %zu",
                            loop_line[l], cnt);
    }
    free(loop_line);
    if (st != BIREF_OK) {
        free(xy);
        free(starts);
        return st;
    }
    starts[nl] = nv;
    const size_t ncell = (size_t)m->gx * m->gy;
    unsigned char *cin = malloc(ncell);
    if (!cin) {
        free(xy);
        free(starts);
        return biref_fail(msg, msg_len, "out of memory"), BIREF_ERR_NOMEM;
    }
    free(m->loop_xy);
    free(m->loop_start);
    free(m->cell_in);
    m->loop_xy = xy;
    m->loop_start = starts;
    m->nloops = nl;
    m->nverts = nv;
    m->cell_in = cin;
    classify_cells(m);
    return BIREF_OK;
}

biref_status biref_pe_mesh_boundary_load(biref_pe_mesh *m, const char *path, double length_m, char *msg,
                                         size_t msg_len)
{
    char *text;
    size_t len;
    biref_status st = biref_pe_read_text(path, MAX_FILE_BYTES, &text, &len, msg, msg_len);
    if (st != BIREF_OK) return st;
    st = biref_pe_mesh_boundary_parse(m, text, len, length_m, msg, msg_len);
    free(text);
    return st;
}

void biref_pe_mesh_destroy(biref_pe_mesh *m)
{
    if (!m) return;
    free(m->xy);
    free(m->s);
    free(m->t);
    free(m->cell_start);
    free(m->cell_tri);
    free(m->loop_start);
    free(m->loop_xy);
    free(m->cell_in);
    free(m);
}

void biref_pe_mesh_get_info(const biref_pe_mesh *m, biref_pe_mesh_info *out)
{
    out->rows = m->rows;
    out->nodes = m->n;
    out->triangles = m->ntri;
    out->loops = m->nloops;
    out->loop_vertices = m->nverts;
}

void biref_pe_mesh_bounds(const biref_pe_mesh *m, double b[4])
{
    memcpy(b, m->box, sizeof m->box);
}

/* Even-odd rule over all loops (an outline and its holes). */
static int inside_boundary(const biref_pe_mesh *m, double x, double y)
{
    int in = 0;
    for (size_t l = 0; l < m->nloops; l++) {
        const size_t s = m->loop_start[l], cnt = m->loop_start[l + 1] - s;
        const double *p = m->loop_xy + 2 * s;
        for (size_t i = 0, j = cnt - 1; i < cnt; j = i++) {
            const double xi = p[2 * i], yi = p[2 * i + 1], xj = p[2 * j], yj = p[2 * j + 1];
            if ((yi > y) != (yj > y) && x < xj + (y - yj) * (xi - xj) / (yi - yj)) in = !in;
        }
    }
    return in;
}

int biref_pe_mesh_stress(const biref_pe_mesh *m, double x, double y, biref_pe_stress *out)
{
    if (!(x >= m->box[0] && x <= m->box[1] && y >= m->box[2] && y <= m->box[3])) return 0;
    int i = (int)((x - m->box[0]) / m->cw), j = (int)((y - m->box[2]) / m->ch);
    if (i >= m->gx) i = m->gx - 1;
    if (j >= m->gy) j = m->gy - 1;
    const size_t c = (size_t)j * m->gx + i;
    /* A sliver of tolerance keeps points on shared edges and on the hull inside. */
    const double eps = -1e-12;
    for (size_t k = m->cell_start[c]; k < m->cell_start[c + 1]; k++) {
        const tri *t = &m->t[m->cell_tri[k]];
        const double dx = x - t->x0, dy = y - t->y0;
        const double l1 = t->a * dx + t->b * dy, l2 = t->c * dx + t->d * dy, l0 = 1.0 - l1 - l2;
        if (l0 < eps || l1 < eps || l2 < eps) continue;
        if (m->nloops && (m->cell_in[c] == 0 || (m->cell_in[c] == 2 && !inside_boundary(m, x, y)))) return 0;
        const double *s0 = m->s + 3 * t->v[0], *s1 = m->s + 3 * t->v[1], *s2 = m->s + 3 * t->v[2];
        out->sxx = l0 * s0[0] + l1 * s1[0] + l2 * s2[0];
        out->syy = l0 * s0[1] + l1 * s1[1] + l2 * s2[1];
        out->txy = l0 * s0[2] + l1 * s1[2] + l2 * s2[2];
        return 1;
    }
    return 0;
}
