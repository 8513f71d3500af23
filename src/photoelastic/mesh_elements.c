/* Interpolation inside finite elements with their own shape functions: linear and quadratic
 * triangles (3, 6 nodes) and quadrilaterals (4, 8 and 9 nodes), isoparametric, so curved edges
 * (mid-side nodes off the chord) are followed. Node order as in VTK (and CalculiX, Abaqus,
 * gmsh): the corners in turn, then the mid-side nodes of edges 01, 12, 20 (quads 01, 12, 23, 30),
 * then the centre. Shape functions: Zienkiewicz & Taylor, The Finite Element Method, vol. 1,
 * ch. 6 (serendipity and Lagrange families). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "optics/validate.h"
#include "photoelastic/mesh_internal.h"

int pe_element_node_count(int type)
{
    static const int nn[] = {3, 6, 4, 8, 9};
    return type >= 0 && type < 5 ? nn[type] : 0;
}

int biref_pe_element_nodes(biref_pe_element_type t)
{
    return pe_element_node_count((int)t);
}

static int is_tri(int type)
{
    return type == BIREF_PE_TRI3 || type == BIREF_PE_TRI6;
}

/* Shape functions N and their derivatives in the reference coordinates (r, s): triangles in
 * barycentric form (r = L1, s = L2, L0 = 1 - r - s), quads on [-1, 1]^2 with corners
 * (-1,-1), (1,-1), (1,1), (-1,1). */
static void shape(int type, double r, double s, double N[9], double Nr[9], double Ns[9])
{
    switch (type) {
    case BIREF_PE_TRI3:
        N[0] = 1 - r - s, N[1] = r, N[2] = s;
        Nr[0] = -1, Nr[1] = 1, Nr[2] = 0;
        Ns[0] = -1, Ns[1] = 0, Ns[2] = 1;
        return;
    case BIREF_PE_TRI6: {
        const double l0 = 1 - r - s;
        N[0] = l0 * (2 * l0 - 1), N[1] = r * (2 * r - 1), N[2] = s * (2 * s - 1);
        N[3] = 4 * l0 * r, N[4] = 4 * r * s, N[5] = 4 * s * l0;
        Nr[0] = 1 - 4 * l0, Nr[1] = 4 * r - 1, Nr[2] = 0, Nr[3] = 4 * (l0 - r), Nr[4] = 4 * s, Nr[5] = -4 * s;
        Ns[0] = 1 - 4 * l0, Ns[1] = 0, Ns[2] = 4 * s - 1, Ns[3] = -4 * r, Ns[4] = 4 * r, Ns[5] = 4 * (l0 - s);
        return;
    }
    default: break;
    }
    static const double cr[4] = {-1, 1, 1, -1}, cs[4] = {-1, -1, 1, 1};
    if (type == BIREF_PE_QUAD4 || type == BIREF_PE_QUAD8) {
        for (int i = 0; i < 4; i++) {
            const double a = 1 + cr[i] * r, b = 1 + cs[i] * s;
            if (type == BIREF_PE_QUAD4) {
                N[i] = 0.25 * a * b, Nr[i] = 0.25 * cr[i] * b, Ns[i] = 0.25 * cs[i] * a;
            } else { /* serendipity corner: (1 + r ri)(1 + s si)(r ri + s si - 1)/4 */
                const double c = cr[i] * r + cs[i] * s - 1;
                N[i] = 0.25 * a * b * c;
                Nr[i] = 0.25 * cr[i] * b * (c + a);
                Ns[i] = 0.25 * cs[i] * a * (c + b);
            }
        }
        if (type == BIREF_PE_QUAD8) { /* mid-sides at (0,-1), (1,0), (0,1), (-1,0) */
            N[4] = 0.5 * (1 - r * r) * (1 - s), Nr[4] = -r * (1 - s), Ns[4] = -0.5 * (1 - r * r);
            N[5] = 0.5 * (1 + r) * (1 - s * s), Nr[5] = 0.5 * (1 - s * s), Ns[5] = -s * (1 + r);
            N[6] = 0.5 * (1 - r * r) * (1 + s), Nr[6] = -r * (1 + s), Ns[6] = 0.5 * (1 - r * r);
            N[7] = 0.5 * (1 - r) * (1 - s * s), Nr[7] = -0.5 * (1 - s * s), Ns[7] = -s * (1 - r);
        }
        return;
    }
    /* QUAD9: products of the 1-D quadratic Lagrange polynomials at -1, 0, 1. */
    const double lr[3] = {0.5 * r * (r - 1), 1 - r * r, 0.5 * r * (r + 1)}, dr[3] = {r - 0.5, -2 * r, r + 0.5};
    const double ls[3] = {0.5 * s * (s - 1), 1 - s * s, 0.5 * s * (s + 1)}, ds[3] = {s - 0.5, -2 * s, s + 0.5};
    static const int ir[9] = {0, 2, 2, 0, 1, 2, 1, 0, 1}, is[9] = {0, 0, 2, 2, 0, 1, 2, 1, 1};
    for (int i = 0; i < 9; i++) {
        N[i] = lr[ir[i]] * ls[is[i]];
        Nr[i] = dr[ir[i]] * ls[is[i]];
        Ns[i] = lr[ir[i]] * ds[is[i]];
    }
}

