/* Photoelasticity: stress fields (boundary conditions, equilibrium, textbook values), the CSV
 * grid (interpolation and every kind of malformed file), the polariscope, and the fast path
 * against the general path (expansion / closed-form Jones matrix) and against ground-truth
 * numeric integration; fringe positions on the disk's diameter; isoclinics. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"
#include "test_cases.h"

static const double MM = 1e-3, MPA = 1e6;
static biref_spectral *sp;

/* Divergence of a stress field by central differences: (d sxx/dx + d txy/dy, d txy/dx + d syy/dy). */
typedef void (*field_fn)(const void *ctx, double x, double y, biref_pe_stress *s);

static void divergence(field_fn fn, const void *ctx, double x, double y, double h, double out[2])
{
    biref_pe_stress xp, xm, yp, ym;
    fn(ctx, x + h, y, &xp);
    fn(ctx, x - h, y, &xm);
    fn(ctx, x, y + h, &yp);
    fn(ctx, x, y - h, &ym);
    out[0] = (xp.sxx - xm.sxx) / (2 * h) + (yp.txy - ym.txy) / (2 * h);
    out[1] = (xp.txy - xm.txy) / (2 * h) + (yp.syy - ym.syy) / (2 * h);
}

typedef struct {
    double R, h, P;
} disk_ctx;
static void disk_fn(const void *c, double x, double y, biref_pe_stress *s)
{
    const disk_ctx *d = c;
    biref_pe_disk_stress(d->R, d->h, d->P, x, y, s);
}
typedef struct {
    double a, S;
} hole_ctx;
static void hole_fn(const void *c, double x, double y, biref_pe_stress *s)
{
    const hole_ctx *d = c;
    biref_pe_kirsch_stress(d->a, d->S, x, y, s);
}

/* Traction sigma . n on a surface with unit normal n. */
static void traction(const biref_pe_stress *s, double nx, double ny, double t[2])
{
    t[0] = s->sxx * nx + s->txy * ny;
    t[1] = s->txy * nx + s->syy * ny;
}

static void material_presets_are_valid_and_unknown_names_refused(void)
{
    biref_pe_material m;
    CHECK(biref_pe_material_preset("polycarbonate", &m) == BIREF_OK);
    CHECK_NEAR(biref_pe_fringe_constant(&m, 546.1), 7.0e3, 0.05e3); /* f = lambda / C, N/m */
    CHECK(biref_pe_material_preset("unobtainium", &m) == BIREF_ERR_INVALID);
    for (size_t i = 0; i < biref_pe_material_count(); i++)
        CHECK(biref_pe_material_check(biref_pe_material_at(i), NULL, 0) == BIREF_OK);
}

/* Disk: R = 25 mm, h = 6 mm, P = 500 N. Scale of the stresses: P / (pi R h). */
static const disk_ctx DISK = {25e-3, 6e-3, 500};
static double disk_unit(void) { return DISK.P / (M_PI * DISK.R * DISK.h); }

/* One seeded sequence (seed 7) serves the disk's equilibrium (200 points, 2 draws each), then
 * the hole's (360 radii), then the principal stresses (1000 x 3): each case skips the draws of
 * the ones before it. */
enum { FIELD_SEED = 7, DISK_DRAWS = 400, KIRSCH_DRAWS = 360 };

static void disk_centre_rim_and_resultant(void)
{
    const disk_ctx d = DISK;
    const double unit = disk_unit();
    biref_pe_stress s;
    biref_pe_disk_stress(d.R, d.h, d.P, 0, 0, &s);
    /* Textbook centre values: sxx = 2P/(pi D h), syy = -6P/(pi D h). */
    CHECK_NEAR(s.sxx, 2 * d.P / (M_PI * 2 * d.R * d.h), 1e-9 * unit);
    CHECK_NEAR(s.syy, -6 * d.P / (M_PI * 2 * d.R * d.h), 1e-9 * unit);
    CHECK_NEAR(s.txy, 0, 1e-9 * unit);
    /* Traction-free rim away from the load points. */
    double worst = 0;
    for (int i = 0; i < 360; i++) {
        double th = (i + 0.5) * M_PI / 180.0;
        if (fabs(cos(th)) < 0.02) continue; /* within ~1 deg of a load point */
        double nx = cos(th), ny = sin(th), t[2];
        biref_pe_disk_stress(d.R, d.h, d.P, d.R * nx, d.R * ny, &s);
        traction(&s, nx, ny, t);
        worst = fmax(worst, fmax(fabs(t[0]), fabs(t[1])) / unit);
    }
    CHECK(worst < 1e-9);
    /* Resultant across the horizontal diameter: h * integral of syy dx = -P (Simpson). */
    {
        const int n = 20000;
        double sum = 0;
        for (int i = 0; i <= n; i++) {
            double x = -d.R + 2 * d.R * i / n;
            biref_pe_disk_stress(d.R, d.h, d.P, x, 0, &s);
            sum += (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2)) * s.syy;
        }
        double F = d.h * sum * (2 * d.R / n) / 3;
        CHECK_NEAR(F, -d.P, 1e-9 * d.P);
    }
}

/* Equilibrium inside: the divergence of the stress vanishes. */
static void disk_is_in_equilibrium(void)
{
    const disk_ctx d = DISK;
    const double unit = disk_unit();
    test_rng rng = {FIELD_SEED};
    double wdiv = 0;
    for (int i = 0; i < 200; i++) {
        double r = d.R * sqrt(test_uniform(&rng, 0, 0.8)), a = test_uniform(&rng, 0, 2 * M_PI), dv[2];
        divergence(disk_fn, &d, r * cos(a), r * sin(a), 1e-6 * d.R, dv);
        wdiv = fmax(wdiv, fmax(fabs(dv[0]), fabs(dv[1])) * d.R / unit);
    }
    CHECK(wdiv < 1e-5);
}

