/* The path-group expansion's packet kernel (src/spectral/expansion_packet.h) on every instruction
 * set this CPU runs: its results against the scalar double expansion (biref_integrate_footprint
 * of a hit's state for the transmission, of its flip for the reflection) on random seeded hits,
 * with point and prefiltered look-ups, adaptive and fixed orders; and small renders of the
 * examples against the scalar path (mean dE00 <= 0.02, max <= 0.5), the same for 1 and 2
 * threads, world-fixed polarizers included (a real light per hit and side). */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"
#include "optics/slab_internal.h"
#include "render/render_internal.h"
#include "spectral/expansion_packet.h"
#include "spectral/integrator_internal.h"
#include "spectral/phase_prefilter.h"
#include "spectral/spectral_internal.h"
#include "test_cases.h"
#include "test_packet_lights.h"
#include "test_render_util.h"

static int quick;

/* A random slab: mostly 0.2-5 mm (groups of different orders do not interfere), every fifth
 * 1-200 um (thin: they do, or the coherent regime), every seventh in a denser surround (total
 * reflection inside: the scalar path); any axis, weak to strong birefringence, 0-89 deg. */
static void random_slab(test_rng *rng, int k, biref_slab *s, double *theta)
{
    test_random_axis(rng, s->axis);
    s->eta_o = test_uniform(rng, 1.3, 1.8);
    s->eta_e = s->eta_o + test_uniform(rng, -0.3, 0.3);
    s->thickness_nm = k % 5 == 4 ? exp(test_uniform(rng, log(1e3), log(2e5))) : exp(test_uniform(rng, log(2e5), log(5e6)));
    s->eta_i = k % 7 == 6 ? test_uniform(rng, 1.5, 2.0) : 1.0;
    *theta = test_uniform(rng, 0, 89) * M_PI / 180;
}

/* A random footprint: every leg's change across the pixel from none through sub-nanometre to many
 * fringes, some legs still. */
static void random_footprint(test_rng *rng, const biref_phase_prefilter *pf, biref_opl_footprint *fp)
{
    fp->pf = pf;
    const double scale = exp(test_uniform(rng, log(1e-5), log(3e4)));
    for (int l = 0; l < 4; l++)
        for (int k = 0; k < 2; k++) fp->grad[l][k] = test_uniform(rng, 0, 1) < 0.2 ? 0.0 : scale * test_uniform(rng, -1, 1);
}

/* The kernels against the scalar expansion on n random hits (footprints when pf is not NULL),
 * under the options o; every hit the lanes take within 1e-12 in XYZ (5e-12 with footprints), and
 * most thick ones taken. */