/* Reference coordinates of the affine map: triangles from corners 0, 1, 2; quads from the
 * parallelogram of corners 0, 1, 3 (r, s in [-1, 1]). */
static void affine_ref(const pe_elem *e, double x, double y, double *r, double *s)
{
    const double dx = x - e->x0, dy = y - e->y0;
    *r = e->a * dx + e->b * dy;
    *s = e->c * dx + e->d * dy;
    if (!is_tri(e->type)) {
        *r = 2 * *r - 1;
        *s = 2 * *s - 1;
    }
}

void pe_element_prepare(const biref_pe_mesh *m, pe_elem *e)
{
    const double *p0 = m->xy + 2 * e->v[0], *p1 = m->xy + 2 * e->v[1];
    const double *p2 = m->xy + 2 * e->v[is_tri(e->type) ? 2 : 3];
    const double ax = p1[0] - p0[0], bx = p2[0] - p0[0], ay = p1[1] - p0[1], by = p2[1] - p0[1];
    const double det = ax * by - bx * ay;
    e->x0 = p0[0];
    e->y0 = p0[1];
    e->a = by / det;
    e->b = -bx / det;
    e->c = -ay / det;
    e->d = ax / det;
    /* Affine if every node sits where the affine map puts its reference position. */
    static const double tr[6] = {0, 1, 0, 0.5, 0.5, 0}, ts[6] = {0, 0, 1, 0, 0.5, 0.5};
    static const double qr[9] = {-1, 1, 1, -1, 0, 1, 0, -1, 0}, qs[9] = {-1, -1, 1, 1, -1, 0, 1, 0, 0};
    const int nn = pe_element_node_count(e->type);
    const double tol = 1e-10 * (fabs(ax) + fabs(ay) + fabs(bx) + fabs(by));
    e->affine = 1;
    for (int i = 0; i < nn; i++) {
        double r = is_tri(e->type) ? tr[i] : 0.5 * (qr[i] + 1), s = is_tri(e->type) ? ts[i] : 0.5 * (qs[i] + 1);
        const double *p = m->xy + 2 * e->v[i];
        if (fabs(p0[0] + r * ax + s * bx - p[0]) > tol || fabs(p0[1] + r * ay + s * by - p[1]) > tol) e->affine = 0;
    }
}

/* Newton's method for the reference coordinates of (x, y) under the isoparametric map, from the
 * affine guess. 1 when it converged. */
static int invert_map(const biref_pe_mesh *m, const pe_elem *e, double x, double y, double *r, double *s)
{
    const int nn = pe_element_node_count(e->type);
    double N[9], Nr[9], Ns[9];
    for (int it = 0; it < 40; it++) {
        shape(e->type, *r, *s, N, Nr, Ns);
        double fx = -x, fy = -y, jxr = 0, jxs = 0, jyr = 0, jys = 0;
        for (int i = 0; i < nn; i++) {
            const double *p = m->xy + 2 * e->v[i];
            fx += N[i] * p[0], fy += N[i] * p[1];
            jxr += Nr[i] * p[0], jxs += Ns[i] * p[0], jyr += Nr[i] * p[1], jys += Ns[i] * p[1];
        }
        const double det = jxr * jys - jxs * jyr;
        if (!(fabs(det) > 0)) return 0;
        const double dr = (jys * fx - jxs * fy) / det, ds = (-jyr * fx + jxr * fy) / det;
        *r -= dr, *s -= ds;
        if (!(fabs(*r) < 10 && fabs(*s) < 10)) return 0; /* far outside: not this element */
        /* Newton doubles the digits each step; below 1e-12 the residual is rounding (coordinates
         * carry ~1e-16 relative error, so a step cannot be resolved much below ~1e-14). */
        if (fabs(dr) + fabs(ds) < 1e-12) return 1;
    }
    return 0;
}

int pe_element_stress(const biref_pe_mesh *m, const pe_elem *e, double x, double y, biref_pe_stress *out)
{
    double r, s;
    affine_ref(e, x, y, &r, &s);
    /* A sliver of tolerance keeps points on shared edges and on the outline inside. */
    const double eps = 1e-12, tri = is_tri(e->type);
    if (e->affine) {
        if (tri ? (r < -eps || s < -eps || r + s > 1 + eps) : (fabs(r) > 1 + eps || fabs(s) > 1 + eps)) return 0;
    } else {
        /* A cheap rejection before Newton. The affine guess of a curved triangle is off by its
         * edges' bulge; a quad's guess comes from the parallelogram of three corners, which can
         * put the fourth corner far from (1, 1), so quads get a wide margin. */
        if (tri ? (r < -0.5 || s < -0.5 || r + s > 1.5) : (fabs(r) > 6 || fabs(s) > 6)) return 0;
        if (!invert_map(m, e, x, y, &r, &s)) return 0;
        const double teps = 1e-9;
        if (tri ? (r < -teps || s < -teps || r + s > 1 + teps) : (fabs(r) > 1 + teps || fabs(s) > 1 + teps)) return 0;
    }
    const int nn = pe_element_node_count(e->type);
    double N[9], Nr[9], Ns[9];
    if (e->type == BIREF_PE_TRI3) { /* the linear case in its exact form: barycentrics */
        N[0] = 1.0 - r - s, N[1] = r, N[2] = s;
    } else {
        shape(e->type, r, s, N, Nr, Ns);
    }
    double acc[3] = {0, 0, 0};
    for (int i = 0; i < nn; i++) {
        const double *sv = m->s + 3 * e->v[i];
        acc[0] += N[i] * sv[0], acc[1] += N[i] * sv[1], acc[2] += N[i] * sv[2];
    }
    out->sxx = acc[0];
    out->syy = acc[1];
    out->txy = acc[2];
    return 1;
}