/* The hole in a plate under tension (Kirsch). */
static void kirsch_hole_concentration_traction_and_equilibrium(void)
{
    test_rng rng = {FIELD_SEED};
    test_skip(&rng, DISK_DRAWS);
    biref_pe_stress s;
    hole_ctx k = {5 * MM, 4 * MPA};
    biref_pe_kirsch_stress(k.a, k.S, 0, k.a, &s);
    CHECK_NEAR(s.sxx, 3 * k.S, 1e-9 * k.S); /* stress concentration factor 3 */
    biref_pe_kirsch_stress(k.a, k.S, k.a, 0, &s);
    CHECK_NEAR(s.syy, -k.S, 1e-9 * k.S);
    biref_pe_kirsch_stress(k.a, k.S, 1e4 * k.a, 3e4 * k.a, &s);
    CHECK_NEAR(s.sxx, k.S, 1e-6 * k.S);
    CHECK_NEAR(s.syy, 0, 1e-6 * k.S);
    CHECK_NEAR(s.txy, 0, 1e-6 * k.S);
    double worst = 0, wdiv = 0;
    for (int i = 0; i < 360; i++) {
        double th = (i + 0.25) * M_PI / 180.0, nx = cos(th), ny = sin(th), t[2], dv[2];
        biref_pe_kirsch_stress(k.a, k.S, k.a * nx, k.a * ny, &s);
        traction(&s, nx, ny, t);
        worst = fmax(worst, fmax(fabs(t[0]), fabs(t[1])) / k.S);
        double r = k.a * test_uniform(&rng, 1.05, 6);
        divergence(hole_fn, &k, r * nx, r * ny, 1e-6 * k.a, dv);
        wdiv = fmax(wdiv, fmax(fabs(dv[0]), fabs(dv[1])) * k.a / k.S);
    }
    CHECK(worst < 1e-12);
    CHECK(wdiv < 1e-5);
}

/* Beam: extreme fibre stress 6 M / (h H^2). */
static void beam_extreme_fibre_stress(void)
{
    biref_pe_stress s;
    biref_pe_beam_stress(20 * MM, 6 * MM, 2.0, 0, 10 * MM, &s);
    CHECK_NEAR(s.sxx, 6 * 2.0 / (6 * MM * 400 * MM * MM), 1e-6);
    CHECK(s.syy == 0 && s.txy == 0);
}

/* Principal stresses: eigen-pairs, ordering, the angle's range. */
static void principal_stresses_are_ordered_eigenpairs(void)
{
    test_rng rng = {FIELD_SEED};
    test_skip(&rng, DISK_DRAWS + KIRSCH_DRAWS);
    for (int i = 0; i < 1000; i++) {
        biref_pe_stress t = {test_uniform(&rng, -50, 50) * MPA, test_uniform(&rng, -50, 50) * MPA,
                             test_uniform(&rng, -50, 50) * MPA};
        biref_pe_principal p;
        biref_pe_principal_of(&t, &p);
        CHECK(p.s1 >= p.s2);
        CHECK(p.phi > -M_PI / 2 && p.phi <= M_PI / 2);
        double c = cos(p.phi), sn = sin(p.phi);
        CHECK_NEAR(t.sxx * c + t.txy * sn, p.s1 * c, 1e-6);
        CHECK_NEAR(t.txy * c + t.syy * sn, p.s1 * sn, 1e-6);
        CHECK_NEAR(cos(2 * p.phi), p.cos2phi, 1e-12);
        CHECK_NEAR(sin(2 * p.phi), p.sin2phi, 1e-12);
    }
}

/* ------------------------------------------------------------------------- */

static biref_status parse(const char *text, biref_pe_grid **g, char *msg)
{
    return biref_pe_grid_parse(text, strlen(text), g, msg, 256);
}

static void expect_csv_error(const char *what, const char *text, const char *needle)
{
    biref_pe_grid *g = NULL;
    char msg[256] = "";
    biref_status s = parse(text, &g, msg);
    CHECK(s == BIREF_ERR_INVALID);
    CHECK(g == NULL);
    CHECK(strchr(msg, '\n') == NULL);
    CHECK(strstr(msg, needle) != NULL);
    if (!strstr(msg, needle)) fprintf(stderr, "CSV %s: message '%s' lacks '%s'\n", what, msg, needle);
}

static const char *const CSV_HEADER = "x_mm,y_mm,sxx_MPa,syy_MPa,txy_MPa\n";

/* A linear field is reproduced exactly by bilinear interpolation; rows in any order, columns
 * in any order, comments, CR LF. */
static void grid_interpolates_linear_field_exactly(void)
{
    char *buf = malloc(1 << 16);
    size_t n = 0;
    n += (size_t)sprintf(buf + n, "# linear test field\r\nsyy_MPa, x_mm,y_mm,txy_MPa,sxx_MPa\r\n");
    for (int j = 4; j >= 0; j--)
        for (int i = 0; i < 7; i++) {
            double x = -3 + i * 0.5, y = 1 + j * 2.0;
            n += (size_t)sprintf(buf + n, "%.17g,%.17g,%.17g,%.17g,%.17g\r\n", 2 * x - y, x, y, 0.5 * x * 0 + 3 * y,
                                 x + 4 * y + 1);
        }
    biref_pe_grid *g = NULL;
    char msg[256];
    CHECK(biref_pe_grid_parse(buf, n, &g, msg, sizeof msg) == BIREF_OK);
    if (g) {
        int nx, ny;
        biref_pe_grid_size(g, &nx, &ny);
        CHECK(nx == 7 && ny == 5);
        double b[4];
        biref_pe_grid_bounds(g, b);
        CHECK_NEAR(b[0], -3 * MM, 1e-15);
        CHECK_NEAR(b[1], 0 * MM, 1e-15);
        CHECK_NEAR(b[2], 1 * MM, 1e-15);
        CHECK_NEAR(b[3], 9 * MM, 1e-15);
        test_rng r = {99};
        for (int t = 0; t < 200; t++) {
            double x = test_uniform(&r, -3, 0), y = test_uniform(&r, 1, 9);
            biref_pe_stress s;
            CHECK(biref_pe_grid_stress(g, x * MM, y * MM, &s) == 1);
            CHECK_NEAR(s.sxx, (x + 4 * y + 1) * MPA, 1e-6);
            CHECK_NEAR(s.syy, (2 * x - y) * MPA, 1e-6);
            CHECK_NEAR(s.txy, 3 * y * MPA, 1e-6);
        }
        biref_pe_stress s;
        CHECK(biref_pe_grid_stress(g, 0.1 * MM, 5 * MM, &s) == 0);
        CHECK(biref_pe_grid_stress(g, -1 * MM, 9.01 * MM, &s) == 0);
        biref_pe_grid_destroy(g);
    }
    free(buf);
}

