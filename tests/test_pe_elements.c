/* Finite elements with their own shape functions (biref_pe_mesh_from_elements) and CalculiX
 * result files (biref_pe_frd_parse): completeness of each element family (a field of the degree
 * the element spans is reproduced exactly, on straight and on curved elements), holes without a
 * boundary, the frd reader's fixed columns, and one-line refusals. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "biref/photoelastic.h"
#include "test_cases.h"

/* Seeded uniform in [-1, 1]. */
static double rnd(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return ((*s >> 8) / 16777216.0) * 2 - 1;
}

/* Fields in (x, y) in metres: linear and quadratic, three components each. */
static double field(int deg, int c, double x, double y)
{
    const double u = x * 100, v = y * 100;
    const double lin = (1.0 + c) + 0.3 * u - (0.2 + 0.1 * c) * v;
    return deg == 1 ? lin : lin + 0.05 * u * u - 0.07 * u * v + (0.02 * c + 0.03) * v * v;
}

/* One element of a type on the unit-ish reference shape, mapped to a quadrilateral/triangle in
 * metres; mid-side nodes displaced by bend (0: straight) perpendicular to their edge. */
typedef struct {
    double xy[9][2];
    int n, type;
} one_element;

static void make_element(int type, double bend, one_element *e)
{
    static const double tri[6][2] = {{0, 0}, {1, 0}, {0.2, 0.9}, {0.5, 0}, {0.6, 0.45}, {0.1, 0.45}};
    static const double quad[9][2] = {{0, 0}, {1, 0.1}, {1.1, 1}, {-0.1, 0.9}, {0.5, 0.05}, {1.05, 0.55},
                                      {0.5, 0.95}, {-0.05, 0.45}, {0.5, 0.5}};
    e->type = type;
    e->n = biref_pe_element_nodes((biref_pe_element_type)type);
    const int ntri = type == BIREF_PE_TRI3 || type == BIREF_PE_TRI6;
    for (int i = 0; i < e->n; i++) {
        const double *p = ntri ? tri[i] : quad[i];
        e->xy[i][0] = 0.01 * p[0] + 0.003;
        e->xy[i][1] = 0.01 * p[1] - 0.002;
    }
    /* bend the first edge's mid-side node outwards (the node between corners 0 and 1) */
    if (bend != 0 && e->n > 4) e->xy[ntri ? 3 : 4][1] -= 0.01 * bend;
    if (type == BIREF_PE_QUAD9) { /* the centre of a straight element: the bilinear image of (0, 0) */
        e->xy[8][0] = 0.25 * (e->xy[0][0] + e->xy[1][0] + e->xy[2][0] + e->xy[3][0]);
        e->xy[8][1] = 0.25 * (e->xy[0][1] + e->xy[1][1] + e->xy[2][1] + e->xy[3][1]);
    }
}

static biref_pe_mesh *mesh_of(const one_element *e, int deg)
{
    double s[9][3];
    size_t conn[9];
    for (int i = 0; i < e->n; i++) {
        for (int c = 0; c < 3; c++) s[i][c] = field(deg, c, e->xy[i][0], e->xy[i][1]);
        conn[i] = (size_t)i;
    }
    biref_pe_elements el = {(size_t)e->n, &e->xy[0][0], &s[0][0], 1, &e->type, conn};
    biref_pe_mesh *m = NULL;
    char msg[256];
    if (biref_pe_mesh_from_elements(&el, &m, msg, sizeof msg) != BIREF_OK) fprintf(stderr, "%s\n", msg);
    return m;
}

/* Max error of the interpolation against the field at the points of the element's box that lie
 * inside it; *inside counts them. */
static double max_error(const biref_pe_mesh *m, int deg, int *inside)
{
    double b[4], err = 0;
    biref_pe_mesh_bounds(m, b);
    *inside = 0;
    for (int i = 0; i <= 60; i++)
        for (int j = 0; j <= 60; j++) {
            const double x = b[0] + (b[1] - b[0]) * i / 60.0, y = b[2] + (b[3] - b[2]) * j / 60.0;
            biref_pe_stress s;
            if (!biref_pe_mesh_stress(m, x, y, &s)) continue;
            ++*inside;
            err = fmax(err, fabs(s.sxx - field(deg, 0, x, y)));
            err = fmax(err, fabs(s.syy - field(deg, 1, x, y)));
            err = fmax(err, fabs(s.txy - field(deg, 2, x, y)));
        }
    return err;
}

