/* Stress from finite-element nodes: parsing (column mapping, units, separators, one-line errors
 * naming row and column), merging of repeated nodes, the Delaunay triangulation's linear
 * interpolation (exact for linear fields), the hull and the boundary as "no material". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "biref/photoelastic.h"
#include "test_cases.h"

static biref_pe_mesh *parse(const char *text, const biref_pe_node_format *f, char *msg)
{
    biref_pe_node_format d;
    biref_pe_node_format_default(&d);
    biref_pe_mesh *m = NULL;
    if (biref_pe_mesh_parse(text, strlen(text), f ? f : &d, &m, msg, 256) != BIREF_OK) return NULL;
    return m;
}

static void expect_error(const char *text, const char *needle)
{
    char msg[256] = "";
    biref_pe_mesh *m = parse(text, NULL, msg);
    CHECK(m == NULL);
    CHECK(strchr(msg, '\n') == NULL);
    CHECK(strstr(msg, needle) != NULL);
    if (!strstr(msg, needle)) fprintf(stderr, "expected '%s' in '%s'\n", needle, msg);
    biref_pe_mesh_destroy(m);
}

/* A linear field sampled at scattered nodes is reproduced exactly everywhere inside. */
static double lin(int c, double x, double y)
{
    static const double k[3][3] = {{1.5, 0.2, -0.3}, {-0.7, 0.05, 0.4}, {0.25, -0.1, 0.15}};
    return k[c][0] + k[c][1] * x + k[c][2] * y;
}

/* 400 seeded nodes of the linear field in a 20 x 20 square (m, Pa; ';'-separated, an unused
 * column, case-insensitive mapped names) and, at (20, 20), a node repeated with a different
 * stress (element-wise exports repeat nodes). rng continues from the nodes' draws. */
static biref_pe_mesh *scattered_mesh(test_rng *rng)
{
    *rng = (test_rng){12345};
    size_t cap = 1 << 16, n = 0;
    char *t = malloc(cap);
    CHECK(t != NULL);
    if (!t) return NULL;
    n += (size_t)snprintf(t + n, cap - n, "id;X;Y;Sxx;Syy;Sxy;extra\n");
    for (int i = 0; i < 400; i++) {
        double x = test_uniform(rng, -10, 10), y = test_uniform(rng, -10, 10);
        n += (size_t)snprintf(t + n, cap - n, "%d;%.17g;%.17g;%.17g;%.17g;%.17g;zz\n", i, x, y, lin(0, x, y),
                              lin(1, x, y), lin(2, x, y));
    }
    n += (size_t)snprintf(t + n, cap - n, "900;20;20;1;2;3;a\n901;20;20;3;4;5;b\n");
    biref_pe_node_format f = {"X", "Y", "SXX", "syy", "sxy", 1.0, 1.0};
    char msg[256] = "";
    biref_pe_mesh *m = parse(t, &f, msg);
    CHECK(m != NULL);
    if (!m) fprintf(stderr, "%s\n", msg);
    free(t);
    return m;
}

static void linear_field_is_interpolated_exactly(void)
{
    test_rng r;
    biref_pe_mesh *m = scattered_mesh(&r);
    if (!m) return;
    biref_pe_mesh_info info;
    biref_pe_mesh_get_info(m, &info);
    CHECK(info.rows == 402);
    CHECK(info.nodes == 401);
    CHECK(info.triangles > 700);
    double err = 0;
    int inside = 0;
    for (int i = 0; i < 2000; i++) {
        double x = test_uniform(&r, -9, 9), y = test_uniform(&r, -9, 9);
        biref_pe_stress s;
        if (!biref_pe_mesh_stress(m, x, y, &s)) continue;
        inside++;
        err = fmax(err, fabs(s.sxx - lin(0, x, y)) + fabs(s.syy - lin(1, x, y)) + fabs(s.txy - lin(2, x, y)));
    }
    CHECK(inside > 1900);
    CHECK(err < 1e-12);
    biref_pe_mesh_destroy(m);
}

/* The repeated node is one node with the mean stress; beyond the hull there is no material. */
static void repeated_nodes_are_averaged_and_outside_the_hull_is_empty(void)
{
    test_rng r;
    biref_pe_mesh *m = scattered_mesh(&r);
    if (!m) return;
    biref_pe_stress s = {0, 0, 0};
    CHECK(biref_pe_mesh_stress(m, 20, 20, &s) == 1);
    CHECK_NEAR(s.sxx, 2.0, 1e-12);
    CHECK_NEAR(s.txy, 4.0, 1e-12);
    CHECK(biref_pe_mesh_stress(m, -30, 0, &s) == 0);
    biref_pe_mesh_destroy(m);
}

