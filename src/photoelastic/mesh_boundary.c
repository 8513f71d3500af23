/* A mesh's boundary: closed polygons (an outline and its holes, even-odd rule) outside which there
 * is no material. Point-in-polygon through an index of the edges by horizontal bands, so a
 * polygon of a million vertices costs a few edge tests per point, not a million. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "optics/validate.h"
#include "photoelastic/mesh_internal.h"
#include "photoelastic/textfile.h"

/* Boundary vertices beyond this are refused before they are stored (a million-vertex outline
 * costs about 50 MB and a second to index). */
#define PE_MAX_BOUNDARY_VERTICES 20000000L

void pe_polygons_free(pe_polygons *p)
{
    free(p->loop_start);
    free(p->xy);
    free(p->band_start);
    free(p->band_edge);
    free(p->next);
    memset(p, 0, sizeof *p);
}

static int band_of(const pe_polygons *p, double y)
{
    const double b = floor((y - p->y0) / p->bh);
    return b < 0 ? 0 : b >= p->nb ? p->nb - 1 : (int)b;
}

/* The band index: as many bands as keep the listed edges under about nine per vertex whatever
 * the edges' lengths. */
static biref_status index_bands(pe_polygons *p)
{
    const size_t nv = p->nverts;
    p->next = malloc(nv * sizeof *p->next);
    if (!p->next) return BIREF_ERR_NOMEM;
    double ylo = INFINITY, yhi = -INFINITY;
    for (size_t l = 0; l < p->nloops; l++)
        for (size_t i = p->loop_start[l]; i < p->loop_start[l + 1]; i++) {
            p->next[i] = i + 1 < p->loop_start[l + 1] ? i + 1 : p->loop_start[l];
            ylo = fmin(ylo, p->xy[2 * i + 1]), yhi = fmax(yhi, p->xy[2 * i + 1]);
        }
    const double H = yhi > ylo ? yhi - ylo : 1.0;
    double S = 0; /* the edges' heights in units of H */
    for (size_t i = 0; i < nv; i++) S += fabs(p->xy[2 * p->next[i] + 1] - p->xy[2 * i + 1]) / H;
    p->nb = (int)fmax(1, fmin(fmin((double)nv, 1 << 22), 7.0 * (double)nv / fmax(S, 1e-300)));
    p->y0 = ylo;
    p->bh = H / p->nb;
    p->band_start = calloc((size_t)p->nb + 1, sizeof *p->band_start);
    if (!p->band_start) return BIREF_ERR_NOMEM;
    size_t *fill = NULL;
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1) {
            for (int b = 0; b < p->nb; b++) p->band_start[b + 1] += p->band_start[b];
            p->band_edge = malloc((p->band_start[p->nb] ? p->band_start[p->nb] : 1) * sizeof *p->band_edge);
            fill = malloc((size_t)p->nb * sizeof *fill);
            if (!p->band_edge || !fill) {
                free(fill);
                return BIREF_ERR_NOMEM;
            }
            memcpy(fill, p->band_start, (size_t)p->nb * sizeof *fill);
        }
        for (size_t i = 0; i < nv; i++) {
            const double ya = p->xy[2 * i + 1], yb = p->xy[2 * p->next[i] + 1];
            for (int b = band_of(p, fmin(ya, yb)), b1 = band_of(p, fmax(ya, yb)); b <= b1; b++) {
                if (pass == 0)
                    p->band_start[b + 1]++;
                else
                    p->band_edge[fill[b]++] = i;
            }
        }
    }
    free(fill);
    return BIREF_OK;
}

/* Even-odd rule over all loops: crossings of a ray towards +x with the edges of y's band (every
 * edge spanning y is listed there). */