static void malformed_csv_gives_one_line_errors(void)
{
    const char *H = CSV_HEADER;
    char t[1024];
    expect_csv_error("empty", "", "empty file");
    expect_csv_error("comments only", "# nothing\n\n", "empty file");
    expect_csv_error("no header", "0,0,1,2,3\n1,0,1,2,3\n", "line 1: expected the header");
    expect_csv_error("missing column", "x_mm,y_mm,sxx_MPa,syy_MPa\n0,0,1,2\n", "line 1: the header lacks column txy_MPa");
    expect_csv_error("unknown column", "x_mm,y_mm,sxx_MPa,syy_MPa,tau\n", "line 1: unknown column 'tau'");
    expect_csv_error("duplicate column", "x_mm,x_mm,sxx_MPa,syy_MPa,txy_MPa\n", "line 1: column x_mm appears twice");
    snprintf(t, sizeof t, "%s0,0,1,2,3\n1,0,1,2\n0,1,1,2,3\n1,1,1,2,3\n", H);
    expect_csv_error("short row", t, "line 3: expected 5 comma-separated fields, got 4");
    snprintf(t, sizeof t, "%s0,0,1,2,3\n1,0,1,2,3,4\n", H);
    expect_csv_error("long row", t, "line 3: expected 5 comma-separated fields, got 6");
    snprintf(t, sizeof t, "%s0,0,1,2,3\n1,0,abc,2,3\n0,1,1,2,3\n1,1,1,2,3\n", H);
    expect_csv_error("non-numeric", t, "line 3, column sxx_MPa: not a number: 'abc'");
    snprintf(t, sizeof t, "%s0,0,1,2,3\n1,0,1,2,3\n0,1,1,NaN,3\n1,1,1,2,3\n", H);
    expect_csv_error("NaN", t, "line 4, column syy_MPa: not a finite number: 'NaN'");
    snprintf(t, sizeof t, "%s0,0,1,2,3\n1,0,1,2,3\n0,1,1,2,inf\n", H);
    expect_csv_error("inf", t, "line 4, column txy_MPa: not a finite number");
    snprintf(t, sizeof t, "%s0,0,1,2,3\n1,0,1e999,2,3\n", H);
    expect_csv_error("overflow", t, "line 3, column sxx_MPa: not a finite number");
    snprintf(t, sizeof t, "%s0,0,1,,3\n", H);
    expect_csv_error("empty field", t, "line 2, column syy_MPa: empty field");
    snprintf(t, sizeof t, "%s0,0,1,2,3\n1,0,1,2,3\n0,1,1,2,3\n", H);
    expect_csv_error("too few rows", t, "line 4: the file ends after 3 data rows");
    snprintf(t, sizeof t, "%s0,0,1,2,3\n1,0,1,2,3\n0,1,1,2,3\n1,1,1,", H);
    expect_csv_error("truncated", t, "line 5: truncated row (4 of 5 fields, and the file ends there)");
    snprintf(t, sizeof t, "%s0,0,1,2,3\n1,0,1,2,3\n2.2,0,1,2,3\n0,1,1,2,3\n1,1,1,2,3\n2.2,1,1,2,3\n", H);
    expect_csv_error("irregular x", t, "is not on a regular grid");
    snprintf(t, sizeof t, "%s0,0,1,2,3\n1,0,1,2,3\n1.01,0,1,2,3\n0,1,1,2,3\n1,1,1,2,3\n1.01,1,1,2,3\n", H);
    expect_csv_error("stray x", t, "line 4: x_mm = 1.01 is not on a regular grid");
    snprintf(t, sizeof t, "%s0,0,1,2,3\n1,0,1,2,3\n1.5,0,1,2,3\n0,1,1,2,3\n1,1,1,2,3\n1.5,1,1,2,3\n", H);
    expect_csv_error("gap in x", t, "line 3: x_mm = 1 follows 0 with a gap of 1, but other values are 0.5 apart");
    snprintf(t, sizeof t, "%s0,0,1,2,3\n1,0,1,2,3\n0,1,1,2,3\n1,1,1,2,3\n1,1,5,5,5\n", H);
    expect_csv_error("duplicate node", t, "line 6: node x_mm = 1, y_mm = 1 repeats line 5");
    snprintf(t, sizeof t, "%s0,0,1,2,3\n1,0,1,2,3\n2,0,1,2,3\n0,1,1,2,3\n1,1,1,2,3\n", H);
    expect_csv_error("missing node", t, "no row for the node x_mm = 2, y_mm = 1");
    snprintf(t, sizeof t, "%s0,0,1,2,3\n0,1,1,2,3\n0,2,1,2,3\n0,3,1,2,3\n", H);
    expect_csv_error("one column of nodes", t, "all rows have x_mm = 0");
}

/* Rounded coordinates, no final newline, a byte-order mark and quoted names are all accepted. */
static void csv_export_variants_are_accepted(void)
{
    const char *H = CSV_HEADER;
    char t[1024], msg[256];
    biref_pe_grid *g = NULL;
    /* Rounded coordinates (6 digits, spacing 85.6 / 43) are still a regular grid. */
    {
        size_t m = (size_t)snprintf(t, sizeof t, "%s", H);
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 4; i++) m += (size_t)snprintf(t + m, sizeof t - m, "%.6f,%d,1,2,3\n", -42.8 + i * 85.6 / 43, j);
        CHECK(parse(t, &g, msg) == BIREF_OK);
        biref_pe_grid_destroy(g);
        g = NULL;
    }
    /* A complete last row without a newline is fine. */
    snprintf(t, sizeof t, "%s0,0,1,2,3\n1,0,1,2,3\n0,1,1,2,3\n1,1,1,2,3", H);
    CHECK(parse(t, &g, msg) == BIREF_OK);
    biref_pe_grid_destroy(g);
    /* A byte-order mark and quoted column names (spreadsheet exports) are accepted. */
    snprintf(t, sizeof t, "\xEF\xBB\xBF\"x_mm\",\"y_mm\",sxx_MPa,syy_MPa,txy_MPa\n0,0,1,2,3\n1,0,1,2,3\n0,1,1,2,3\n1,1,1,2,3\n");
    CHECK(parse(t, &g, msg) == BIREF_OK);
    biref_pe_grid_destroy(g);
}