static void kernels_vs_scalar(const biref_expansion_opts *xo, int prefilter, unsigned seed)
{
    const biref_spectral *sp = test_sp();
    biref_phase_prefilter *pf = NULL;
    biref_integrator *it = NULL;
    if (prefilter) CHECK(biref_phase_prefilter_create(sp, &pf) == BIREF_OK);
    biref_integrator_options io;
    biref_integrator_options_default(&io);
    io.method = BIREF_METHOD_EXPANSION;
    io.expansion = *xo;
    setenv("BIREF_SIMD", "scalar", 1);
    CHECK(biref_integrator_create(sp, &io, &it, NULL, 0) == BIREF_OK);
    unsetenv("BIREF_SIMD");
    enum { N = 403 };
    const size_t want_n = quick ? 101 : N;
    static biref_packet_hit hits[N];
    static biref_opl_footprint fps[N];
    static double wantT[N][3], wantR[N][3], T[N][3], R[N][3];
    static unsigned char scalar[N], thick[N], thin[N];
    test_rng rng = {seed};
    const double w_in[2] = {0.7, 0.3}, mask[2] = {0.4, 1.0};
    biref_light light;
    CHECK(biref_light_sp(w_in, mask, &light) == BIREF_OK);
    size_t n = 0;
    while (n < want_n) {
        biref_slab s;
        double theta;
        biref_slab_state st, fl;
        random_slab(&rng, (int)n, &s, &theta);
        if (biref_slab_prepare_trusted(&s, theta, &st) != BIREF_OK) continue;
        hits[n] = (biref_packet_hit){s.eta_o, s.eta_e, {0, 0, 0}, s.thickness_nm, s.eta_i, s.eta_i * sin(theta)};
        biref_axis_unit_unchecked(s.axis, hits[n].axis);
        thick[n] = s.eta_i == 1.0 && s.thickness_nm > 4e5 && theta < 80 * M_PI / 180;
        thin[n] = s.eta_i == 1.0 && s.thickness_nm > 2e4 && s.thickness_nm < 2e5 && theta < 60 * M_PI / 180;
        biref_opl_footprint fpR;
        if (pf) {
            random_footprint(&rng, pf, &fps[n]);
            biref_opl_footprint_flip(&fps[n], &fpR);
        }
        biref_slab_state_flip(&st, &fl);
        biref_integration res;
        if (biref_integrate_footprint(it, &st, pf ? &fps[n] : NULL, BIREF_SIDE_TRANSMISSION, &light, &res) != BIREF_OK)
            continue;
        memcpy(wantT[n], res.T, sizeof res.T);
        if (biref_integrate_footprint(it, &fl, pf ? &fpR : NULL, BIREF_SIDE_REFLECTION, &light, &res) != BIREF_OK)
            continue;
        memcpy(wantR[n], res.R, sizeof res.R);
        n++;
    }
    for (int isa = BIREF_SIMD_BASELINE; isa < BIREF_SIMD_COUNT; isa++) {
        if (!biref_simd_isa_supported((biref_simd_isa)isa)) continue;
        /* The kernel's weights are the detected power fractions, the mask itself (the scalar
         * expansion's analyzer P = diag(sqrt(mask)) passes mask of each output's intensity). */
        biref_simd_expansion_kernel((biref_simd_isa)isa)(sp, xo, w_in, mask, hits, n, T, R, scalar, pf ? fps : NULL, NULL);
        double worst = 0.0;
        int taken = 0, n_thick = 0, thick_taken = 0, n_thin = 0, thin_taken = 0;
        for (size_t k = 0; k < n; k++) {
            n_thick += thick[k];
            n_thin += thin[k];
            if (scalar[k]) continue;
            taken++;
            thick_taken += thick[k];
            thin_taken += thin[k];
            for (int b = 0; b < 3; b++)
                worst = fmax(worst, fmax(fabs(T[k][b] - wantT[k][b]), fabs(R[k][b] - wantR[k][b])));
        }
        printf("%s%s, order %d, tolerance %g: %d of %zu hits in lanes (%d of %d thick, %d of %d 20-200 um), "
               "max |packet - scalar| = %.3g\n",
               biref_simd_isa_name((biref_simd_isa)isa), pf ? " prefiltered" : "", xo->order, xo->tolerance, taken, n,
               thick_taken, n_thick, thin_taken, n_thin, worst);
        CHECK(worst < (pf ? 5e-12 : 1e-12)); /* box averages: two look-ups per integral */
        CHECK(thick_taken * 10 >= n_thick * 7);
        CHECK(thin_taken * 2 >= n_thin); /* groups of different orders interfere there */
    }
    biref_integrator_destroy(it);
    biref_phase_prefilter_destroy(pf);
}

static void hit_kernels_vs_scalar_adaptive_orders(void)
{
    biref_expansion_opts xo;
    biref_expansion_opts_default(&xo);
    kernels_vs_scalar(&xo, 0, 0xe9a1u);
    xo.tolerance = 1e-5; /* higher orders */
    kernels_vs_scalar(&xo, 0, 0xe9a2u);
}

static void hit_kernels_vs_scalar_fixed_order(void)
{
    biref_expansion_opts xo;
    biref_expansion_opts_default(&xo);
    xo.order = 2;
    kernels_vs_scalar(&xo, 0, 0xe9a3u);
}

static void prefiltered_hit_kernels_vs_scalar(void)
{
    biref_expansion_opts xo;
    biref_expansion_opts_default(&xo);
    kernels_vs_scalar(&xo, 1, 0xe9a4u);
}

/* The kernels under a real light per hit and side (world-fixed polarizers' form) against the
 * scalar expansion under the same matrices (biref_light_coherency + biref_light_set_analyzer:
 * series_polarized, one direction, a negative result moved towards the paths' energy), point and
 * prefiltered; and through the integrator's door (biref_integrate_packet_hits_lit). */