int pe_polygons_inside(const pe_polygons *p, double x, double y)
{
    if (!(y >= p->y0 && y <= p->y0 + p->bh * p->nb)) return 0;
    const int b = band_of(p, y);
    int in = 0;
    for (size_t k = p->band_start[b]; k < p->band_start[b + 1]; k++) {
        const size_t i = p->band_edge[k], j = p->next[i];
        const double xi = p->xy[2 * i], yi = p->xy[2 * i + 1], xj = p->xy[2 * j], yj = p->xy[2 * j + 1];
        if ((yi > y) != (yj > y) && x < xj + (y - yj) * (xi - xj) / (yi - yj)) in = !in;
    }
    return in;
}

/* Per bucket cell: 2 if a boundary edge may touch it (its points are tested one by one), else
 * wholly inside (1) or outside (0) the boundary, as its centre. */
static void classify_cells(biref_pe_mesh *m)
{
    const pe_polygons *p = &m->bnd;
    unsigned char *cin = m->cell_in;
    memset(cin, 0, (size_t)m->gx * m->gy);
    for (size_t i = 0; i < p->nverts; i++) {
        const size_t j = p->next[i];
        const double *xy = p->xy;
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
            if (*c != 2) *c = (unsigned char)pe_polygons_inside(p, m->box[0] + (ii + 0.5) * m->cw, m->box[2] + (jj + 0.5) * m->ch);
        }
}

/* Appends a vertex (and, at a new polygon, its start); BIREF_ERR_NOMEM when full. */
static biref_status add_vertex(pe_polygons *p, size_t *cap, size_t *lcap, long **loop_line, int new_loop, long line,
                               const double v[2])
{
    if (new_loop) {
        if (p->nloops == *lcap) {
            *lcap = *lcap ? 2 * *lcap : 8;
            size_t *ns = realloc(p->loop_start, (*lcap + 1) * sizeof *ns);
            if (ns) p->loop_start = ns;
            long *nll = realloc(*loop_line, *lcap * sizeof *nll);
            if (nll) *loop_line = nll;
            if (!ns || !nll) return BIREF_ERR_NOMEM;
        }
        p->loop_start[p->nloops] = p->nverts;
        (*loop_line)[p->nloops++] = line;
    }
    if (p->nverts == *cap) {
        *cap = *cap ? 2 * *cap : 256;
        double *nx = realloc(p->xy, *cap * 2 * sizeof *nx);
        if (!nx) return BIREF_ERR_NOMEM;
        p->xy = nx;
    }
    p->xy[2 * p->nverts] = v[0];
    p->xy[2 * p->nverts + 1] = v[1];
    p->nverts++;
    return BIREF_OK;
}

/* One vertex line "x,y" scaled to metres. */
static biref_status parse_vertex(const char *b, const char *e, long line, double length_m, double v[2], char *msg,
                                 size_t msg_len)
{
    const char *fb[3], *fe[3];
    char delim = memchr(b, ',', (size_t)(e - b)) ? ',' : memchr(b, ';', (size_t)(e - b)) ? ';' : ' ';
    int nf = pe_split_fields(b, e, delim, fb, fe, 3);
    if (nf != 2) return biref_fail(msg, msg_len, "line %ld: expected two fields x,y, got %d", line, nf);
    for (int c = 0; c < 2; c++) {
        char show[48];
        int why = pe_parse_number(fb[c], fe[c], &v[c], show);
        if (why == PE_NUM_OK && !(fabs(v[c] * length_m) <= PE_MAX_COORD_M)) why = PE_NUM_RANGE;
        if (why)
            return biref_fail(msg, msg_len, "line %ld, column %s: %s: '%s'", line, c ? "y" : "x",
                              why == PE_NUM_EMPTY ? "empty field" : why == PE_NUM_NAN ? "not a number"
                              : why == PE_NUM_INF ? "not a finite number" : "out of range (|coordinate| at most 1000 m)",
                              show);
        v[c] *= length_m;
    }
    return BIREF_OK;
}

