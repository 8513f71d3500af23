/* The finite-element mesh behind biref_pe_mesh: nodes with nodal stresses, elements (Delaunay
 * triangles of a node table, or a solver's own elements), a bucket grid locating them, and an
 * optional boundary. Split by concern: mesh_table.c (node tables), mesh_delaunay.c (qhull),
 * mesh_elements.c (element interpolation), mesh_locate.c (buckets, look-up), mesh_boundary.c
 * (polygons and their index), frd.c (CalculiX results). */
#ifndef BIREF_PHOTOELASTIC_MESH_INTERNAL_H
#define BIREF_PHOTOELASTIC_MESH_INTERNAL_H

#include <stddef.h>

#include "biref/photoelastic.h"

/* Node-count limits, checked before anything is allocated for the nodes. A node table is
 * triangulated by qhull, measured at about 24 s and 1.9 GB per million nodes on a lattice (the
 * cocircular worst case): 2 million keep a run within a minute and 4 GB. A solver's own elements
 * need no triangulation (about 150 bytes per node with its elements): 50 million fit in 24 GiB. */
#define PE_MAX_TABLE_NODES 2000000L
#define PE_MAX_ELEMENT_NODES 50000000L
#define PE_MAX_FILE_BYTES ((size_t)1 << 31)
/* Coordinates and stresses beyond these are refused as out of range (a plate a kilometre wide, a
 * stress of 1 TPa: no photoelastic specimen; far inside the double range). */
#define PE_MAX_COORD_M 1e3
#define PE_MAX_STRESS_PA 1e12

typedef struct {
    unsigned char type;  /* biref_pe_element_type */
    unsigned char affine; /* straight edges, mid-side nodes at the midpoints: the map is affine */
    int v[9];             /* node indices, VTK order */
    double x0, y0;        /* first corner */
    double a, b, c, d;    /* inverse of the corner triangle's edge matrix (triangles) */
} pe_elem;

/* Boundary polygons with an index over y: band k of nb (height bh from y0) lists the edges whose
 * y-range meets it, so a crossing count looks at a few edges instead of all. */
typedef struct {
    size_t nloops, nverts;
    size_t *loop_start; /* nloops + 1 */
    double *xy;
    int nb;
    double y0, bh;
    size_t *band_start; /* nb + 1 */
    size_t *band_edge;  /* edge i runs from vertex i to the loop's next vertex */
    size_t *next;       /* per vertex: the loop's next vertex */
} pe_polygons;

struct biref_pe_mesh {
    size_t rows, n;
    double *xy; /* [n][2] m */
    double *s;  /* [n][3] Pa */
    size_t nel;
    pe_elem *el;
    int delaunay;  /* elements are qhull's triangles of a node table */
    double box[4];   /* xmin, xmax, ymin, ymax of the buckets (curved elements padded) */
    double nodes_box[4]; /* of the elements' nodes: the part's extent */
    /* Element buckets on a gx x gy grid over box (CSR). */
    int gx, gy;
    double cw, ch;
    size_t *cell_start;
    int *cell_el;
    pe_polygons bnd; /* nloops = 0: no boundary */
    /* Per bucket cell: 1 all inside the boundary, 0 all outside, 2 crossed by it (test points). */
    unsigned char *cell_in;
};

/* A node row of a table: position (m), stress (Pa), line. */
typedef struct {
    double x, y, s[3];
    long line;
} pe_node_row;

/* Sorts rows, merges coincident ones (stresses averaged) into m->xy, m->s; m->rows, m->n. */
biref_status pe_mesh_nodes_from_rows(biref_pe_mesh *m, pe_node_row *rows, size_t n, char *msg, size_t msg_len);
/* Delaunay triangles of m's nodes as TRI3 elements, then the buckets. */
biref_status pe_mesh_triangulate(biref_pe_mesh *m, char *msg, size_t msg_len);
/* The bucket grid over m's elements (box from their nodes). */
biref_status pe_mesh_buckets(biref_pe_mesh *m, char *msg, size_t msg_len);
/* Node count of an element type (0 for an unknown type). */
int pe_element_node_count(int type);
/* Fills the affine data of an element from its nodes. */
void pe_element_prepare(const biref_pe_mesh *m, pe_elem *e);
/* Interpolates the stress at (x, y) if it lies in element e: 1 and *out, else 0. */
int pe_element_stress(const biref_pe_mesh *m, const pe_elem *e, double x, double y, biref_pe_stress *out);
/* Boundary: even-odd inside test and the per-cell classification. */
int pe_polygons_inside(const pe_polygons *p, double x, double y);
void pe_polygons_free(pe_polygons *p);

#endif