static void light_per_hit_kernels_vs_scalar(void)
{
    const biref_spectral *sp = test_sp();
    biref_phase_prefilter *pf = NULL;
    CHECK(biref_phase_prefilter_create(sp, &pf) == BIREF_OK);
    biref_integrator_options io;
    biref_integrator_options_default(&io);
    io.method = BIREF_METHOD_EXPANSION;
    biref_integrator *it = NULL, *scalar_it = NULL;
    CHECK(biref_integrator_create(sp, &io, &it, NULL, 0) == BIREF_OK);
    setenv("BIREF_SIMD", "scalar", 1);
    CHECK(biref_integrator_create(sp, &io, &scalar_it, NULL, 0) == BIREF_OK);
    unsetenv("BIREF_SIMD");
    enum { N = 301 };
    const size_t want_n = quick ? 81 : N;
    static biref_packet_hit hits[N];
    static biref_packet_hit_light lights[N];
    static biref_opl_footprint fps[N];
    static double want[2][N][2][3], T[N][3], R[N][3];
    static unsigned char scalar[N], thick[N];
    test_rng rng = {0xe9a5u};
    size_t n = 0;
    while (n < want_n) {
        biref_slab s;
        double theta;
        biref_slab_state st, fl;
        random_slab(&rng, (int)n, &s, &theta);
        if (biref_slab_prepare_trusted(&s, theta, &st) != BIREF_OK) continue;
        hits[n] = (biref_packet_hit){s.eta_o, s.eta_e, {0, 0, 0}, s.thickness_nm, s.eta_i, s.eta_i * sin(theta)};
        biref_axis_unit_unchecked(s.axis, hits[n].axis);
        thick[n] = s.eta_i == 1.0 && s.thickness_nm > 4e5 && theta < 80 * M_PI / 180;
        random_real_light(&rng, &lights[n].T);
        random_real_light(&rng, &lights[n].R);
        random_footprint(&rng, pf, &fps[n]);
        biref_opl_footprint fpR;
        biref_opl_footprint_flip(&fps[n], &fpR);
        biref_slab_state_flip(&st, &fl);
        int fine = 1;
        for (int f = 0; f < 2; f++)
            for (int side = 0; side < 2; side++) {
                double complex C[2][2], P[2][2];
                light_matrices(side ? &lights[n].R : &lights[n].T, C, P);
                biref_light l;
                biref_light_coherency((const double complex(*)[2])C, &l);
                biref_light_set_analyzer(&l, (const double complex(*)[2])P);
                biref_integration res;
                fine &= biref_integrate_footprint(scalar_it, side ? &fl : &st, f ? (side ? &fpR : &fps[n]) : NULL,
                                                  side ? BIREF_SIDE_REFLECTION : BIREF_SIDE_TRANSMISSION, &l,
                                                  &res) == BIREF_OK;
                memcpy(want[f][n][side], side ? res.R : res.T, sizeof res.T);
            }
        n += fine;
    }
    double moved = 0.0; /* the footprints matter */
    for (size_t k = 0; k < n; k++)
        for (int b = 0; b < 3; b++) moved = fmax(moved, fabs(want[1][k][0][b] - want[0][k][0][b]));
    CHECK(moved > 0.01);
    for (int isa = BIREF_SIMD_BASELINE; isa < BIREF_SIMD_COUNT; isa++) {
        if (!biref_simd_isa_supported((biref_simd_isa)isa)) continue;
        for (int f = 0; f < 2; f++) {
            biref_simd_expansion_kernel((biref_simd_isa)isa)(sp, &io.expansion, NULL, NULL, hits, n, T, R, scalar,
                                                             f ? fps : NULL, lights);
            double worst = 0.0;
            int n_thick = 0, thick_taken = 0;
            for (size_t k = 0; k < n; k++) {
                n_thick += thick[k];
                if (scalar[k]) continue;
                thick_taken += thick[k];
                for (int b = 0; b < 3; b++)
                    worst = fmax(worst, fmax(fabs(T[k][b] - want[f][k][0][b]), fabs(R[k][b] - want[f][k][1][b])));
            }
            printf("%s%s, light per hit: %d of %d thick hits in lanes, max |packet - scalar| = %.3g (point vs box "
                   "up to %.2g)\n",
                   biref_simd_isa_name((biref_simd_isa)isa), f ? " prefiltered" : "", thick_taken, n_thick, worst, moved);
            CHECK(worst < (f ? 5e-12 : 1e-12));
            CHECK(thick_taken * 10 >= n_thick * 7);
        }
    }
    /* The integrator's door: the expansion takes them as well. */
    biref_integrate_packet_hits_lit(it, hits, NULL, n, lights, T, R, scalar);
    int taken = 0;
    for (size_t k = 0; k < n; k++)
        if (!scalar[k]) {
            taken++;
            for (int b = 0; b < 3; b++) CHECK_NEAR(R[k][b], want[0][k][1][b], 1e-12);
        }
    CHECK(taken > 0);
    biref_integrator_destroy(it);
    biref_integrator_destroy(scalar_it);
    biref_phase_prefilter_destroy(pf);
}