/* The polygons of a boundary text. */
static biref_status parse_polygons(const char *text, size_t len, double length_m, pe_polygons *p, char *msg, size_t msg_len)
{
    pe_line_reader rd = {text, text + len, 0, 0};
    if (len >= 3 && !memcmp(text, "\xEF\xBB\xBF", 3)) rd.p += 3;
    size_t cap = 0, lcap = 0;
    long *loop_line = NULL;
    biref_status st = BIREF_OK;
    const char *b, *e;
    int blank = 0, first = 1;
    while (st == BIREF_OK) {
        blank = 0;
        if (!pe_next_line(&rd, &b, &e, &blank)) break;
        if (first) {
            const char *fb[1], *fe[1];
            char delim = memchr(b, ',', (size_t)(e - b)) ? ',' : memchr(b, ';', (size_t)(e - b)) ? ';' : ' ';
            pe_split_fields(b, e, delim, fb, fe, 1);
            first = 0;
            if (!pe_looks_numeric(fb[0], fe[0])) continue; /* a header */
        }
        double v[2];
        st = parse_vertex(b, e, rd.line, length_m, v, msg, msg_len);
        if (st == BIREF_OK && p->nverts >= (size_t)PE_MAX_BOUNDARY_VERTICES)
            st = biref_fail(msg, msg_len, "line %ld: more than %ld boundary vertices", rd.line, PE_MAX_BOUNDARY_VERTICES);
        if (st == BIREF_OK) st = add_vertex(p, &cap, &lcap, &loop_line, p->nloops == 0 || blank, rd.line, v);
    }
    if (st == BIREF_ERR_NOMEM) biref_fail(msg, msg_len, "out of memory");
    if (st == BIREF_OK && p->nloops == 0) st = biref_fail(msg, msg_len, "no boundary vertices (expected lines x,y)");
    for (size_t l = 0; st == BIREF_OK && l < p->nloops; l++) {
        size_t cnt = (l + 1 < p->nloops ? p->loop_start[l + 1] : p->nverts) - p->loop_start[l];
        if (cnt < 3)
            st = biref_fail(msg, msg_len, "line %ld: a boundary polygon needs at least 3 vertices, this one has %zu",
                            loop_line[l], cnt);
    }
    free(loop_line);
    if (st == BIREF_OK) {
        p->loop_start[p->nloops] = p->nverts;
        if (index_bands(p) != BIREF_OK) st = biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    }
    return st;
}

biref_status biref_pe_mesh_boundary_parse(biref_pe_mesh *m, const char *text, size_t len, double length_m, char *msg,
                                          size_t msg_len)
{
    if (!m || !text) return biref_fail(msg, msg_len, "no mesh or text");
    if (!(isfinite(length_m) && length_m > 0)) return biref_fail(msg, msg_len, "the length unit must be positive");
    long nul = pe_nul_line(text, len);
    if (nul) return biref_fail(msg, msg_len, "line %ld: contains a NUL byte (not a text file?)", nul);
    pe_polygons p;
    memset(&p, 0, sizeof p);
    biref_status st = parse_polygons(text, len, length_m, &p, msg, msg_len);
    unsigned char *cin = st == BIREF_OK ? malloc((size_t)m->gx * m->gy) : NULL;
    if (st == BIREF_OK && !cin) st = biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    if (st != BIREF_OK) {
        pe_polygons_free(&p);
        return st;
    }
    pe_polygons_free(&m->bnd);
    free(m->cell_in);
    m->bnd = p;
    m->cell_in = cin;
    classify_cells(m);
    return BIREF_OK;
}

biref_status biref_pe_mesh_boundary_load(biref_pe_mesh *m, const char *path, double length_m, char *msg,
                                         size_t msg_len)
{
    char *text;
    size_t len;
    biref_status st = biref_pe_read_text(path, PE_MAX_FILE_BYTES, &text, &len, msg, msg_len);
    if (st != BIREF_OK) return st;
    st = biref_pe_mesh_boundary_parse(m, text, len, length_m, msg, msg_len);
    free(text);
    return st;
}