/* Boundary: a 16 x 16 square with a hole of 2 x 2 (even-odd), in mm; malformed outlines. */
static void boundary_loops_mark_holes_and_outside_as_empty(void)
{
    test_rng r;
    biref_pe_mesh *m = scattered_mesh(&r);
    if (!m) return;
    char msg[256] = "";
    biref_pe_stress s;
    const char *b = "x,y\n-8,-8\n8,-8\n8,8\n-8,8\n\n-1,-1\n1,-1\n1,1\n-1,1\n";
    CHECK(biref_pe_mesh_boundary_parse(m, b, strlen(b), 1.0, msg, sizeof msg) == BIREF_OK);
    CHECK(biref_pe_mesh_stress(m, 0, 0, &s) == 0);     /* in the hole */
    CHECK(biref_pe_mesh_stress(m, 1.5, 0.3, &s) == 1); /* material */
    CHECK(biref_pe_mesh_stress(m, 8.5, 0, &s) == 0);   /* outside the outline */
    biref_pe_mesh_info info;
    biref_pe_mesh_get_info(m, &info);
    CHECK(info.loops == 2 && info.loop_vertices == 8);
    CHECK(biref_pe_mesh_boundary_parse(m, "0,0\n1,1\n", 8, 1.0, msg, sizeof msg) != BIREF_OK);
    CHECK(strstr(msg, "at least 3 vertices") != NULL);
    CHECK(biref_pe_mesh_boundary_parse(m, "0,0\n1,x\n2,2\n", 12, 1.0, msg, sizeof msg) != BIREF_OK);
    CHECK(strstr(msg, "line 2, column y: not a number: 'x'") != NULL);
    biref_pe_mesh_destroy(m);
}

/* Units: the same numbers in mm and MPa scale by 1e-3 and 1e6; whitespace separators. */
static void default_units_are_mm_and_mpa_with_whitespace_separators(void)
{
    char msg[256] = "";
    const char *u = "x y sxx syy txy\n0 0 1 0 0\n10 0 1 0 0\n0 10 1 0 0\n";
    biref_pe_mesh *m = parse(u, NULL, msg);
    CHECK(m != NULL);
    if (m) {
        biref_pe_stress s;
        CHECK(biref_pe_mesh_stress(m, 2e-3, 2e-3, &s) == 1);
        CHECK_NEAR(s.sxx, 1e6, 1e-6);
        double bb[4];
        biref_pe_mesh_bounds(m, bb);
        CHECK_NEAR(bb[1], 0.01, 1e-15);
    }
    biref_pe_mesh_destroy(m);
}

static void malformed_files_give_one_line_errors(void)
{
    expect_error("", "empty file");
    expect_error("node,x,y,s11,s22,s12\n1,0,0,1,2,3\n", "the header has no column 'sxx' for sxx");
    expect_error("0,0,1,2,3\n", "line 1: expected a header naming the columns");
    expect_error("x,y,sxx,syy,txy\n0,0,1,2,3\n1,0,1,abc,3\n0,1,1,2,3\n", "line 3, column syy: not a number: 'abc'");
    expect_error("x,y,sxx,syy,txy\n0,0,1,2,3\n1,0,1,nan,3\n0,1,1,2,3\n", "line 3, column syy: not a finite number: 'nan'");
    expect_error("x,y,sxx,syy,txy\n0,0,1,2,3\n1,0,1,,3\n0,1,1,2,3\n", "line 3, column syy: empty field");
    expect_error("x,y,sxx,syy,txy\n0,0,1,2,3\n1,0,1,2\n0,1,1,2,3\n", "line 3: expected 5 fields as in the header, got 4");
    expect_error("x,y,sxx,syy,txy\n0,0,1,2,3\n1,0,1,2,3\n0,1,1,2", "line 4: truncated row (4 of 5 fields");
    expect_error("x,y,sxx,syy,txy\n0,0,1,2,3\n1,0,1,2,3\n", "after 2 data rows");
    expect_error("x,y,sxx,syy,txy\n0,0,1,2,3\n1,1,1,2,3\n2,2,1,2,3\n3,3,1,2,3\n", "cannot triangulate");
    expect_error("x,y,x,syy,txy\n", "column x appears twice");
    expect_error("x,y,sxx,syy,txy\n0,0,1e400,2,3\n", "line 2, column sxx: 1e400 is out of range");
    expect_error("x,y,sxx,syy,txy\n0,0,1e308,2,3\n", "line 2, column sxx: 1e308 is out of range (|stress| at most 1e+12 Pa)");
    expect_error("x,y,sxx,syy,txy\n1e308,0,1,2,3\n", "line 2, column x: 1e308 is out of range");
}

/* A number written with 200 000 digits is still a number; a table beyond the node limit is
 * refused from its row count, before the rows are stored. */