/* Checks and copies the nodes of an element mesh. */
static biref_status copy_nodes(biref_pe_mesh *m, const biref_pe_elements *in, char *msg, size_t msg_len)
{
    if (in->nodes > (size_t)PE_MAX_ELEMENT_NODES)
        return biref_fail(msg, msg_len, "%zu nodes: more than the limit of %ld", in->nodes, PE_MAX_ELEMENT_NODES);
    m->rows = m->n = in->nodes;
    m->xy = malloc((in->nodes ? in->nodes : 1) * 2 * sizeof *m->xy);
    m->s = malloc((in->nodes ? in->nodes : 1) * 3 * sizeof *m->s);
    if (!m->xy || !m->s) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory for %zu nodes", in->nodes);
    for (size_t i = 0; i < in->nodes; i++) {
        for (int c = 0; c < 2; c++)
            if (!(fabs(in->xy[2 * i + c]) <= PE_MAX_COORD_M))
                return biref_fail(msg, msg_len, "node %zu: coordinate %g m is %s", i, in->xy[2 * i + c],
                                  isfinite(in->xy[2 * i + c]) ? "out of range (at most 1000 m)" : "not finite");
        for (int c = 0; c < 3; c++)
            if (!(fabs(in->stress[3 * i + c]) <= PE_MAX_STRESS_PA))
                return biref_fail(msg, msg_len, "node %zu: stress %g Pa is %s", i, in->stress[3 * i + c],
                                  isfinite(in->stress[3 * i + c]) ? "out of range (at most 1e12 Pa)" : "not finite");
    }
    memcpy(m->xy, in->xy, in->nodes * 2 * sizeof *m->xy);
    memcpy(m->s, in->stress, in->nodes * 3 * sizeof *m->s);
    return BIREF_OK;
}

/* Checks and copies the elements: types, node indices, no zero-area corner triangles. */
static biref_status copy_elements(biref_pe_mesh *m, const biref_pe_elements *in, char *msg, size_t msg_len)
{
    m->el = calloc(in->elements, sizeof *m->el);
    if (!m->el) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory for %zu elements", in->elements);
    size_t k = 0;
    for (size_t i = 0; i < in->elements; i++) {
        pe_elem *e = &m->el[i];
        const int nn = pe_element_node_count(in->type[i]);
        if (!nn) return biref_fail(msg, msg_len, "element %zu: unknown type %d", i, in->type[i]);
        e->type = (unsigned char)in->type[i];
        for (int j = 0; j < nn; j++, k++) {
            if (in->conn[k] >= in->nodes)
                return biref_fail(msg, msg_len, "element %zu: node index %zu, but there are %zu nodes", i, in->conn[k],
                                  in->nodes);
            e->v[j] = (int)in->conn[k];
        }
        pe_element_prepare(m, e);
        if (!(isfinite(e->a) && isfinite(e->b) && isfinite(e->c) && isfinite(e->d)))
            return biref_fail(msg, msg_len, "element %zu has no area (its first corners coincide or lie on a line)", i);
    }
    m->nel = in->elements;
    return BIREF_OK;
}

biref_status biref_pe_mesh_from_elements(const biref_pe_elements *in, biref_pe_mesh **out, char *msg, size_t msg_len)
{
    if (!out) return biref_fail(msg, msg_len, "no output");
    *out = NULL;
    if (!in || !in->xy || !in->stress || !in->type || !in->conn) return biref_fail(msg, msg_len, "no nodes or elements");
    if (in->elements == 0) return biref_fail(msg, msg_len, "no elements");
    if (in->elements > (size_t)PE_MAX_ELEMENT_NODES)
        return biref_fail(msg, msg_len, "%zu elements: more than the limit of %ld", in->elements, PE_MAX_ELEMENT_NODES);
    biref_pe_mesh *m = calloc(1, sizeof *m);
    if (!m) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    biref_status st = copy_nodes(m, in, msg, msg_len);
    if (st == BIREF_OK) st = copy_elements(m, in, msg, msg_len);
    if (st == BIREF_OK) st = pe_mesh_buckets(m, msg, msg_len);
    if (st != BIREF_OK) {
        biref_pe_mesh_destroy(m);
        return st;
    }
    *out = m;
    return BIREF_OK;
}