static void missing_csv_file_is_an_io_error(void)
{
    biref_pe_grid *g = NULL;
    char msg[256];
    CHECK(biref_pe_grid_load("/nonexistent/stress.csv", &g, msg, sizeof msg) == BIREF_ERR_IO);
    CHECK(strstr(msg, "cannot read") != NULL);
}

/* ------------------------------------------------------------------------- */

static void random_principal(test_rng *r, double dsigma_max, biref_pe_principal *p)
{
    biref_pe_stress s = {test_uniform(r, -1, 1), test_uniform(r, -1, 1), test_uniform(r, -1, 1)};
    biref_pe_principal q;
    biref_pe_principal_of(&s, &q);
    double scale = test_uniform(r, 0, dsigma_max) / (q.s1 - q.s2);
    s.sxx *= scale;
    s.syy *= scale;
    s.txy *= scale;
    biref_pe_principal_of(&s, p);
}

static void setup_for(biref_pe_setup *s, const char *mat, double h_mm, double eta_i, biref_pe_polariscope_kind k,
                      biref_pe_field_type f, double psi, biref_pe_light_kind light, double lambda)
{
    memset(s, 0, sizeof *s);
    CHECK(biref_pe_material_preset(mat, &s->material) == BIREF_OK);
    s->thickness = h_mm * MM;
    s->eta_i = eta_i < 0 ? s->material.n0 : eta_i;
    biref_pe_polariscope_make(k, f, psi, &s->pol);
    s->light = light;
    s->lambda_nm = lambda;
}

static void polariscope_backgrounds_and_custom_refusals(void)
{
    /* Backgrounds without a specimen. */
    biref_pe_polariscope pol;
    for (int k = 0; k < 2; k++) {
        biref_pe_polariscope_make((biref_pe_polariscope_kind)k, BIREF_PE_DARK, 0.3, &pol);
        CHECK_NEAR(biref_pe_polariscope_background(&pol), 0.0, 1e-15);
        biref_pe_polariscope_make((biref_pe_polariscope_kind)k, BIREF_PE_LIGHT, 0.3, &pol);
        CHECK_NEAR(biref_pe_polariscope_background(&pol), 1.0, 1e-15);
    }
    const double P_bad[2][2] = {{1, 0}, {0, 1}};
    double complex Pb[2][2] = {{P_bad[0][0], P_bad[0][1]}, {P_bad[1][0], P_bad[1][1]}};
    const double stokes[4] = {1, 0, 0, 1};
    CHECK(biref_pe_polariscope_custom(stokes, Pb, &pol) == BIREF_ERR_INVALID);
    const double bad_stokes[4] = {1, 1, 1, 0};
    biref_analyzer_linear(0, Pb);
    CHECK(biref_pe_polariscope_custom(bad_stokes, Pb, &pol) == BIREF_ERR_INVALID);
}

/* The index-matched points draw 7 numbers each; the in-air case continues the sequence. */
enum { MONO_SEED = 2024, MONO_MATCHED_POINTS = 2000, MONO_MATCHED_DRAWS = 7 * MONO_MATCHED_POINTS };

static void mono_index_matched_matches_closed_forms(void)
{
    test_rng rng = {MONO_SEED};
    /* Circular dark field, index-matched surround (no reflections): I = sin^2(pi N) exactly. */
    double worst_circ = 0, worst_plane = 0, worst_gen = 0, worst_iso = 0;
    for (int t = 0; t < MONO_MATCHED_POINTS; t++) {
        biref_pe_setup s;
        const char *mats[] = {"polycarbonate", "epoxy", "pmma", "glass"};
        double lambda = test_uniform(&rng, 400, 700);
        setup_for(&s, mats[t % 4], test_uniform(&rng, 0.5, 12), -1, BIREF_PE_CIRCULAR, BIREF_PE_DARK, 0,
                  BIREF_PE_MONO, lambda);
        biref_pe_principal p;
        random_principal(&rng, 8 * lambda * 1e-9 / (s.material.C_per_Pa * s.thickness), &p); /* N <= 8 */
        double N = s.thickness * s.material.C_per_Pa * (p.s1 - p.s2) / (lambda * 1e-9), xyz[3];
        CHECK_NEAR(biref_pe_retardation_nm(&s, &p) / lambda, N, 1e-12);
        /* The only residual is the e-mode's own reflectance against the matched surround,
         * r_e^2 = (dn / (2 n0 + dn))^2 = O(dn^2): the error is scaled by it (plus rounding). */
        double dn = s.material.C_per_Pa * (p.s1 - p.s2), re2 = pow(dn / (2 * s.material.n0 + dn), 2);
        double scale = 1.0 / (1e-12 + 4 * re2);
        biref_pe_shade(&s, NULL, &p, xyz);
        worst_circ = fmax(worst_circ, fabs(xyz[0] - pow(sin(M_PI * N), 2)) * scale);
        /* Plane polariscope, dark, polarizer psi: I = sin^2(2 (phi - psi)) sin^2(pi N). */
        double psi = test_uniform(&rng, -M_PI, M_PI);
        setup_for(&s, mats[t % 4], s.thickness / MM, -1, BIREF_PE_PLANE, BIREF_PE_DARK, psi, BIREF_PE_MONO, lambda);
        biref_pe_shade(&s, NULL, &p, xyz);
        worst_plane =
            fmax(worst_plane, fabs(xyz[0] - pow(sin(2 * (p.phi - psi)), 2) * pow(sin(M_PI * N), 2)) * scale);
        /* Isoclinic: a principal direction along the polarizer gives darkness at any N. */
        biref_pe_principal q = p;
        q.phi = psi + (t % 2) * M_PI / 2;
        q.cos2phi = cos(2 * q.phi);
        q.sin2phi = sin(2 * q.phi);
        biref_pe_shade(&s, NULL, &q, xyz);
        worst_iso = fmax(worst_iso, fabs(xyz[0]));
        /* The general path (biref_slab_prepare + closed-form Jones matrix, eq. 17) agrees: with no
         * reflections the coherent and order-incoherent sums coincide. */
        double g[3];
        setup_for(&s, mats[t % 4], s.thickness / MM, -1, t % 3 ? BIREF_PE_PLANE : BIREF_PE_CIRCULAR,
                  t % 2 ? BIREF_PE_DARK : BIREF_PE_LIGHT, psi, BIREF_PE_MONO, lambda);
        biref_pe_shade(&s, NULL, &p, xyz);
        CHECK(biref_pe_shade_general(&s, NULL, &p, 1, 0, g) == BIREF_OK);
        worst_gen = fmax(worst_gen, fabs(xyz[0] - g[0]) * scale);
    }
    /* Printed in units of (1e-12 + 4 r_e^2): a value <= 1 means "equal up to O(dn^2)". */
    printf("mono, index-matched (errors in units of 1e-12 + 4 r_e^2): |I - sin^2(pi N)| <= %.3f (circular dark), "
           "plane dark %.3f, fast vs general %.3f; isoclinic %.2e\n",
           worst_circ, worst_plane, worst_gen, worst_iso);
    CHECK(worst_circ <= 1.0);
    CHECK(worst_plane <= 1.0);
    CHECK(worst_iso < 1e-12);
    CHECK(worst_gen <= 1.0);
}

