/* The world-space entry point (biref_shade_hit): the paper's frame is recovered where world and
 * paper frame coincide, results do not depend on how the world is rotated (nor, under the paper's
 * light, on which way the normal points), lossless energy is conserved, bad input is refused. */
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
static const biref_polarization POLARIZER = {BIREF_POL_LINEAR, 0.5, 0.5, {0.6, 0.0, 0.8}};
static const biref_filter ANALYZER = {BIREF_FILTER_LINEAR, {0.0, 0.8, -0.6}};

static biref_shader *analytic; /* default options, no polarizer */
static biref_spectral *sp;

static biref_shader *numeric_shader(const biref_polarization *pol, const biref_filter *filt)
{
    biref_render_options opt;
    biref_render_options_default(&opt);
    opt.method = BIREF_METHOD_NUMERIC;
    opt.samples = 32;
    biref_shader *sh = NULL;
    char msg[256];
    CHECK(biref_shader_create(&opt, pol, filt, &sh, msg, sizeof msg) == BIREF_OK);
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
    biref_shader *num = numeric_shader(&POLARIZER, &ANALYZER);
    if (!num) return;
    double T0[3], R0[3];
    CHECK(biref_shade_hit(num, &SURFACE, view, T0, R0, NULL) == BIREF_OK);
    CHECK(T0[1] > 1e-4 && R0[1] > 1e-4); /* not a trivially dark configuration */
    test_rng rng = {ROTATION_SEED};
    for (int trial = 0; trial < ROTATIONS; trial++) {
        double M[3][3], rv[3], T1[3], R1[3];
        biref_surface rs;
        rotated_hit(&rng, M, &rs, rv);
        biref_polarization rpol = POLARIZER;
        biref_filter rfilt = ANALYZER;
        rotate(M, POLARIZER.direction, rpol.direction);
        rotate(M, ANALYZER.direction, rfilt.direction);
        biref_shader *rnum = numeric_shader(&rpol, &rfilt);
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

static void analytic_shader_takes_world_fixed_polarizer(void)
{
    biref_shader *sh = NULL;
    char msg[256];
    CHECK(biref_shader_create(NULL, &POLARIZER, NULL, &sh, msg, sizeof msg) == BIREF_OK && sh);
    double T[3], R[3];
    if (sh) CHECK(biref_shade_hit(sh, &SURFACE, view, T, R, NULL) == BIREF_OK && T[1] >= 0 && R[1] >= 0);
    biref_shader_destroy(sh);
}

int main(int argc, char **argv)
{
    view[1] = cos(THETA);
    view[2] = sin(THETA);
    char msg[256];
    if (biref_shader_create(NULL, NULL, NULL, &analytic, msg, sizeof msg) != BIREF_OK) {
        fprintf(stderr, "shader: %s\n", msg);
        return 1;
    }
    if (biref_spectral_create(NULL, &sp, NULL, 0) != BIREF_OK) return 1;
    static const test_case cases[] = {
        {"paper_frame_is_recovered", paper_frame_is_recovered},
        {"hit_equals_analytic_spectrum_and_conserves_energy", hit_equals_analytic_spectrum_and_conserves_energy},
        {"rotating_the_world_changes_nothing", rotating_the_world_changes_nothing},
        {"rotating_the_world_with_its_polarizers_changes_nothing", rotating_the_world_with_its_polarizers_changes_nothing},
        {"flipping_the_normal_changes_nothing_under_paper_light", flipping_the_normal_changes_nothing_under_paper_light},
        {"bad_hits_are_refused", bad_hits_are_refused},
        {"analytic_shader_takes_world_fixed_polarizer", analytic_shader_takes_world_fixed_polarizer},
    };
    int rc = test_run_cases("test_shading", cases, TEST_COUNT(cases), argc, argv);
    biref_shader_destroy(analytic);
    biref_spectral_destroy(sp);
    return rc;
}
