/* The world-space entry point (biref_shade_hit): the paper's frame is recovered where world and
 * paper frame coincide, results do not depend on how the world is rotated (nor, under the paper's
 * light, on which way the normal points), lossless energy is conserved, bad input is refused. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "biref/biref.h"
#include "test_cases.h"

/* World = the paper's transmission frame: normal +y, tangent +x (local z = x cross y = +z) and
 * a view ray v = (0, cos t, sin t), so the light behind travels along -v = (0, -cos t, -sin t). */
static const double THETA = 35.0 * M_PI / 180.0;
static const biref_surface SURFACE = {{0, 1, 0}, {1, 0, 0}, {0.3, 0.8, -0.52}, 1.66, 1.49, 4200.0, 1.0};
static double view[3];

/* A numeric shader with a world-fixed polarizer and analyzer (not the paper's s/p light). */
static const double POLARIZER[3] = {0.6, 0.0, 0.8};
static const double ANALYZER[3] = {0.0, 0.8, -0.6};

static biref_shader *analytic; /* default options, no polarizer */
static biref_spectral *sp;

/* Unpolarized light through world-fixed linear polarizers along pol and an. */
static biref_light world_light(const double pol[3], const double an[3])
{
    static const double half[2] = {0.5, 0.5}, pass[2] = {1, 1};
    biref_light l;
    CHECK(biref_light_sp(half, pass, &l) == BIREF_OK);
    CHECK(biref_light_world_polarizer(&l, pol) == BIREF_OK);
    CHECK(biref_light_world_analyzer(&l, an) == BIREF_OK);
    return l;
}

static biref_shader *numeric_shader(const double pol[3], const double an[3])
{
    biref_integrator_options opt;
    biref_integrator_options_default(&opt);
    opt.method = BIREF_METHOD_NUMERIC;
    opt.samples = 32;
    const biref_light l = world_light(pol, an);
    biref_shader *sh = NULL;
    char msg[256];
    CHECK(biref_shader_create(sp, &opt, &l, &sh, msg, sizeof msg) == BIREF_OK);
    return sh;
}

static void rotate(const double R[3][3], const double v[3], double o[3])
{
    for (int i = 0; i < 3; i++) o[i] = R[i][0] * v[0] + R[i][1] * v[1] + R[i][2] * v[2];
}