static float *render_with(const char *path, const char *isa, biref_antialias aa, int threads, int w, int h)
{
    biref_scene sc;
    char msg[256];
    if (biref_scene_load(path, &sc, msg, sizeof msg) != BIREF_OK) {
        fprintf(stderr, "%s: %s\n", path, msg);
        return NULL;
    }
    sc.camera.width = w;
    sc.camera.height = h;
    setenv("BIREF_SIMD", isa, 1);
    biref_render_options opt;
    biref_render_options_default(&opt);
    opt.method = BIREF_METHOD_EXPANSION;
    opt.threads = threads;
    opt.antialias = aa;
    biref_renderer *r = NULL;
    float *xyz = NULL;
    if (biref_renderer_create(test_sp(), &sc, &opt, &r, msg, sizeof msg) == BIREF_OK) {
        xyz = malloc((size_t)w * h * 3 * sizeof *xyz);
        if (xyz && biref_render_image(r, xyz, NULL, NULL, NULL) != BIREF_OK) CHECK(0);
    }
    unsetenv("BIREF_SIMD");
    biref_renderer_destroy(r);
    return xyz;
}

/* Small expansion renders of the examples on the CPU's fastest path against the scalar one, point
 * and prefiltered; the same image on one thread. */
static void renders_vs_scalar(void)
{
    const char *scenes[] = {"examples/fig9a.json", "examples/fig9c_analyzer45.json", "examples/default.json",
                            "examples/fig9c.json", "examples/fig9b.json"};
    const size_t n_scenes = quick ? 2 : sizeof scenes / sizeof scenes[0];
    const int W = quick ? 24 : 48, H = quick ? 14 : 27;
    const size_t n = (size_t)W * H;
    const char *isa = biref_simd_isa_name(biref_simd_isa_choose());
    for (int f = 0; f < 2; f++) {
        biref_antialias aa = f ? BIREF_ANTIALIAS_PREFILTER : BIREF_ANTIALIAS_NONE;
        /* Quick (sanitizer) runs: each prefiltered renderer builds its own antiderivative table,
         * so only fig9a there. */
        for (size_t i = 0; i < (quick && f ? 1 : n_scenes); i++) {
            float *ref = render_with(scenes[i], "scalar", aa, 2, W, H);
            float *a = render_with(scenes[i], isa, aa, 2, W, H);
            float *b = render_with(scenes[i], isa, aa, 1, W, H);
            CHECK(ref && a && b);
            if (ref && a && b) {
                CHECK(memcmp(a, b, n * 3 * sizeof *a) == 0);
                double sum = 0.0, worst = 0.0;
                for (size_t k = 0; k < n; k++) {
                    double x[3] = {ref[3 * k], ref[3 * k + 1], ref[3 * k + 2]};
                    double y[3] = {a[3 * k], a[3 * k + 1], a[3 * k + 2]};
                    double d = biref_delta_e00_xyz(x, y);
                    sum += d;
                    worst = fmax(worst, d);
                }
                printf("%s, %s, %s: dE00 to the scalar expansion mean %.2g, max %.2g\n", scenes[i], isa,
                       f ? "prefiltered" : "point", sum / (double)n, worst);
                CHECK(sum / (double)n <= 0.02 && worst <= 0.5);
            }
            free(ref);
            free(a);
            free(b);
        }
    }
}

int main(int argc, char **argv)
{
    quick = getenv("BIREF_TEST_QUICK") != NULL;
    static const test_case cases[] = {
        {"hit_kernels_vs_scalar_adaptive_orders", hit_kernels_vs_scalar_adaptive_orders},
        {"hit_kernels_vs_scalar_fixed_order", hit_kernels_vs_scalar_fixed_order},
        {"prefiltered_hit_kernels_vs_scalar", prefiltered_hit_kernels_vs_scalar},
        {"light_per_hit_kernels_vs_scalar", light_per_hit_kernels_vs_scalar},
        {"renders_vs_scalar", renders_vs_scalar},
    };
    return test_run_cases("test_expansion_packet", cases, TEST_COUNT(cases), argc, argv);
}