/* In air the plate's multiple reflections are coherent only within an order (the source's
 * coherence length is below 2 n h): the general path averaged over thickness jitter of many
 * Fabry-Perot periods (which washes out the cross-order terms) agrees with the fast path. */
static void mono_in_air_fast_path_matches_averaged_general_path(void)
{
    test_rng rng = {MONO_SEED};
    test_skip(&rng, MONO_MATCHED_DRAWS);
    double worst_air = 0, worst_air_formula = 0;
    for (int t = 0; t < 60; t++) {
        biref_pe_setup s;
        double lambda = test_uniform(&rng, 450, 650), psi = test_uniform(&rng, 0, M_PI);
        setup_for(&s, t % 2 ? "polycarbonate" : "glass", test_uniform(&rng, 1, 6), 1.0,
                  t % 3 ? BIREF_PE_PLANE : BIREF_PE_CIRCULAR, t % 4 ? BIREF_PE_DARK : BIREF_PE_LIGHT, psi,
                  BIREF_PE_MONO, lambda);
        biref_pe_principal p;
        random_principal(&rng, 5 * lambda * 1e-9 / (s.material.C_per_Pa * s.thickness), &p);
        double f[3], g[3];
        biref_pe_shade(&s, NULL, &p, f);
        /* 400 samples over 40 half-wavelength periods: the retardation changes by only
         * 40 lambda/(2n) * dn, i.e. < 1e-4 fringe. */
        double period = lambda / (2 * s.material.n0);
        CHECK(biref_pe_shade_general(&s, NULL, &p, 400, 40 * period, g) == BIREF_OK);
        worst_air = fmax(worst_air, fabs(f[0] - g[0]));
        if (t % 3 == 0 && t % 4) { /* circular, dark */
            /* Circular dark in air: tau_e tau_o ~ (1-R)^2 times sin^2(pi N), plus order-1 terms ~R^2. */
            double N = biref_pe_retardation_nm(&s, &p) / lambda;
            double r = (s.material.n0 - 1) / (s.material.n0 + 1), T = 1 - r * r;
            worst_air_formula = fmax(worst_air_formula, fabs(f[0] - T * T * pow(sin(M_PI * N), 2)));
        }
    }
    printf("mono, air: fast vs thickness-averaged general path %.2e; vs (1-R)^2 sin^2(pi N) %.2e\n", worst_air,
           worst_air_formula);
    CHECK(worst_air < 3e-3);
    CHECK(worst_air_formula < 0.01);
}

static const char *const MATERIALS[] = {"polycarbonate", "epoxy", "pmma", "glass"};
enum { WHITE_SEED = 4242, WHITE_EXPANSION_POINTS = 300 };

/* Point t of the fast path vs expansion comparison: thick plates in air, retardations up to
 * 6000 nm (~11 orders at 550 nm), standard and random polariscopes. */
static void white_expansion_point(test_rng *rng, int t, biref_pe_setup *s, biref_pe_principal *p)
{
    setup_for(s, MATERIALS[t % 4], test_uniform(rng, 0.5, 12), t % 5 ? 1.0 : 1.33,
              t % 2 ? BIREF_PE_PLANE : BIREF_PE_CIRCULAR, t % 3 ? BIREF_PE_DARK : BIREF_PE_LIGHT,
              test_uniform(rng, 0, M_PI), BIREF_PE_WHITE, 0);
    if (t % 4 == 3) {
        double S[4];
        double complex P[2][2];
        test_random_stokes(rng, S);
        if (t % 8 == 3)
            biref_analyzer_circular(t % 16 == 3 ? 1 : -1, P);
        else
            biref_analyzer_linear(test_uniform(rng, 0, M_PI), P);
        CHECK(biref_pe_polariscope_custom(S, P, &s->pol) == BIREF_OK);
    }
    random_principal(rng, 6000e-9 / (s->material.C_per_Pa * s->thickness), p);
}