/* Every element reproduces linear fields exactly, straight or curved (isoparametric: the shape
 * functions sum to one and reproduce x and y); the quadratic ones reproduce quadratic fields
 * exactly when straight (affine map). The quadratic field on a linear element is not exact. */
static void each_element_reproduces_the_fields_it_spans(void)
{
    for (int type = 0; type < BIREF_PE_ELEMENT_TYPES; type++) {
        const int quadratic = type == BIREF_PE_TRI6 || type == BIREF_PE_QUAD8 || type == BIREF_PE_QUAD9;
        one_element e;
        int in;
        make_element(type, 0, &e);
        biref_pe_mesh *m = mesh_of(&e, 1);
        CHECK(m && max_error(m, 1, &in) < 1e-12 && in > 500);
        biref_pe_mesh_destroy(m);
        if (type == BIREF_PE_TRI6 || type == BIREF_PE_TRI3) { /* straight-sided: affine */
            m = mesh_of(&e, 2);
            const double err = m ? max_error(m, 2, &in) : 1;
            CHECK(quadratic ? err < 1e-12 : err > 1e-4);
            biref_pe_mesh_destroy(m);
        }
        if (quadratic) {
            make_element(type, 0.12, &e);
            m = mesh_of(&e, 1);
            const double err = m ? max_error(m, 1, &in) : 1;
            CHECK(err < 1e-9 && in > 500);
            if (err >= 1e-9) fprintf(stderr, "type %d curved: linear field error %g\n", type, err);
            biref_pe_mesh_destroy(m);
        }
    }
}

/* On a rectangle the bilinear quad reproduces u v, the serendipity quad u^2 v and the Lagrange
 * quad u^2 v^2: each family's highest term. */
static void rectangles_reproduce_their_highest_terms(void)
{
    const int types[3] = {BIREF_PE_QUAD4, BIREF_PE_QUAD8, BIREF_PE_QUAD9};
    static const double ref[9][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}, {0, 0}};
    for (int t = 0; t < 3; t++) {
        const int n = biref_pe_element_nodes((biref_pe_element_type)types[t]);
        double xy[9][2], s[9][3];
        size_t conn[9];
        for (int i = 0; i < n; i++) {
            xy[i][0] = 0.002 * ref[i][0] + 0.01;
            xy[i][1] = 0.001 * ref[i][1] - 0.004;
            const double u = ref[i][0], v = ref[i][1];
            s[i][0] = u * v;
            s[i][1] = t >= 1 ? u * u * v : u * v;
            s[i][2] = t == 2 ? u * u * v * v : u * v;
            conn[i] = (size_t)i;
        }
        biref_pe_elements el = {(size_t)n, &xy[0][0], &s[0][0], 1, &types[t], conn};
        biref_pe_mesh *m = NULL;
        CHECK(biref_pe_mesh_from_elements(&el, &m, NULL, 0) == BIREF_OK);
        unsigned seed = 7u + (unsigned)t;
        double err = 0;
        for (int k = 0; k < 500 && m; k++) {
            const double u = rnd(&seed), v = rnd(&seed);
            biref_pe_stress st;
            CHECK(biref_pe_mesh_stress(m, 0.002 * u + 0.01, 0.001 * v - 0.004, &st));
            err = fmax(err, fabs(st.sxx - u * v));
            err = fmax(err, fabs(st.syy - (t >= 1 ? u * u * v : u * v)));
            err = fmax(err, fabs(st.txy - (t == 2 ? u * u * v * v : u * v)));
        }
        CHECK(err < 1e-12);
        biref_pe_mesh_destroy(m);
    }
}

/* A ring of four straight quads around a square hole: the hole has no material with no boundary;
 * a point on the bulging side of a curved edge belongs to the element, on its hollow side not. */