static void long_numbers_read_and_row_limit_refused_early(void)
{
    const char *head = "x,y,sxx,syy,txy\n0,0,1,2,3\n1,0,1,2,3\n0,1,";
    size_t nz = 200000, hl = strlen(head);
    char *t = malloc(hl + nz + 16);
    memcpy(t, head, hl);
    memset(t + hl, '0', nz);
    strcpy(t + hl + nz, ",2,3\n");
    char msg[256] = "";
    biref_pe_mesh *m = parse(t, NULL, msg);
    CHECK(m != NULL);
    if (!m) fprintf(stderr, "200 000-digit zero: %s\n", msg);
    biref_pe_mesh_destroy(m);
    free(t);
    const size_t rows = 2000001;
    t = malloc(16 + rows * 2 + 1);
    strcpy(t, "x,y,sxx,syy,txy\n");
    char *p = t + strlen(t);
    for (size_t i = 0; i < rows; i++) *p++ = '1', *p++ = '\n';
    *p = '\0';
    m = parse(t, NULL, msg);
    CHECK(m == NULL && strstr(msg, "more than 2000000 node rows") != NULL);
    if (!strstr(msg, "more than 2000000 node rows")) fprintf(stderr, "row limit: %s\n", msg);
    free(t);
}

/* The band index of the boundary answers as the plain even-odd count over every edge, on seeded
 * random star polygons with holes and points on a lattice. */
static int brute_inside(const double *xy, const size_t *start, size_t nl, double x, double y)
{
    int in = 0;
    for (size_t l = 0; l < nl; l++)
        for (size_t i = start[l], j = start[l + 1] - 1; i < start[l + 1]; j = i++) {
            const double xi = xy[2 * i], yi = xy[2 * i + 1], xj = xy[2 * j], yj = xy[2 * j + 1];
            if ((yi > y) != (yj > y) && x < xj + (y - yj) * (xi - xj) / (yi - yj)) in = !in;
        }
    return in;
}

static void boundary_index_agrees_with_every_edge_count(void)
{
    char msg[256];
    biref_pe_mesh *m = parse("x,y,sxx,syy,txy\n-30,-30,1,0,0\n30,-30,1,0,0\n30,30,1,0,0\n-30,30,1,0,0\n", NULL, msg);
    CHECK(m != NULL);
    if (!m) return;
    unsigned seed = 12345;
    for (int trial = 0; trial < 6; trial++) {
        const size_t nv[2] = {(size_t)(50 + trial * 400), (size_t)(7 + trial * 3)};
        double xy[2 * 3000];
        size_t start[3] = {0, nv[0], nv[0] + nv[1]};
        char *text = malloc(64 * 3000), *p = text;
        for (int l = 0; l < 2; l++) {
            for (size_t i = 0; i < nv[l]; i++) {
                seed = seed * 1103515245u + 12345u;
                const double u = (seed >> 8) / 16777216.0, ang = 2 * M_PI * i / nv[l];
                const double r = l == 0 ? 20 + 8 * u : 3 + 4 * u;
                const double x = r * cos(ang) + (l ? 2 : 0), y = r * sin(ang);
                xy[2 * (start[l] + i)] = x * 1e-3;
                xy[2 * (start[l] + i) + 1] = y * 1e-3;
                p += sprintf(p, "%.17g,%.17g\n", x, y);
            }
            p += sprintf(p, "\n");
        }
        CHECK(biref_pe_mesh_boundary_parse(m, text, strlen(text), 1e-3, msg, sizeof msg) == BIREF_OK);
        free(text);
        int bad = 0;
        for (int i = 0; i < 121; i++)
            for (int j = 0; j < 121; j++) {
                const double x = (-30 + 0.5 * i + 0.013) * 1e-3, y = (-30 + 0.5 * j + 0.007) * 1e-3;
                biref_pe_stress s;
                bad += biref_pe_mesh_stress(m, x, y, &s) != brute_inside(xy, start, 2, x, y);
            }
        CHECK(bad == 0);
    }
    biref_pe_mesh_destroy(m);
}

static void mapped_column_is_named_with_its_role_in_errors(void)
{
    biref_pe_node_format f;
    biref_pe_node_format_default(&f);
    f.syy = "S22";
    char msg[256] = "";
    biref_pe_mesh *m = parse("x,y,sxx,S22,txy\n0,0,1,2,3\n1,0,1,?,3\n0,1,1,2,3\n", &f, msg);
    CHECK(m == NULL && strstr(msg, "line 3, column S22 (syy): not a number: '?'") != NULL);
    biref_pe_mesh_destroy(m);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"linear_field_is_interpolated_exactly", linear_field_is_interpolated_exactly},
        {"repeated_nodes_are_averaged_and_outside_the_hull_is_empty", repeated_nodes_are_averaged_and_outside_the_hull_is_empty},
        {"boundary_loops_mark_holes_and_outside_as_empty", boundary_loops_mark_holes_and_outside_as_empty},
        {"default_units_are_mm_and_mpa_with_whitespace_separators", default_units_are_mm_and_mpa_with_whitespace_separators},
        {"malformed_files_give_one_line_errors", malformed_files_give_one_line_errors},
        {"mapped_column_is_named_with_its_role_in_errors", mapped_column_is_named_with_its_role_in_errors},
        {"long_numbers_read_and_row_limit_refused_early", long_numbers_read_and_row_limit_refused_early},
        {"boundary_index_agrees_with_every_edge_count", boundary_index_agrees_with_every_edge_count},
    };
    return test_run_cases("test_pe_nodes", cases, TEST_COUNT(cases), argc, argv);
}
