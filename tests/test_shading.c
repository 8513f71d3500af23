/* The world-space entry point (biref_shade_hit): the paper's frame is recovered where world and
 * paper frame coincide, results do not depend on how the world is rotated, lossless energy is
 * conserved, bad input is refused. */
#include <math.h>
#include <string.h>

#include "biref/biref.h"
#include "test_util.h"

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

int main(void)
{
    biref_shader *sh = NULL;
    char msg[256];
    CHECK(biref_shader_create(NULL, NULL, NULL, &sh, msg, sizeof msg) == BIREF_OK);
    if (!sh) return test_report("test_shading");
    biref_spectral *sp = NULL;
    biref_spectral_config cfg;
    biref_spectral_config_default(&cfg);
    CHECK(biref_spectral_create(&cfg, &sp) == BIREF_OK);

    /* World = the paper's transmission frame: normal +y, tangent +x (local z = x cross y = +z) and
     * a view ray v = (0, cos t, sin t), so the light behind travels along -v = (0, -cos t, -sin t). */
    const double theta = 35.0 * M_PI / 180.0;
    biref_surface s = {{0, 1, 0}, {1, 0, 0}, {0.3, 0.8, -0.52}, 1.66, 1.49, 4200.0, 1.0};
    const double v[3] = {0, cos(theta), sin(theta)};
    double T[3], R[3];
    biref_hit_frames fr;
    CHECK(biref_shade_hit(sh, &s, v, T, R, &fr) == BIREF_OK);
    CHECK_NEAR(fr.theta, theta, 1e-14);
    CHECK_NEAR(fr.x_T[0], 1, 1e-15);
    CHECK_NEAR(fr.y_T[1], 1, 1e-15);
    CHECK_NEAR(fr.z[2], 1, 1e-15);
    CHECK_NEAR(fr.mirror[1], -cos(theta), 1e-15);
    CHECK_NEAR(fr.mirror[2], sin(theta), 1e-15);
    biref_slab slab = {s.eta_o, s.eta_e, {s.axis[0], s.axis[1], s.axis[2]}, s.thickness_nm, 1.0};
    biref_slab_state st, flipped;
    CHECK(biref_slab_prepare(&slab, theta, &st) == BIREF_OK);
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

    /* Rotating the world (normal, tangent, view ray together) and flipping the normal change
     * nothing; a numeric shader with a world-fixed polarizer and analyzer rotated along too. */
    biref_render_options opt;
    biref_render_options_default(&opt);
    opt.method = BIREF_METHOD_NUMERIC;
    opt.samples = 32;
    biref_polarization pol = {BIREF_POL_LINEAR, 0.5, 0.5, {0.6, 0.0, 0.8}};
    biref_filter filt = {BIREF_FILTER_LINEAR, {0.0, 0.8, -0.6}};
    biref_shader *num = NULL;
    CHECK(biref_shader_create(&opt, &pol, &filt, &num, msg, sizeof msg) == BIREF_OK);
    double T0[3], R0[3];
    CHECK(biref_shade_hit(num, &s, v, T0, R0, NULL) == BIREF_OK);
    CHECK(T0[1] > 1e-4 && R0[1] > 1e-4); /* not a trivially dark configuration */
    test_rng rng = {0x5eed5eedULL};
    for (int trial = 0; trial < 20; trial++) {
        double M[3][3];
        random_rotation(&rng, M);
        biref_surface rs = s;
        rotate(M, s.normal, rs.normal);
        rotate(M, s.tangent, rs.tangent);
        double rv[3];
        rotate(M, v, rv);
        double T1[3], R1[3];
        CHECK(biref_shade_hit(sh, &rs, rv, T1, R1, NULL) == BIREF_OK);
        for (int j = 0; j < 3; j++) {
            CHECK_NEAR(T1[j], T[j], 1e-12);
            CHECK_NEAR(R1[j], R[j], 1e-12);
        }
        biref_polarization rpol = pol;
        biref_filter rfilt = filt;
        rotate(M, pol.direction, rpol.direction);
        rotate(M, filt.direction, rfilt.direction);
        biref_shader *rnum = NULL;
        CHECK(biref_shader_create(&opt, &rpol, &rfilt, &rnum, msg, sizeof msg) == BIREF_OK);
        if (rnum) {
            CHECK(biref_shade_hit(rnum, &rs, rv, T1, R1, NULL) == BIREF_OK);
            for (int j = 0; j < 3; j++) {
                CHECK_NEAR(T1[j], T0[j], 1e-12);
                CHECK_NEAR(R1[j], R0[j], 1e-12);
            }
        }
        biref_shader_destroy(rnum);
    }

    /* Refusals: an edge-on ray, a tangent along the normal, non-finite input, a bad slab, and the
     * analytic method with a world-fixed polarizer. */
    const double edge[3] = {1, 0, 0};
    CHECK(biref_shade_hit(sh, &s, edge, T, R, NULL) == BIREF_ERR_INVALID);
    biref_surface bad = s;
    memcpy(bad.tangent, bad.normal, sizeof bad.tangent);
    CHECK(biref_shade_hit(sh, &bad, v, T, R, NULL) == BIREF_ERR_INVALID);
    bad = s;
    bad.normal[0] = NAN;
    CHECK(biref_shade_hit(sh, &bad, v, T, R, NULL) == BIREF_ERR_INVALID);
    bad = s;
    bad.thickness_nm = -1;
    CHECK(biref_shade_hit(sh, &bad, v, T, R, NULL) == BIREF_ERR_INVALID);
    biref_shader *refused = NULL;
    CHECK(biref_shader_create(NULL, &pol, NULL, &refused, msg, sizeof msg) == BIREF_ERR_INVALID && !refused);
    CHECK(strstr(msg, "world-fixed") != NULL);

    biref_shader_destroy(num);
    biref_shader_destroy(sh);
    biref_spectral_destroy(sp);
    return test_report("test_shading");
}