/* Fast path vs the expansion (every interference term, adaptive order). */
static void white_fast_path_matches_expansion(void)
{
    test_rng rng = {WHITE_SEED};
    double worst_xyz = 0, worst_de = 0;
    for (int t = 0; t < WHITE_EXPANSION_POINTS; t++) {
        biref_pe_setup s;
        biref_pe_principal p;
        white_expansion_point(&rng, t, &s, &p);
        double f[3], g[3];
        biref_pe_shade(&s, sp, &p, f);
        CHECK(biref_pe_shade_general(&s, sp, &p, 0, 0, g) == BIREF_OK);
        for (int j = 0; j < 3; j++) worst_xyz = fmax(worst_xyz, fabs(f[j] - g[j]));
        worst_de = fmax(worst_de, biref_delta_e00_xyz(f, g));
    }
    printf("white: fast vs expansion (300 random points): max |dXYZ| %.2e, max dE00 %.3f\n", worst_xyz, worst_de);
    CHECK(worst_xyz < 1e-4);
    CHECK(worst_de < 0.05);
}

/* Fast path vs ground truth (16384 samples). The samples must resolve the plate's Fabry-Perot
 * oscillation in lambda (period lambda^2 / (2 n h)): in air, plates up to 0.15 mm (>= 15 samples
 * per period at 380 nm); index-matched, any thickness. The points continue the expansion
 * comparison's sequence. */
static void white_fast_path_matches_ground_truth(void)
{
    biref_integrator_options go;
    biref_integrator_options_default(&go);
    go.method = BIREF_METHOD_GROUND_TRUTH;
    biref_integrator *gt = NULL;
    CHECK(biref_integrator_create(sp, &go, &gt, NULL, 0) == BIREF_OK);
    if (!gt) return;
    test_rng rng = {WHITE_SEED};
    for (int t = 0; t < WHITE_EXPANSION_POINTS; t++) {
        biref_pe_setup s;
        biref_pe_principal p;
        white_expansion_point(&rng, t, &s, &p);
    }
    const char *const *mats = MATERIALS;
    double worst_gt = 0, sum_gt = 0;
    int count = 0;
    for (int t = 0; t < 96; t++) {
        biref_pe_setup s;
        int matched = t % 2;
        setup_for(&s, mats[t % 4], matched ? test_uniform(&rng, 1, 10) : test_uniform(&rng, 0.05, 0.15),
                  matched ? -1 : 1.0, t % 3 ? BIREF_PE_PLANE : BIREF_PE_CIRCULAR, t % 4 < 3 ? BIREF_PE_DARK : BIREF_PE_LIGHT,
                  test_uniform(&rng, 0, M_PI), BIREF_PE_WHITE, 0);
        biref_pe_principal p;
        random_principal(&rng, 3000e-9 / (s.material.C_per_Pa * s.thickness), &p);
        double f[3], g[3];
        biref_pe_shade(&s, sp, &p, f);
        CHECK(biref_pe_shade_integrated(&s, gt, &p, 0.0, g) == BIREF_OK);
        double de = biref_delta_e00_xyz(f, g);
        worst_gt = fmax(worst_gt, de);
        sum_gt += de;
        count++;
    }
    printf("white: fast vs ground truth (16384 samples, %d points): mean dE00 %.4f, max %.4f\n", count,
           sum_gt / count, worst_gt);
    CHECK(worst_gt <= 1.0);
    biref_integrator_destroy(gt);
}

/* Dark fringes along the disk's vertical diameter, found in a rendered column, against the
 * closed form N(y) = 4 C P R / (pi lambda (R^2 - y^2)) (sigma1 - sigma2 on x = 0). */
static void disk_fringes_on_the_diameter_at_closed_form_orders(void)
{
    biref_pe_setup s;
    setup_for(&s, "polycarbonate", 6, 1.0, BIREF_PE_CIRCULAR, BIREF_PE_DARK, 0, BIREF_PE_MONO, 589.0);
    biref_pe_field f;
    char msg[128];
    const double R = 25 * MM, P = 500;
    CHECK(biref_pe_field_disk(&f, R, s.thickness, P, msg, sizeof msg) == BIREF_OK);
    const int H = 1024;
    biref_pe_image_opts o = {.width = 1, .height = H, .supersample = 1, .threads = 0, .tint = {1, 1, 1}, .tilt = 0};
    float *img = malloc(sizeof(float) * 3 * H);
    CHECK(biref_pe_render(&s, NULL, &f, &o, img, NULL, 0) == BIREF_OK);
    const double Cc = s.material.C_per_Pa, lam = 589e-9;
    const double sy = (f.frame[3] - f.frame[2]) / H;
    double worst = 0;
    int found = 0, expected = 0;
    double ylim = 0.85 * R; /* beyond, fringes approach the pixel size near the load points */
    for (int j = 1; j < H - 1; j++) {
        double y = f.frame[3] - (j + 0.5) * sy;
        if (fabs(y) > ylim) continue;
        float a = img[3 * (j - 1)], b = img[3 * j], c = img[3 * (j + 1)];
        if (b < a && b <= c && b < 0.2f) {
            /* Parabola through three samples: sub-pixel minimum (y decreases with j). */
            double d = 0.5 * (a - c) / (a - 2 * b + c);
            double ym = y - d * sy;
            double N = 4 * Cc * P * R / (M_PI * lam * (R * R - ym * ym));
            worst = fmax(worst, fabs(N - nearbyint(N)));
            found++;
        }
    }
    /* Integer orders between the centre and ylim on both halves. */
    double Nc = 4 * Cc * P / (M_PI * lam * R), Nl = 4 * Cc * P * R / (M_PI * lam * (R * R - ylim * ylim));
    for (int k = (int)ceil(Nc); k <= (int)floor(Nl); k++) expected += 2;
    printf("disk diameter: %d dark fringes found (%d expected, N from %.3f to %.3f), worst |N - round(N)| = %.4f\n",
           found, expected, Nc, Nl, worst);
    CHECK(found == expected);
    CHECK(worst < 0.1);
    free(img);
}

/* Isoclinics in a picture: in a dark plane polariscope every pixel's intensity is at most
 * sin^2(2 (phi - psi)) of its principal direction, so pixels whose principal direction is along
 * the polarizer are dark, whatever their fringe order. */