static void holes_and_curved_edges_without_a_boundary(void)
{
    const double xy[8][2] = {{-2, -2}, {2, -2}, {2, 2}, {-2, 2}, {-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    double pts[8][2], s[8][3];
    for (int i = 0; i < 8; i++) {
        pts[i][0] = xy[i][0] * 1e-3, pts[i][1] = xy[i][1] * 1e-3;
        s[i][0] = 1, s[i][1] = 2, s[i][2] = 3;
    }
    const int type[4] = {BIREF_PE_QUAD4, BIREF_PE_QUAD4, BIREF_PE_QUAD4, BIREF_PE_QUAD4};
    const size_t conn[16] = {0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7};
    biref_pe_elements el = {8, &pts[0][0], &s[0][0], 4, type, conn};
    biref_pe_mesh *m = NULL;
    CHECK(biref_pe_mesh_from_elements(&el, &m, NULL, 0) == BIREF_OK);
    biref_pe_stress st;
    CHECK(m && !biref_pe_mesh_stress(m, 0, 0, &st) && !biref_pe_mesh_stress(m, 0.9e-3, 0.5e-3, &st));
    CHECK(m && biref_pe_mesh_stress(m, 1.5e-3, 0, &st) && st.syy == 2);
    CHECK(m && biref_pe_mesh_nodes_inside(m, NULL) == 8);
    biref_pe_mesh_destroy(m);
    /* one TRI6 whose edge 01 bulges down by 0.2 mm at its middle */
    const double t6[6][2] = {{0, 0}, {2e-3, 0}, {0, 2e-3}, {1e-3, -0.2e-3}, {1e-3, 1e-3}, {0, 1e-3}};
    double s6[6][3] = {{0}};
    const int tt = BIREF_PE_TRI6;
    const size_t c6[6] = {0, 1, 2, 3, 4, 5};
    biref_pe_elements e6 = {6, &t6[0][0], &s6[0][0], 1, &tt, c6};
    CHECK(biref_pe_mesh_from_elements(&e6, &m, NULL, 0) == BIREF_OK);
    CHECK(m && biref_pe_mesh_stress(m, 1e-3, -0.15e-3, &st));  /* inside the bulge */
    CHECK(m && !biref_pe_mesh_stress(m, 1e-3, -0.25e-3, &st)); /* beyond it */
    biref_pe_mesh_destroy(m);
}

static void bad_elements_are_refused_with_one_line(void)
{
    const double xy[4][2] = {{0, 0}, {1e-3, 0}, {0, 1e-3}, {2e-3, 0}};
    double s[4][3] = {{0}};
    char msg[256];
    biref_pe_mesh *m = NULL;
    const int t3 = BIREF_PE_TRI3, bad = 17;
    const size_t over[3] = {0, 1, 9}, flat[3] = {0, 1, 3}, ok[3] = {0, 1, 2};
    biref_pe_elements e = {4, &xy[0][0], &s[0][0], 1, &t3, over};
    CHECK(biref_pe_mesh_from_elements(&e, &m, msg, sizeof msg) != BIREF_OK && strstr(msg, "node index 9, but there are 4"));
    e.conn = flat;
    CHECK(biref_pe_mesh_from_elements(&e, &m, msg, sizeof msg) != BIREF_OK && strstr(msg, "has no area"));
    e.conn = ok;
    e.type = &bad;
    CHECK(biref_pe_mesh_from_elements(&e, &m, msg, sizeof msg) != BIREF_OK && strstr(msg, "unknown type 17"));
    e.type = &t3;
    s[2][1] = INFINITY;
    CHECK(biref_pe_mesh_from_elements(&e, &m, msg, sizeof msg) != BIREF_OK && strstr(msg, "not finite"));
    CHECK(m == NULL);
}

/* A two-element CalculiX file (long format, values touching in their 12-character fields): the
 * reader takes the last STRESS block, scales units, and refuses solids and missing components. */
static const char FRD[] =
    "    1C\n"
    "    2C                             6                                     1\n"
    " -1         1 0.00000E+00 0.00000E+00 0.00000E+00\n"
    " -1         2 2.00000E+00 0.00000E+00 0.00000E+00\n"
    " -1         3 2.00000E+00 2.00000E+00 0.00000E+00\n"
    " -1         4 0.00000E+00 2.00000E+00 0.00000E+00\n"
    " -1         5-1.00000E+00 1.00000E+00 0.00000E+00\n"
    " -1         6 1.00000E+00 1.00000E+00 0.00000E+00\n"
    " -3\n"
    "    3C                             2                                     1\n"
    " -1         1    9    0    1\n"
    " -2         1         2         3         4\n"
    " -1         2    7    0    1\n"
    " -2         1         4         5\n"
    " -3\n"
    "  100CL  101 1.000000000           6                     0    1           1\n"
    " -4  STRESS      6    1\n"
    " -5  SXX         1    4    1    1\n -5  SYY         1    4    2    2\n -5  SZZ         1    4    3    3\n"
    " -5  SXY         1    4    1    2\n -5  SYZ         1    4    2    3\n -5  SZX         1    4    3    1\n"
    " -1         1 9.00000E+00 9.00000E+00 0.00000E+00 9.00000E+00 0.00000E+00 0.00000E+00\n"
    " -3\n"
    "  100CL  101 2.000000000           6                     0    1           1\n"
    " -4  STRESS      6    1\n"
    " -5  SXX         1    4    1    1\n -5  SYY         1    4    2    2\n -5  SZZ         1    4    3    3\n"
    " -5  SXY         1    4    1    2\n -5  SYZ         1    4    2    3\n -5  SZX         1    4    3    1\n"
    " -1         1 1.00000E+00-2.00000E+00 0.00000E+00 3.00000E+00 0.00000E+00 0.00000E+00\n"
    " -1         2 1.00000E+00-2.00000E+00 0.00000E+00 3.00000E+00 0.00000E+00 0.00000E+00\n"
    " -1         3 1.00000E+00-2.00000E+00 0.00000E+00 3.00000E+00 0.00000E+00 0.00000E+00\n"
    " -1         4 1.00000E+00-2.00000E+00 0.00000E+00 3.00000E+00 0.00000E+00 0.00000E+00\n"
    " -1         5 1.00000E+00-2.00000E+00 0.00000E+00 3.00000E+00 0.00000E+00 0.00000E+00\n"
    " -1         6 5.00000E+00-5.00000E+00 0.00000E+00 5.00000E+00 0.00000E+00 0.00000E+00\n"
    " -3\n"
    "9999\n";

static void frd_reader_takes_the_last_stress_block(void)
{
    biref_pe_frd_format f;
    biref_pe_frd_format_default(&f);
    biref_pe_mesh *m = NULL;
    char msg[256] = "";
    CHECK(biref_pe_frd_parse(FRD, strlen(FRD), &f, &m, msg, sizeof msg) == BIREF_OK);
    if (!m) {
        fprintf(stderr, "%s\n", msg);
        return;
    }
    biref_pe_mesh_info info;
    biref_pe_mesh_get_info(m, &info);
    CHECK(info.nodes == 6 && info.elements == 2 && info.by_type[BIREF_PE_QUAD4] == 1 && info.by_type[BIREF_PE_TRI3] == 1);
    biref_pe_stress s;
    CHECK(biref_pe_mesh_stress(m, 1e-3, 1e-3, &s) && fabs(s.sxx - 1e6) < 1e-6 && fabs(s.syy + 2e6) < 1e-6 &&
          fabs(s.txy - 3e6) < 1e-6);
    CHECK(biref_pe_mesh_stress(m, -0.5e-3, 1e-3, &s));  /* the triangle */
    CHECK(!biref_pe_mesh_stress(m, 1e-3, 2.5e-3, &s)); /* outside both */
    biref_pe_mesh_destroy(m);
    /* the same as a solid: one line saying what to export */
    char *solid = strdup(FRD);
    memcpy(strstr(solid, " -1         1    9"), " -1         1    3", 18); /* te4 */
    CHECK(biref_pe_frd_parse(solid, strlen(solid), &f, &m, msg, sizeof msg) != BIREF_OK && strstr(msg, "3-D solid") &&
          strstr(msg, "plane-stress") && !strchr(msg, '\n'));
    free(solid);
    f.txy = "TXY";
    CHECK(biref_pe_frd_parse(FRD, strlen(FRD), &f, &m, msg, sizeof msg) != BIREF_OK && strstr(msg, "SXX, SYY, TXY"));
    CHECK(biref_pe_frd_parse("hello\n", 6, &f, &m, msg, sizeof msg) != BIREF_OK && strstr(msg, "no nodes block"));
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"each_element_reproduces_the_fields_it_spans", each_element_reproduces_the_fields_it_spans},
        {"rectangles_reproduce_their_highest_terms", rectangles_reproduce_their_highest_terms},
        {"holes_and_curved_edges_without_a_boundary", holes_and_curved_edges_without_a_boundary},
        {"bad_elements_are_refused_with_one_line", bad_elements_are_refused_with_one_line},
        {"frd_reader_takes_the_last_stress_block", frd_reader_takes_the_last_stress_block},
    };
    return test_run_cases("test_pe_elements", cases, TEST_COUNT(cases), argc, argv);
}