/* A random rotation from a random unit quaternion. */
static void random_rotation(test_rng *rng, double R[3][3])
{
    double q[4], n = 0;
    for (int i = 0; i < 4; i++) {
        q[i] = test_uniform(rng, -1, 1);
        n += q[i] * q[i];
    }
    n = sqrt(n);
    double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    double M[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                      {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                      {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
    memcpy(R, M, sizeof M);
}

/* The same 20 random rotations for every case that rotates the world. */
enum { ROTATIONS = 20 };
static const uint64_t ROTATION_SEED = 0x5eed5eedULL;

/* The next random rotation M, and the surface and view ray rotated by it. */
static void rotated_hit(test_rng *rng, double M[3][3], biref_surface *rs, double rv[3])
{
    random_rotation(rng, M);
    *rs = SURFACE;
    rotate(M, SURFACE.normal, rs->normal);
    rotate(M, SURFACE.tangent, rs->tangent);
    rotate(M, view, rv);
}

static void paper_frame_is_recovered(void)
{
    double T[3], R[3];
    biref_hit_frames fr;
    CHECK(biref_shade_hit(analytic, &SURFACE, view, T, R, &fr) == BIREF_OK);
    CHECK_NEAR(fr.theta, THETA, 1e-14);
    CHECK_NEAR(fr.x_T[0], 1, 1e-15);
    CHECK_NEAR(fr.y_T[1], 1, 1e-15);
    CHECK_NEAR(fr.z[2], 1, 1e-15);
    CHECK_NEAR(fr.mirror[1], -cos(THETA), 1e-15);
    CHECK_NEAR(fr.mirror[2], sin(THETA), 1e-15);
}

/* In the paper's frame the hit is the analytic spectrum of the slab (reflection: of the flipped
 * state) under unpolarized light. */
static void hit_equals_analytic_spectrum_and_conserves_energy(void)
{
    double T[3], R[3];
    CHECK(biref_shade_hit(analytic, &SURFACE, view, T, R, NULL) == BIREF_OK);
    const biref_surface *s = &SURFACE;
    biref_slab slab = {s->eta_o, s->eta_e, {s->axis[0], s->axis[1], s->axis[2]}, s->thickness_nm, 1.0};
    biref_slab_state st, flipped;
    CHECK(biref_slab_prepare(&slab, THETA, &st) == BIREF_OK);
    biref_slab_state_flip(&st, &flipped);
    biref_spectrum spT, spR;
    biref_spectrum_analytic(sp, &st, &spT);
    biref_spectrum_analytic(sp, &flipped, &spR);
    const double w[2] = {0.5, 0.5}, mask[2] = {1, 1};
    double expT[3], expR[3];
    biref_spectrum_mix(spT.T, w, mask, expT);
    biref_spectrum_mix(spR.R, w, mask, expR);
    for (int j = 0; j < 3; j++) {
        CHECK_NEAR(T[j], expT[j], 1e-12);
        CHECK_NEAR(R[j], expR[j], 1e-12);
        /* Reciprocity: transmission from behind plus reflection from the front is all the light
         * (to the paper's analytic approximation: 2e-4 here). */
        CHECK_NEAR(T[j] + R[j], 1.0, 5e-4);
    }
}

/* Rotating the world (normal, tangent, view ray together) changes nothing. */
static void rotating_the_world_changes_nothing(void)
{
    double T[3], R[3];
    CHECK(biref_shade_hit(analytic, &SURFACE, view, T, R, NULL) == BIREF_OK);
    test_rng rng = {ROTATION_SEED};
    for (int trial = 0; trial < ROTATIONS; trial++) {
        double M[3][3], rv[3], T1[3], R1[3];
        biref_surface rs;
        rotated_hit(&rng, M, &rs, rv);
        CHECK(biref_shade_hit(analytic, &rs, rv, T1, R1, NULL) == BIREF_OK);
        for (int j = 0; j < 3; j++) {
            CHECK_NEAR(T1[j], T[j], 1e-12);
            CHECK_NEAR(R1[j], R[j], 1e-12);
        }
    }
}

/* The same with a world-fixed polarizer and analyzer (numeric shader), rotated along. */
static void rotating_the_world_with_its_polarizers_changes_nothing(void)
{
    biref_shader *num = numeric_shader(POLARIZER, ANALYZER);
    if (!num) return;
    double T0[3], R0[3];
    CHECK(biref_shade_hit(num, &SURFACE, view, T0, R0, NULL) == BIREF_OK);
    CHECK(T0[1] > 1e-4 && R0[1] > 1e-4); /* not a trivially dark configuration */
    test_rng rng = {ROTATION_SEED};
    for (int trial = 0; trial < ROTATIONS; trial++) {
        double M[3][3], rv[3], T1[3], R1[3];
        biref_surface rs;
        rotated_hit(&rng, M, &rs, rv);
        double rpol[3], ran[3];
        rotate(M, POLARIZER, rpol);
        rotate(M, ANALYZER, ran);
        biref_shader *rnum = numeric_shader(rpol, ran);
        if (rnum) {
            CHECK(biref_shade_hit(rnum, &rs, rv, T1, R1, NULL) == BIREF_OK);
            for (int j = 0; j < 3; j++) {
                CHECK_NEAR(T1[j], T0[j], 1e-12);
                CHECK_NEAR(R1[j], R0[j], 1e-12);
            }
        }
        biref_shader_destroy(rnum);
    }
    biref_shader_destroy(num);
}

/* The normal may point either way: with the paper's light (s/p relative to the plane of
 * incidence) flipping it changes nothing. (With world-fixed polarizers it does: z = x cross y
 * turns with the normal, so the same local optic axis describes the plate turned over about its
 * tangent, another slab in the world.) */
static void flipping_the_normal_changes_nothing_under_paper_light(void)
{
    biref_surface flipped = SURFACE;
    for (int i = 0; i < 3; i++) flipped.normal[i] = -SURFACE.normal[i];
    double T[3], R[3], T1[3], R1[3];
    CHECK(biref_shade_hit(analytic, &SURFACE, view, T, R, NULL) == BIREF_OK);
    CHECK(biref_shade_hit(analytic, &flipped, view, T1, R1, NULL) == BIREF_OK);
    for (int j = 0; j < 3; j++) {
        CHECK_NEAR(T1[j], T[j], 1e-12);
        CHECK_NEAR(R1[j], R[j], 1e-12);
    }
}

/* An edge-on ray, a tangent along the normal, non-finite input, a bad slab. */
static void bad_hits_are_refused(void)
{
    double T[3], R[3];
    const double edge[3] = {1, 0, 0};
    CHECK(biref_shade_hit(analytic, &SURFACE, edge, T, R, NULL) == BIREF_ERR_INVALID);
    biref_surface bad = SURFACE;
    memcpy(bad.tangent, bad.normal, sizeof bad.tangent);
    CHECK(biref_shade_hit(analytic, &bad, view, T, R, NULL) == BIREF_ERR_INVALID);
    bad = SURFACE;
    bad.normal[0] = NAN;
    CHECK(biref_shade_hit(analytic, &bad, view, T, R, NULL) == BIREF_ERR_INVALID);
    bad = SURFACE;
    bad.thickness_nm = -1;
    CHECK(biref_shade_hit(analytic, &bad, view, T, R, NULL) == BIREF_ERR_INVALID);
}

/* The analytic method integrates world-fixed polarizers (a general coherency and analyzer per hit,
 * the GPU shader's formulas). */
static void analytic_shader_takes_world_fixed_polarizer(void)
{
    biref_shader *sh = NULL;
    char msg[256];
    const biref_light l = world_light(POLARIZER, ANALYZER);
    CHECK(biref_shader_create(sp, NULL, &l, &sh, msg, sizeof msg) == BIREF_OK && sh);
    double T[3], R[3];
    if (sh) CHECK(biref_shade_hit(sh, &SURFACE, view, T, R, NULL) == BIREF_OK && T[1] >= 0 && R[1] >= 0);
    biref_shader_destroy(sh);
}

/* An analytic shader under l (the kernel's general-light terms for a real light, one hit at a time
 * for a complex one). */
static biref_shader *analytic_shader(const biref_light *l)
{
    biref_shader *sh = NULL;
    char msg[256];
    CHECK(biref_shader_create(sp, NULL, l, &sh, msg, sizeof msg) == BIREF_OK);
    return sh;
}

/* Stokes light (linear: S3 = 0, or circular) through a linear or circular analyzer. */
static biref_light stokes_light(int circular)
{
    const double stokes[4] = {1.0, 0.3, circular ? 0.0 : 0.5, circular ? 0.8 : 0.0};
    biref_light l;
    CHECK(biref_light_stokes(stokes, &l) == BIREF_OK);
    biref_complex P[2][2];
    if (circular)
        biref_analyzer_circular(-1, P);
    else
        biref_analyzer_linear(0.7, P);
    biref_light_set_analyzer(&l, P);
    return l;
}

/* Random hits (slabs, orientations, view rays) and a few bad ones, in one batch: every good hit
 * is biref_shade_hit's to the packet kernel's rounding (the analytic shaders: the paper's light,
 * world-fixed polarizers and linear Stokes light resolved per hit for the kernel, circular light
 * one hit at a time) or exactly (the numeric shader with world-fixed polarizers, one hit at a
 * time), every bad one has its code. */
static void shade_hits_equals_shade_hit_per_hit(void)
{
    enum { N = 77 }; /* more than two of the batch's chunks, not a multiple of any packet */
    biref_surface s[N];
    double v[N][3], T[N][3], R[N][3];
    biref_status st[N];
    test_rng rng = {0x5ade5ULL};
    for (int k = 0; k < N; k++) {
        double M[3][3];
        rotated_hit(&rng, M, &s[k], v[k]);
        test_random_axis(&rng, s[k].axis);
        s[k].eta_o = test_uniform(&rng, 1.3, 1.8);
        s[k].eta_e = s[k].eta_o + test_uniform(&rng, -0.2, 0.2);
        s[k].thickness_nm = test_uniform(&rng, 500, 20000);
    }
    s[5].thickness_nm = -1;                  /* a bad slab */
    memcpy(s[40].tangent, s[40].normal, sizeof s[40].tangent); /* no frame */
    v[60][0] = NAN;                          /* a bad ray */
    biref_shader *num = numeric_shader(POLARIZER, ANALYZER);
    const biref_light world = world_light(POLARIZER, ANALYZER), linear = stokes_light(0), circular = stokes_light(1);
    biref_shader *lit[3] = {analytic_shader(&world), analytic_shader(&linear), analytic_shader(&circular)};
    const biref_shader *shaders[5] = {analytic, num, lit[0], lit[1], lit[2]};
    static const char *const names[5] = {"analytic", "numeric, world-fixed", "analytic, world-fixed",
                                         "analytic, linear Stokes", "analytic, circular Stokes"};
    for (int i = 0; i < 5; i++) {
        if (!shaders[i]) continue;
        CHECK(biref_shade_hits(shaders[i], N, s, (const double(*)[3])v, T, R, st) == BIREF_ERR_INVALID);
        double worst = 0.0;
        int agree = 1;
        for (int k = 0; k < N; k++) {
            double T1[3], R1[3];
            const biref_status one = biref_shade_hit(shaders[i], &s[k], v[k], T1, R1, NULL);
            agree &= one == st[k];
            if (one != BIREF_OK) continue;
            for (int j = 0; j < 3; j++) worst = fmax(worst, fmax(fabs(T[k][j] - T1[j]), fabs(R[k][j] - R1[j])));
        }
        CHECK(agree);
        CHECK(st[5] == BIREF_ERR_INVALID && st[40] == BIREF_ERR_INVALID && st[60] == BIREF_ERR_INVALID);
        printf("%s shader: batch against one hit at a time, worst |difference| %.3g\n", names[i], worst);
        /* Packets (lanes) against one hit at a time: the paper's light takes float lanes on AVX2
         * and AVX-512 (within ~1e-7, docs/PERFORMANCE.md), the others double lanes. */
        CHECK(worst <= (i == 0 ? 1e-6 : 1e-12));
    }
    biref_shader_destroy(num);
    for (int i = 0; i < 3; i++) biref_shader_destroy(lit[i]);
    CHECK(biref_shade_hits(analytic, 0, NULL, NULL, NULL, NULL, NULL) == BIREF_OK);
    CHECK(biref_shade_hits(NULL, 1, s, (const double(*)[3])v, T, R, NULL) == BIREF_ERR_INVALID);
}

/* A world-fixed polarizer along the incident wave's s passes s light only; an analyzer along its
 * p passes p only; an axis along the wave itself blocks everything. */
static void world_fixed_polarizer_resolves_in_each_wave_basis(void)
{
    const double s[3] = {1, 0, 0}, p_in[3] = {0, 0.6, 0.8}, p_out[3] = {0, 0.8, 0.6}, along[3] = {0, 0.8, -0.6};
    biref_light l = world_light(s, p_out), at;
    biref_light_at(&l, s, p_in, p_out, &at);
    CHECK(!biref_light_is_world_fixed(&at) && !at.sp_model && at.has_analyzer);
    CHECK_NEAR(creal(at.C[0][0]), 1, 1e-15);
    CHECK_NEAR(cabs(at.C[1][1]) + cabs(at.C[0][1]), 0, 1e-15);
    CHECK_NEAR(creal(at.P[1][1]), 1, 1e-15);
    CHECK_NEAR(cabs(at.P[0][0]) + cabs(at.P[0][1]) + cabs(at.P[1][0]), 0, 1e-15);
    CHECK_NEAR(biref_light_passthrough(&at), 0, 1e-15); /* crossed */
    l = world_light(along, s);
    biref_light_at(&l, s, p_in, p_out, &at);
    CHECK_NEAR(creal(at.C[0][0]) + creal(at.C[1][1]), 0, 1e-15);
    const double zero[3] = {0, 0, 0};
    CHECK(biref_light_world_polarizer(&l, zero) == BIREF_ERR_INVALID);
}

/* The polarizer's text form: states and analyzers of "linear:DEG" and "circular:+1|-1", one line
 * for anything else. */
static void polarizer_text_form_parses_and_refuses(void)
{
    biref_polarizer p;
    char msg[256];
    CHECK(biref_polarizer_parse("linear:45", &p, msg, sizeof msg) == BIREF_OK);
    CHECK_NEAR(p.stokes[0], 1, 0);
    CHECK_NEAR(p.stokes[1], 0, 1e-15);
    CHECK_NEAR(p.stokes[2], 1, 1e-15);
    CHECK_NEAR(creal(p.analyzer[0][1]), 0.5, 1e-15);
    CHECK(biref_polarizer_parse("circular:-1", &p, msg, sizeof msg) == BIREF_OK);
    CHECK(p.stokes[3] == -1 && p.stokes[1] == 0);
    CHECK_NEAR(cimag(p.analyzer[0][1]), -0.5, 1e-15);
    CHECK(biref_polarizer_parse("circular:1", &p, NULL, 0) == BIREF_OK && p.stokes[3] == 1);
    const char *bad[] = {"linear:", "linear:x", "linear:1e999", "linear:5deg", "circular:2", "circular:", "elliptic:1", ""};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        msg[0] = 0;
        CHECK(biref_polarizer_parse(bad[i], &p, msg, sizeof msg) == BIREF_ERR_INVALID && msg[0]);
    }
    CHECK(biref_polarizer_parse("circular:2", &p, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(strstr(msg, "+1 or -1") != NULL);
}

int main(int argc, char **argv)
{
    view[1] = cos(THETA);
    view[2] = sin(THETA);
    char msg[256];
    if (biref_spectral_create(NULL, &sp, NULL, 0) != BIREF_OK) return 1;
    if (biref_shader_create(sp, NULL, NULL, &analytic, msg, sizeof msg) != BIREF_OK) {
        fprintf(stderr, "shader: %s\n", msg);
        return 1;
    }
    static const test_case cases[] = {
        {"paper_frame_is_recovered", paper_frame_is_recovered},
        {"hit_equals_analytic_spectrum_and_conserves_energy", hit_equals_analytic_spectrum_and_conserves_energy},
        {"rotating_the_world_changes_nothing", rotating_the_world_changes_nothing},
        {"rotating_the_world_with_its_polarizers_changes_nothing", rotating_the_world_with_its_polarizers_changes_nothing},
        {"flipping_the_normal_changes_nothing_under_paper_light", flipping_the_normal_changes_nothing_under_paper_light},
        {"bad_hits_are_refused", bad_hits_are_refused},
        {"analytic_shader_takes_world_fixed_polarizer", analytic_shader_takes_world_fixed_polarizer},
        {"shade_hits_equals_shade_hit_per_hit", shade_hits_equals_shade_hit_per_hit},
        {"world_fixed_polarizer_resolves_in_each_wave_basis", world_fixed_polarizer_resolves_in_each_wave_basis},
        {"polarizer_text_form_parses_and_refuses", polarizer_text_form_parses_and_refuses},
    };
    int rc = test_run_cases("test_shading", cases, TEST_COUNT(cases), argc, argv);
    biref_shader_destroy(analytic);
    biref_spectral_destroy(sp);
    return rc;
}