static void isoclinics(biref_pe_light_kind light)
{
    biref_pe_setup s;
    const double psi = 20 * M_PI / 180;
    setup_for(&s, "polycarbonate", 6, 1.0, BIREF_PE_PLANE, BIREF_PE_DARK, psi, light, 589);
    biref_pe_field f;
    char msg[128];
    CHECK(biref_pe_field_disk(&f, 25 * MM, s.thickness, 500, msg, sizeof msg) == BIREF_OK);
    const int W = 96;
    biref_pe_image_opts o = {.width = W, .height = W, .supersample = 1, .threads = 2, .tint = {1, 1, 1}, .tilt = 0};
    float *img = malloc(sizeof(float) * 3 * W * W);
    CHECK(biref_pe_render(&s, sp, &f, &o, img, NULL, 0) == BIREF_OK);
    double worst = 0, dark = 0;
    int n_iso = 0;
    for (int j = 0; j < W; j++)
        for (int i = 0; i < W; i++) {
            double x = f.frame[0] + (i + 0.5) * (f.frame[1] - f.frame[0]) / W;
            double y = f.frame[3] - (j + 0.5) * (f.frame[3] - f.frame[2]) / W;
            biref_pe_stress st;
            if (!biref_pe_field_stress(&f, x, y, &st)) continue;
            biref_pe_principal p;
            biref_pe_principal_of(&st, &p);
            double bound = pow(sin(2 * (p.phi - psi)), 2);
            for (int m = 0; m < 3; m++) worst = fmax(worst, img[3 * (j * W + i) + m] - bound);
            if (bound < 1e-3) {
                n_iso++;
                dark = fmax(dark, img[3 * (j * W + i) + 1]);
            }
        }
    printf("isoclinics (%s): intensity - sin^2(2(phi - psi)) <= %.2e; %d pixels within 1 deg of the "
           "isoclinic, max Y there %.2e\n",
           light == BIREF_PE_MONO ? "mono" : "white", worst, n_iso, dark);
    CHECK(worst < 1e-6);
    CHECK(n_iso > 10);
    CHECK(dark < 1e-3);
    free(img);
}

static void isoclinics_are_dark_in_white_light(void) { isoclinics(BIREF_PE_WHITE); }
static void isoclinics_are_dark_in_mono_light(void) { isoclinics(BIREF_PE_MONO); }

/* Oblique viewing, continuity with the fast path at normal incidence; the seeded sequence
 * (40 points of 6 draws) continues in the uniaxial case. */
enum { OBLIQUE_SEED = 777, OBLIQUE_NEAR_NORMAL_DRAWS = 40 * 6 };

static void oblique_near_normal_matches_fast_path(void)
{
    test_rng rng = {OBLIQUE_SEED};
    double worst_w = 0, worst_m = 0;
    for (int t = 0; t < 40; t++) {
        biref_pe_setup s;
        setup_for(&s, t % 2 ? "polycarbonate" : "epoxy", test_uniform(&rng, 1, 8), 1.0,
                  t % 3 ? BIREF_PE_PLANE : BIREF_PE_CIRCULAR, t % 4 ? BIREF_PE_DARK : BIREF_PE_LIGHT,
                  test_uniform(&rng, 0, M_PI), t % 2 ? BIREF_PE_WHITE : BIREF_PE_MONO, 589);
        biref_pe_principal p;
        random_principal(&rng, 4000e-9 / (s.material.C_per_Pa * s.thickness), &p);
        double f[3], o[3];
        biref_pe_shade(&s, sp, &p, f);
        CHECK(biref_pe_shade_oblique(&s, sp, &p, 1e-7, o) == BIREF_OK);
        /* Where |s2| > |s1| the best slab shifts both indices by -dn (a common shift, which
         * changes the Fresnel transmittances by ~ dn / 4); elsewhere it is the same slab. */
        double dn = s.material.C_per_Pa * (p.s1 - p.s2);
        double scale = fabs(p.s1) >= fabs(p.s2) ? 1.0 : 1e-5 / (0.5 * dn);
        for (int j = 0; j < 3; j++)
            if (t % 2)
                worst_w = fmax(worst_w, fabs(f[j] - o[j]) * scale);
            else
                worst_m = fmax(worst_m, fabs(f[j] - o[j]) * scale);
    }
    printf("oblique at 1e-7 rad vs fast path (in units of 1e-5 or, with the index shift, dn / 2): white %.3f, "
           "mono %.3f\n",
           worst_w / 1e-5, worst_m / 1e-5);
    CHECK(worst_w < 1e-5);
    CHECK(worst_m < 1e-5);
}

/* Index-matched (no refraction), plane polariscope crossed at 45 deg, uniaxial stress along x:
 * tension (axis along direction 1 = x) and compression (the best slab puts the axis along
 * direction 2 = x). Both are exactly uniaxial media with the axis normal to the plane of
 * incidence: N(theta) = h C |sigma| / (lambda cos theta) up to O(dn^2). */
