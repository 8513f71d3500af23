/* Locating a point among a mesh's elements: a bucket grid over their bounding boxes (about two
 * elements per cell), the boundary's per-cell classification, and the look-up itself. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "optics/validate.h"
#include "photoelastic/mesh_internal.h"

/* Bounding box of an element's nodes; curved (non-affine) elements are padded by an eighth of
 * their extent, as a quadratic edge may bulge beyond its nodes. */
static void element_box(const biref_pe_mesh *m, const pe_elem *e, double b[4])
{
    b[0] = b[2] = INFINITY;
    b[1] = b[3] = -INFINITY;
    const int nn = pe_element_node_count(e->type);
    for (int k = 0; k < nn; k++) {
        const double *p = m->xy + 2 * e->v[k];
        b[0] = fmin(b[0], p[0]), b[1] = fmax(b[1], p[0]);
        b[2] = fmin(b[2], p[1]), b[3] = fmax(b[3], p[1]);
    }
    if (!e->affine) {
        const double px = 0.125 * (b[1] - b[0]), py = 0.125 * (b[3] - b[2]);
        b[0] -= px, b[1] += px, b[2] -= py, b[3] += py;
    }
}

static int clampi(double v, int hi)
{
    return v < 0 ? 0 : v >= hi ? hi - 1 : (int)v;
}

/* The grid's size and cells from the box and the element count. */
static void grid_geometry(biref_pe_mesh *m)
{
    const double w = m->box[1] - m->box[0], h = m->box[3] - m->box[2];
    double side = sqrt(w * h / fmax(1.0, (double)m->nel / 2.0));
    if (!(side > 0)) side = fmax(w, h);
    m->gx = (int)fmin(4096, fmax(1, ceil(w / side)));
    m->gy = (int)fmin(4096, fmax(1, ceil(h / side)));
    m->cw = w / m->gx;
    m->ch = h / m->gy;
    if (!(m->cw > 0)) m->cw = 1;
    if (!(m->ch > 0)) m->ch = 1;
}

biref_status pe_mesh_buckets(biref_pe_mesh *m, char *msg, size_t msg_len)
{
    m->box[0] = m->box[2] = m->nodes_box[0] = m->nodes_box[2] = INFINITY;
    m->box[1] = m->box[3] = m->nodes_box[1] = m->nodes_box[3] = -INFINITY;
    for (size_t i = 0; i < m->nel; i++) {
        double b[4];
        element_box(m, &m->el[i], b);
        m->box[0] = fmin(m->box[0], b[0]), m->box[1] = fmax(m->box[1], b[1]);
        m->box[2] = fmin(m->box[2], b[2]), m->box[3] = fmax(m->box[3], b[3]);
        const pe_elem *e = &m->el[i];
        for (int k = 0; k < pe_element_node_count(e->type); k++) {
            const double *p = m->xy + 2 * e->v[k];
            m->nodes_box[0] = fmin(m->nodes_box[0], p[0]), m->nodes_box[1] = fmax(m->nodes_box[1], p[0]);
            m->nodes_box[2] = fmin(m->nodes_box[2], p[1]), m->nodes_box[3] = fmax(m->nodes_box[3], p[1]);
        }
    }
    grid_geometry(m);
    const size_t ncell = (size_t)m->gx * m->gy;
    m->cell_start = calloc(ncell + 1, sizeof *m->cell_start);
    if (!m->cell_start) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    size_t *fill = NULL;
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1) {
            for (size_t c = 0; c < ncell; c++) m->cell_start[c + 1] += m->cell_start[c];
            m->cell_el = malloc((m->cell_start[ncell] ? m->cell_start[ncell] : 1) * sizeof *m->cell_el);
            fill = malloc(ncell * sizeof *fill);
            if (!m->cell_el || !fill) {
                free(fill);
                return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
            }
            memcpy(fill, m->cell_start, ncell * sizeof *fill);
        }
        for (size_t i = 0; i < m->nel; i++) {
            double b[4];
            element_box(m, &m->el[i], b);
            const int i0 = clampi(floor((b[0] - m->box[0]) / m->cw), m->gx), i1 = clampi(floor((b[1] - m->box[0]) / m->cw), m->gx);
            const int j0 = clampi(floor((b[2] - m->box[2]) / m->ch), m->gy), j1 = clampi(floor((b[3] - m->box[2]) / m->ch), m->gy);
            for (int j = j0; j <= j1; j++)
                for (int ii = i0; ii <= i1; ii++) {
                    const size_t c = (size_t)j * m->gx + ii;
                    if (pass == 0)
                        m->cell_start[c + 1]++;
                    else
                        m->cell_el[fill[c]++] = (int)i;
                }
        }
    }
    free(fill);
    return BIREF_OK;
}

void biref_pe_mesh_destroy(biref_pe_mesh *m)
{
    if (!m) return;
    free(m->xy);
    free(m->s);
    free(m->el);
    free(m->cell_start);
    free(m->cell_el);
    pe_polygons_free(&m->bnd);
    free(m->cell_in);
    free(m);
}

void biref_pe_mesh_get_info(const biref_pe_mesh *m, biref_pe_mesh_info *out)
{
    memset(out, 0, sizeof *out);
    out->rows = m->rows;
    out->nodes = m->n;
    out->triangles = m->delaunay ? m->nel : 0;
    out->elements = m->nel;
    for (size_t i = 0; i < m->nel; i++) out->by_type[m->el[i].type]++;
    out->loops = m->bnd.nloops;
    out->loop_vertices = m->bnd.nverts;
}

void biref_pe_mesh_bounds(const biref_pe_mesh *m, double b[4])
{
    memcpy(b, m->nodes_box, sizeof m->nodes_box);
}

size_t biref_pe_mesh_nodes_inside(const biref_pe_mesh *m, const double window[4])
{
    size_t k = 0;
    for (size_t i = 0; i < m->n; i++) {
        const double x = m->xy[2 * i], y = m->xy[2 * i + 1];
        if (window && !(x >= window[0] && x <= window[1] && y >= window[2] && y <= window[3])) continue;
        if (m->bnd.nloops && !pe_polygons_inside(&m->bnd, x, y)) continue;
        k++;
    }
    return k;
}

int biref_pe_mesh_stress(const biref_pe_mesh *m, double x, double y, biref_pe_stress *out)
{
    if (!(x >= m->box[0] && x <= m->box[1] && y >= m->box[2] && y <= m->box[3])) return 0;
    int i = (int)((x - m->box[0]) / m->cw), j = (int)((y - m->box[2]) / m->ch);
    if (i >= m->gx) i = m->gx - 1;
    if (j >= m->gy) j = m->gy - 1;
    const size_t c = (size_t)j * m->gx + i;
    if (m->bnd.nloops && (m->cell_in[c] == 0 || (m->cell_in[c] == 2 && !pe_polygons_inside(&m->bnd, x, y)))) return 0;
    for (size_t k = m->cell_start[c]; k < m->cell_start[c + 1]; k++)
        if (pe_element_stress(m, &m->el[m->cell_el[k]], x, y, out)) return 1;
    return 0;
}
