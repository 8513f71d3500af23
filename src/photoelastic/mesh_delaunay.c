/* The nodes of a node table: coincident ones merged, then triangulated by qhull (Delaunay), each
 * triangle a linear element. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libqhull_r/qhull_ra.h>

#include "optics/validate.h"
#include "photoelastic/mesh_internal.h"

static int cmp_row(const void *pa, const void *pb)
{
    const pe_node_row *a = pa, *b = pb;
    if (a->x != b->x) return a->x < b->x ? -1 : 1;
    if (a->y != b->y) return a->y < b->y ? -1 : 1;
    return (a->line > b->line) - (a->line < b->line);
}

/* Merges nodes at the same position (within tol) into their first row, stresses averaged.
 * rows sorted by x; returns the distinct count (rows compacted), 0 when out of memory. */
static size_t merge_coincident(pe_node_row *r, size_t n, double tol)
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
        pe_node_row m = r[i];
        for (int k = 0; k < 3; k++) m.s[k] = acc[k] / cnt;
        r[out++] = m;
    }
    free(gone);
    return out;
}

biref_status pe_mesh_nodes_from_rows(biref_pe_mesh *m, pe_node_row *rows, size_t n, char *msg, size_t msg_len)
{
    qsort(rows, n, sizeof *rows, cmp_row);
    double ext = 0;
    for (size_t i = 0; i < n; i++) ext = fmax(ext, fmax(fabs(rows[i].x), fabs(rows[i].y)));
    m->rows = n;
    m->n = merge_coincident(rows, n, 1e-12 * ext);
    m->xy = malloc((m->n ? m->n : 1) * 2 * sizeof *m->xy);
    m->s = malloc((m->n ? m->n : 1) * 3 * sizeof *m->s);
    if (!m->n || !m->xy || !m->s) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    for (size_t i = 0; i < m->n; i++) {
        m->xy[2 * i] = rows[i].x;
        m->xy[2 * i + 1] = rows[i].y;
        memcpy(m->s + 3 * i, rows[i].s, sizeof rows[i].s);
    }
    return BIREF_OK;
}

/* The Delaunay triangles qhull found (in qhull's order), as TRI3 elements; zero-area triangles
 * (Qt's) are dropped. */
static biref_status collect_triangles(qhT *qh, biref_pe_mesh *m, double area_tol, char *msg, size_t msg_len)
{
    const size_t n = m->n;
    size_t cap = 0;
    facetT *facet;
    vertexT *vertex, **vertexp;
    FORALLfacets {
        if (!facet->upperdelaunay) cap++;
    }
    m->el = malloc((cap ? cap : 1) * sizeof *m->el);
    if (!m->el) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
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
        double det = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1]);
        if (!(fabs(det) > area_tol)) continue; /* Qt's zero-area triangles */
        pe_elem *e = &m->el[m->nel++];
        memset(e, 0, sizeof *e);
        e->type = BIREF_PE_TRI3;
        memcpy(e->v, v, sizeof v);
        pe_element_prepare(m, e);
    }
    if (m->nel == 0) return biref_fail(msg, msg_len, "the nodes do not span an area (all on one line?)");
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
        st = biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory while triangulating %zu nodes", n);
    else if (code == qh_ERRsingular)
        st = biref_fail(msg, msg_len, "cannot triangulate the nodes: they all lie on one line");
    else if (code)
        st = biref_fail(msg, msg_len, "cannot triangulate the nodes (qhull error %d)", code);
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

biref_status pe_mesh_triangulate(biref_pe_mesh *m, char *msg, size_t msg_len)
{
    const size_t n = m->n;
    if (n < 3) return biref_fail(msg, msg_len, "%zu distinct node%s: a triangulation needs at least 3", n, n == 1 ? "" : "s");
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 2; c++) {
            lo[c] = fmin(lo[c], m->xy[2 * i + c]);
            hi[c] = fmax(hi[c], m->xy[2 * i + c]);
        }
    m->delaunay = 1;
    biref_status st = delaunay(m, lo, hi, msg, msg_len);
    if (st != BIREF_OK) return st;
    return pe_mesh_buckets(m, msg, msg_len);
}