static void oblique_uniaxial_stress_matches_closed_form(void)
{
    test_rng rng = {OBLIQUE_SEED};
    test_skip(&rng, OBLIQUE_NEAR_NORMAL_DRAWS);
    double worst_a = 0, worst_naive = 0;
    for (int t = 0; t < 40; t++) {
        biref_pe_setup s;
        double lambda = 589, theta = test_uniform(&rng, 5, 40) * M_PI / 180;
        setup_for(&s, "polycarbonate", 5, -1, BIREF_PE_PLANE, BIREF_PE_DARK, M_PI / 4, BIREF_PE_MONO, lambda);
        double S = test_uniform(&rng, 0.2, 4) * lambda * 1e-9 / (s.material.C_per_Pa * s.thickness);
        biref_pe_stress st = {t % 2 ? S : -S, 0, 0};
        biref_pe_principal p;
        biref_pe_principal_of(&st, &p);
        double o[3];
        CHECK(biref_pe_shade_oblique(&s, NULL, &p, theta, o) == BIREF_OK);
        double N = s.thickness * s.material.C_per_Pa * S / (lambda * 1e-9 * cos(theta));
        CHECK_NEAR(biref_pe_retardation_oblique_nm(&s, &p, theta) / lambda, N, 1e-3 * N);
        CHECK_NEAR(biref_pe_retardation_oblique_nm(&s, &p, 0.0), biref_pe_retardation_nm(&s, &p),
                   1e-6 * biref_pe_retardation_nm(&s, &p));
        worst_a = fmax(worst_a, fabs(o[0] - pow(sin(M_PI * N), 2)));
        if (t % 2 == 0) {
            /* The naive axis (direction 1, in the plane of incidence) misses by C |sigma2| sin^2. */
            biref_slab sl = biref_pe_slab_at(&s.material, s.thickness, s.eta_i, &p);
            biref_slab_state ss;
            CHECK(biref_slab_prepare(&sl, theta, &ss) == BIREF_OK);
            double opd = creal(ss.opl_down[1] - ss.opl_down[0]);
            worst_naive = fmax(worst_naive, fabs(fabs(opd) / lambda - N));
        }
    }
    printf("oblique, uniaxial stress: |I - sin^2(pi N / cos)| <= %.2e; the naive axis would be off by up to %.2f "
           "fringe\n",
           worst_a, worst_naive);
    CHECK(worst_a < 2e-3);
    CHECK(worst_naive > 0.05);
}

static const double HOLE_THICKNESS = 5e-3; /* the epoxy plate of the render case */

static void field_builders_refuse_bad_geometry(void)
{
    biref_pe_field f;
    char msg[128];
    const double h = HOLE_THICKNESS;
    CHECK(biref_pe_field_hole(&f, 5 * MM, 60 * MM, 40 * MM, h, 4 * MPA, 0, msg, sizeof msg) == BIREF_OK);
    CHECK(biref_pe_field_hole(&f, 25 * MM, 40 * MM, 40 * MM, h, 4 * MPA, 0, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(biref_pe_field_disk(&f, -1, 1, 1, msg, sizeof msg) == BIREF_ERR_INVALID);
}

/* One and two threads give the same picture; the hole shows the light-field background. */
static void render_is_thread_independent_and_hole_shows_background(void)
{
    biref_pe_setup s;
    setup_for(&s, "epoxy", HOLE_THICKNESS / MM, 1.0, BIREF_PE_CIRCULAR, BIREF_PE_LIGHT, 0, BIREF_PE_WHITE, 0);
    biref_pe_field f;
    char msg[128];
    CHECK(biref_pe_field_hole(&f, 5 * MM, 60 * MM, 40 * MM, s.thickness, 4 * MPA, 0, msg, sizeof msg) == BIREF_OK);
    const int W = 90, H = 60;
    float *a = malloc(sizeof(float) * 3 * W * H), *b = malloc(sizeof(float) * 3 * W * H);
    biref_pe_image_opts o = {.width = W, .height = H, .supersample = 2, .threads = 1, .tint = {1, 1, 1}, .tilt = 0};
    CHECK(biref_pe_render(&s, sp, &f, &o, a, NULL, 0) == BIREF_OK);
    o.threads = 2;
    CHECK(biref_pe_render(&s, sp, &f, &o, b, NULL, 0) == BIREF_OK);
    CHECK(memcmp(a, b, sizeof(float) * 3 * W * H) == 0);
    /* The hole shows the light-field background: white E. */
    size_t c = 3 * ((size_t)(H / 2) * W + W / 2);
    CHECK_NEAR(a[c], 1.0, 1e-6);
    CHECK_NEAR(a[c + 1], 1.0, 1e-6);
    free(a);
    free(b);
}

int main(int argc, char **argv)
{
    if (biref_spectral_create(NULL, &sp, NULL, 0) != BIREF_OK) return 1;
    static const test_case cases[] = {
        {"material_presets_are_valid_and_unknown_names_refused", material_presets_are_valid_and_unknown_names_refused},
        {"disk_centre_rim_and_resultant", disk_centre_rim_and_resultant},
        {"disk_is_in_equilibrium", disk_is_in_equilibrium},
        {"kirsch_hole_concentration_traction_and_equilibrium", kirsch_hole_concentration_traction_and_equilibrium},
        {"beam_extreme_fibre_stress", beam_extreme_fibre_stress},
        {"principal_stresses_are_ordered_eigenpairs", principal_stresses_are_ordered_eigenpairs},
        {"grid_interpolates_linear_field_exactly", grid_interpolates_linear_field_exactly},
        {"malformed_csv_gives_one_line_errors", malformed_csv_gives_one_line_errors},
        {"csv_export_variants_are_accepted", csv_export_variants_are_accepted},
        {"missing_csv_file_is_an_io_error", missing_csv_file_is_an_io_error},
        {"polariscope_backgrounds_and_custom_refusals", polariscope_backgrounds_and_custom_refusals},
        {"mono_index_matched_matches_closed_forms", mono_index_matched_matches_closed_forms},
        {"mono_in_air_fast_path_matches_averaged_general_path", mono_in_air_fast_path_matches_averaged_general_path},
        {"white_fast_path_matches_expansion", white_fast_path_matches_expansion},
        {"white_fast_path_matches_ground_truth", white_fast_path_matches_ground_truth},
        {"disk_fringes_on_the_diameter_at_closed_form_orders", disk_fringes_on_the_diameter_at_closed_form_orders},
        {"isoclinics_are_dark_in_white_light", isoclinics_are_dark_in_white_light},
        {"isoclinics_are_dark_in_mono_light", isoclinics_are_dark_in_mono_light},
        {"oblique_near_normal_matches_fast_path", oblique_near_normal_matches_fast_path},
        {"oblique_uniaxial_stress_matches_closed_form", oblique_uniaxial_stress_matches_closed_form},
        {"field_builders_refuse_bad_geometry", field_builders_refuse_bad_geometry},
        {"render_is_thread_independent_and_hole_shows_background",
         render_is_thread_independent_and_hole_shows_background},
    };
    int rc = test_run_cases("test_photoelastic", cases, TEST_COUNT(cases), argc, argv);
    biref_spectral_destroy(sp);
    return rc;
}
