/* The analytic method's packet kernel (src/spectral/analytic_packet.h) on every instruction set
 * this CPU runs, in float lanes and in double: which states it takes, its results against the
 * scalar double worker (biref_analytic_mixed) on random slabs, and small renders of the examples
 * against the scalar path (mean dE00 <= 0.02, max <= 0.5; in fact <= 1e-3), the same for 1 and 2
 * threads. */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"
#include "optics/slab_internal.h"
#include "render/render_internal.h"
#include "spectral/analytic_packet.h"
#include "spectral/analytic_terms.h"
#include "spectral/integrator_internal.h"
#include "spectral/phase_prefilter.h"
#include "spectral/spectral_internal.h"
#include "test_cases.h"
#include "test_packet_lights.h"
#include "test_render_util.h"

static int quick;

/* A random slab: thin to thick, weak to strong birefringence, every fourth in a denser surround
 * (total reflection inside). */
static void random_slab(test_rng *rng, int k, biref_slab *s, double *theta)
{
    test_random_axis(rng, s->axis);
    s->eta_o = test_uniform(rng, 1.3, 1.8);
    s->eta_e = s->eta_o + test_uniform(rng, -0.3, 0.3);
    s->thickness_nm = exp(test_uniform(rng, log(20.0), log(5e6)));
    s->eta_i = k % 4 == 3 ? test_uniform(rng, 1.5, 2.0) : 1.0;
    *theta = test_uniform(rng, 0, 89.5) * M_PI / 180;
}

/* Eligible exactly when nothing is evanescent or complex and the slab is not in the coherent
 * regime; biref_coherent_real_paths agrees with biref_coherent_plan; the flip does not change
 * the answer. */
static void test_packet_eligible_unless_total_reflection_or_coherent_regime(void)
{
    biref_spectral *sp = NULL;
    CHECK(biref_spectral_create(NULL, &sp, NULL, 0) == BIREF_OK);
    test_rng rng = {0x9ac4e7u};
    int eligible = 0, tir = 0, coherent = 0;
    for (int k = 0; k < (quick ? 400 : 4000); k++) {
        biref_slab s;
        double theta;
        random_slab(&rng, k, &s, &theta);
        biref_slab_state st, fl;
        if (biref_slab_prepare(&s, theta, &st) != BIREF_OK) continue;
        biref_slab_state_flip(&st, &fl);
        int e = biref_packet_eligible(sp, &st);
        CHECK(e == biref_packet_eligible(sp, &fl));
        int is_coherent = biref_coherent_plan(sp, &st) != NULL;
        if (!st.total_reflection) CHECK(biref_coherent_real_paths(&st) == is_coherent);
        CHECK(e == (!st.total_reflection && !is_coherent));
        eligible += e;
        tir += st.total_reflection;
        coherent += !st.total_reflection && is_coherent;
    }
    printf("eligible %d, total reflection %d, coherent regime %d\n", eligible, tir, coherent);
    CHECK(eligible > 0 && tir > 0 && coherent > 0);
    biref_spectral_destroy(sp);
}

/* An unknown or unsupported BIREF_SIMD is refused by biref_integrator_create with one line
 * naming the accepted values, for every method; a known one is taken; unset or empty: automatic. */
static void unknown_simd_value_is_refused(void)
{
    biref_spectral *sp = NULL;
    CHECK(biref_spectral_create(NULL, &sp, NULL, 0) == BIREF_OK);
    biref_integrator_options o;
    biref_integrator_options_default(&o);
    biref_integrator *it = NULL;
    char msg[256] = "";
    const char *bad[] = {"avx9", "AVX2", "sse2", " baseline"};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        for (int m = 0; m < 2; m++) {
            o.method = m ? BIREF_METHOD_EXPANSION : BIREF_METHOD_ANALYTIC;
            setenv("BIREF_SIMD", bad[k], 1);
            CHECK(biref_integrator_create(sp, &o, &it, msg, sizeof msg) == BIREF_ERR_INVALID && !it);
            CHECK(strstr(msg, "expected scalar, baseline, avx2 or avx512") != NULL && !strchr(msg, '\n'));
        }
    o.method = BIREF_METHOD_ANALYTIC;
    for (int isa = 0; isa < BIREF_SIMD_COUNT; isa++) {
        setenv("BIREF_SIMD", biref_simd_isa_name((biref_simd_isa)isa), 1);
        biref_status s = biref_integrator_create(sp, &o, &it, msg, sizeof msg);
        if (biref_simd_isa_supported((biref_simd_isa)isa)) {
            CHECK(s == BIREF_OK && biref_integrator_simd(it) == (biref_simd_isa)isa);
        } else {
            CHECK(s == BIREF_ERR_INVALID && strstr(msg, "this CPU cannot run it") != NULL);
        }
        biref_integrator_destroy(it);
        it = NULL;
    }
    setenv("BIREF_SIMD", "", 1);
    CHECK(biref_integrator_create(sp, &o, &it, NULL, 0) == BIREF_OK && it);
    biref_integrator_destroy(it);
    unsetenv("BIREF_SIMD");
    biref_spectral_destroy(sp);
}

/* The hits as the kernel reads them (biref_packet_hits: field by field) in buf, which holds
 * BIREF_PACKET_HIT_FIELDS * n doubles. */
static biref_packet_hits columns(const biref_packet_hit *h, size_t n, double *buf)
{
    for (size_t k = 0; k < n; k++) biref_packet_hit_put(buf, n, k, &h[k]);
    return (biref_packet_hits){buf, n};
}

/* The double kernel of a path for the analytic method (pairs 0) or analytic-pairs (1). */
static biref_packet_hits_kernel f64_kernel(int isa, int pairs)
{
    return pairs ? biref_simd_hits_kernel_f64_pairs((biref_simd_isa)isa) : biref_simd_hits_kernel_f64((biref_simd_isa)isa);
}

/* The kernels of a path: k = 0 the integrator's (float lanes on AVX2 and AVX-512), k = 1 the
 * double one when it is another (NULL when not). */
static biref_packet_hits_kernel path_kernel(int isa, int k, int pairs)
{
    biref_packet_hits_kernel fast = pairs ? biref_simd_hits_kernel_pairs((biref_simd_isa)isa)
                                          : biref_simd_hits_kernel((biref_simd_isa)isa),
                             f64 = f64_kernel(isa, pairs);
    return k == 0 ? fast : f64 != fast ? f64 : NULL;
}

/* Bounds on |kernel - scalar double path| in band-normalised XYZ: the double lanes to rounding,
 * the float lanes a few float roundings of each term (measured 1.0e-7 point, 1.3e-7 prefiltered). */
#define F64_LANES_XYZ 1e-12
#define F32_LANES_XYZ 1e-6

/* The kernels that prepare the hits themselves, against biref_slab_prepare_trusted and
 * biref_analytic_mixed of the state (transmission) and of its flip (reflection). A hit the kernel
 * takes must be one the scalar path would give it (biref_packet_eligible). */
static void hit_kernels_vs_scalar(int pairs)
{
    biref_spectral *sp = NULL;
    CHECK(biref_spectral_create(NULL, &sp, NULL, 0) == BIREF_OK);
    enum { N = 1001 };
    static biref_packet_hit hits[N];
    static double cols[BIREF_PACKET_HIT_FIELDS * N];
    static biref_slab_state states[N];
    static double wantT[N][3], wantR[N][3], T[N][3], R[N][3];
    static unsigned char scalar[N];
    test_rng rng = {0x417u};
    double w_in[2] = {0.6, 0.4}, mask[2] = {0.2, 1.0};
    size_t n = 0;
    int eligible = 0;
    while (n < N) {
        biref_slab s;
        double theta;
        random_slab(&rng, (int)n, &s, &theta);
        if (n % 50 == 7) theta = 89.99999 * M_PI / 180; /* grazing */
        if (biref_slab_prepare_trusted(&s, theta, &states[n]) != BIREF_OK) continue;
        hits[n] = (biref_packet_hit){s.eta_o, s.eta_e, {0, 0, 0}, s.thickness_nm, s.eta_i, s.eta_i * sin(theta)};
        biref_axis_unit_unchecked(s.axis, hits[n].axis);
        if (biref_packet_eligible(sp, &states[n])) {
            biref_slab_state fl;
            biref_slab_state_flip(&states[n], &fl);
            biref_analytic_mixed(sp, &states[n], BIREF_TRANSMISSION, pairs, w_in, mask, wantT[n]);
            biref_analytic_mixed(sp, &fl, BIREF_REFLECTION, pairs, w_in, mask, wantR[n]);
            eligible++;
        }
        n++;
    }
    const biref_packet_hits H = columns(hits, n, cols);
    for (int isa = BIREF_SIMD_BASELINE; isa < BIREF_SIMD_COUNT; isa++) {
        for (int kk = 0; kk < 2; kk++) {
            biref_packet_hits_kernel kernel = biref_simd_isa_supported((biref_simd_isa)isa) ? path_kernel(isa, kk, pairs) : NULL;
            if (!kernel) continue;
            const int f32 = kernel != f64_kernel(isa, pairs);
            kernel(sp, w_in, mask, &H, n, T, R, scalar, NULL, NULL);
            double worst = 0.0;
            int taken = 0, declined = 0;
            for (size_t k = 0; k < n; k++) {
                int e = biref_packet_eligible(sp, &states[k]);
                if (scalar[k]) {
                    declined += e;
                    continue;
                }
                CHECK(e);
                taken++;
                for (int b = 0; b < 3; b++)
                    worst = fmax(worst, fmax(fabs(T[k][b] - wantT[k][b]), fabs(R[k][b] - wantR[k][b])));
            }
            printf("%s%s%s: %d of %d eligible hits in lanes (%d declined), max |packet - scalar| = %.3g\n",
                   pairs ? "analytic-pairs " : "", biref_simd_isa_name((biref_simd_isa)isa), f32 ? " float lanes" : "",
                   taken, eligible, declined, worst);
            CHECK(worst < (f32 ? F32_LANES_XYZ : F64_LANES_XYZ));
            CHECK(declined <= eligible / 100);
        }
    }
    biref_spectral_destroy(sp);
}

static void test_hit_kernels_vs_scalar(void) { hit_kernels_vs_scalar(0); }
static void pairs_hit_kernels_vs_scalar(void) { hit_kernels_vs_scalar(1); }

/* A random footprint: every leg's change across the pixel from none through sub-nanometre (below
 * the point-width threshold) to many fringes, some legs still. */
static void random_footprint(test_rng *rng, const biref_phase_prefilter *pf, biref_opl_footprint *fp)
{
    fp->pf = pf;
    fp->disp = NULL;
    const double scale = exp(test_uniform(rng, log(1e-5), log(3e4)));
    for (int l = 0; l < 4; l++)
        for (int k = 0; k < 2; k++) fp->grad[l][k] = test_uniform(rng, 0, 1) < 0.2 ? 0.0 : scale * test_uniform(rng, -1, 1);
}

/* The hit kernels with footprints against the scalar prefiltered path (biref_integrate_footprint
 * of the state over the footprint, of its flip over the flipped footprint): every box average in
 * lanes must be the scalar one to rounding. Hits whose lanes differ in width (zero, below the
 * point threshold, wide) share packets. */
static void prefiltered_hit_kernels_vs_scalar(void)
{
    biref_spectral *sp = NULL;
    biref_phase_prefilter *pf = NULL;
    biref_integrator *it = NULL;
    CHECK(biref_spectral_create(NULL, &sp, NULL, 0) == BIREF_OK);
    CHECK(biref_phase_prefilter_create(sp, &pf) == BIREF_OK);
    biref_integrator_options io;
    biref_integrator_options_default(&io);
    CHECK(biref_integrator_create(sp, &io, &it, NULL, 0) == BIREF_OK);
    enum { N = 603 };
    static biref_packet_hit hits[N];
    static double cols[BIREF_PACKET_HIT_FIELDS * N];
    static biref_slab_state states[N];
    static biref_opl_footprint fps[N];
    static double wantT[N][3], wantR[N][3], plainT[N][3], T[N][3], R[N][3];
    static unsigned char scalar[N];
    test_rng rng = {0x5eedu};
    const double w_in[2] = {0.3, 0.7}, mask[2] = {1.0, 0.6};
    biref_light light;
    CHECK(biref_light_sp(w_in, mask, &light) == BIREF_OK);
    size_t n = 0;
    while (n < N) {
        biref_slab s;
        double theta;
        random_slab(&rng, (int)n, &s, &theta);
        if (biref_slab_prepare_trusted(&s, theta, &states[n]) != BIREF_OK || !biref_packet_eligible(sp, &states[n]))
            continue;
        hits[n] = (biref_packet_hit){s.eta_o, s.eta_e, {0, 0, 0}, s.thickness_nm, s.eta_i, s.eta_i * sin(theta)};
        biref_axis_unit_unchecked(s.axis, hits[n].axis);
        random_footprint(&rng, pf, &fps[n]);
        biref_opl_footprint fpR;
        biref_opl_footprint_flip(&fps[n], &fpR);
        biref_slab_state fl;
        biref_slab_state_flip(&states[n], &fl);
        biref_integration res;
        CHECK(biref_integrate_footprint(it, &states[n], &fps[n], BIREF_SIDE_TRANSMISSION, &light, &res) == BIREF_OK);
        memcpy(wantT[n], res.T, sizeof res.T);
        CHECK(biref_integrate_footprint(it, &fl, &fpR, BIREF_SIDE_REFLECTION, &light, &res) == BIREF_OK);
        memcpy(wantR[n], res.R, sizeof res.R);
        biref_analytic_mixed(sp, &states[n], BIREF_TRANSMISSION, 0, w_in, mask, plainT[n]);
        n++;
    }
    /* The footprints matter: the prefiltered results are not the point ones. */
    double moved = 0.0;
    for (size_t k = 0; k < n; k++)
        for (int b = 0; b < 3; b++) moved = fmax(moved, fabs(wantT[k][b] - plainT[k][b]));
    CHECK(moved > 0.05);
    const biref_packet_hits H = columns(hits, n, cols);
    for (int isa = BIREF_SIMD_BASELINE; isa < BIREF_SIMD_COUNT; isa++) {
        for (int kk = 0; kk < 2; kk++) {
            biref_packet_hits_kernel kernel = biref_simd_isa_supported((biref_simd_isa)isa) ? path_kernel(isa, kk, 0) : NULL;
            if (!kernel) continue;
            const int f32 = kernel != f64_kernel(isa, 0);
            kernel(sp, w_in, mask, &H, n, T, R, scalar, fps, NULL);
            double worst = 0.0;
            int taken = 0;
            for (size_t k = 0; k < n; k++) {
                if (scalar[k]) continue;
                taken++;
                for (int b = 0; b < 3; b++)
                    worst = fmax(worst, fmax(fabs(T[k][b] - wantT[k][b]), fabs(R[k][b] - wantR[k][b])));
            }
            printf("%s%s: %d of %zu prefiltered hits in lanes, max |packet - scalar| = %.3g (point vs box up to %.2g)\n",
                   biref_simd_isa_name((biref_simd_isa)isa), f32 ? " float lanes" : "", taken, n, worst, moved);
            CHECK(taken >= (int)n - (int)n / 100);
            CHECK(worst < (f32 ? F32_LANES_XYZ : 10 * F64_LANES_XYZ));
        }
    }
    biref_integrator_destroy(it);
    biref_phase_prefilter_destroy(pf);
    biref_spectral_destroy(sp);
}

/* The float lanes against the double lanes of the same set, hit by hit, on seeded random slabs,
 * angles (grazing ones too), footprints and lights (w_in, mask), for every hit count from 1 to 40
 * (packets with spare lanes in either half) and for a long run: every hit the double kernel takes
 * is taken, within F32_LANES_XYZ. */
static void float_lanes_vs_double_lanes_random_lights(void)
{
    biref_spectral *sp = NULL;
    biref_phase_prefilter *pf = NULL;
    CHECK(biref_spectral_create(NULL, &sp, NULL, 0) == BIREF_OK);
    CHECK(biref_phase_prefilter_create(sp, &pf) == BIREF_OK);
    enum { N = 509 };
    static biref_packet_hit hits[N];
    static double cols[BIREF_PACKET_HIT_FIELDS * N];
    static biref_opl_footprint fps[N];
    static double T[2][N][3], R[2][N][3];
    static unsigned char scalar[2][N];
    test_rng rng = {0xf32u};
    for (size_t k = 0; k < N; k++) {
        biref_slab s;
        double theta;
        random_slab(&rng, (int)k, &s, &theta);
        if (k % 37 == 5) theta = 89.9 * M_PI / 180;
        hits[k] = (biref_packet_hit){s.eta_o, s.eta_e, {0, 0, 0}, s.thickness_nm, s.eta_i, s.eta_i * sin(theta)};
        biref_axis_unit_unchecked(s.axis, hits[k].axis);
        random_footprint(&rng, pf, &fps[k]);
    }
    const biref_packet_hits H = columns(hits, N, cols);
    int runs = 0;
    for (int isa = BIREF_SIMD_BASELINE; isa < BIREF_SIMD_COUNT; isa++) {
        biref_packet_hits_kernel f32 = biref_simd_isa_supported((biref_simd_isa)isa) ? path_kernel(isa, 0, 0) : NULL,
                                 f64 = f32 ? path_kernel(isa, 1, 0) : NULL;
        if (!f64) continue; /* no float lanes on this path */
        double worst = 0.0;
        int taken = 0;
        for (size_t n = 1; n <= (quick ? 20 : 40) + 1; n++) {
            const size_t count = n <= (quick ? 20u : 40u) ? n : N; /* the last: all hits */
            const size_t k0 = count == N ? 0 : (n * 53) % (N - 40);
            const biref_packet_hits Hk = {H.v + k0, H.stride};
            const double a = test_uniform(&rng, 0, 1), b = test_uniform(&rng, 0, 1);
            const double w_in[2] = {a, 1 - a}, mask[2] = {b, test_uniform(&rng, 0, 1)};
            const biref_opl_footprint *fp = n % 2 ? fps + k0 : NULL;
            f32(sp, w_in, mask, &Hk, count, T[0], R[0], scalar[0], fp, NULL);
            f64(sp, w_in, mask, &Hk, count, T[1], R[1], scalar[1], fp, NULL);
            for (size_t k = 0; k < count; k++) {
                CHECK(scalar[0][k] == scalar[1][k]);
                if (scalar[1][k]) continue;
                taken++;
                for (int c = 0; c < 3; c++)
                    worst = fmax(worst, fmax(fabs(T[0][k][c] - T[1][k][c]), fabs(R[0][k][c] - R[1][k][c])));
            }
        }
        printf("%s: float lanes vs double lanes on %d hits, random lights, point and prefiltered: max |diff| = %.3g\n",
               biref_simd_isa_name((biref_simd_isa)isa), taken, worst);
        CHECK(taken > 100);
        CHECK(worst < F32_LANES_XYZ);
        runs++;
    }
    if (!runs) printf("no float lanes on this CPU\n");
    biref_phase_prefilter_destroy(pf);
    biref_spectral_destroy(sp);
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
    opt.threads = threads;
    opt.antialias = aa;
    biref_renderer *r = NULL;
    float *xyz = NULL;
    if (biref_renderer_create(test_sp(), &sc, &opt, &r, msg, sizeof msg) == BIREF_OK) {
        CHECK(!strcmp(biref_simd_isa_name(biref_integrator_simd(r->shader->it)), isa));
        xyz = malloc((size_t)w * h * 3 * sizeof *xyz);
        if (xyz && biref_render_image(r, xyz, NULL, NULL, NULL) != BIREF_OK) CHECK(0);
    }
    unsetenv("BIREF_SIMD");
    biref_renderer_destroy(r);
    return xyz;
}

/* Small renders of the examples on every path against the scalar double path (each renderer
 * builds its own look-up table: few renderers, so that the sanitizer build stays quick), with
 * point or prefiltered look-ups; the first two scenes also on one thread, which must give the
 * same image. */
static void renders_per_isa(biref_antialias aa)
{
    const char *scenes[] = {"examples/fig9a.json", "examples/aliasing/thick_grazing.json", "examples/default.json",
                            "examples/fig9b.json", "examples/fig9c.json"};
    const size_t n_scenes = quick ? 2 : sizeof scenes / sizeof scenes[0];
    const int W = quick ? 32 : 64, H = quick ? 18 : 36;
    const size_t n = (size_t)W * H;
    for (size_t i = 0; i < n_scenes; i++) {
        float *ref = render_with(scenes[i], "scalar", aa, 2, W, H);
        CHECK(ref != NULL);
        for (int isa = BIREF_SIMD_BASELINE; ref && isa < BIREF_SIMD_COUNT; isa++) {
            if (!biref_simd_isa_supported((biref_simd_isa)isa)) continue;
            const char *name = biref_simd_isa_name((biref_simd_isa)isa);
            float *a = render_with(scenes[i], name, aa, 2, W, H);
            CHECK(a != NULL);
            if (a && i < 2) { /* fig9a and the thick slab at grazing view */
                /* The same image on one thread (other packets: hits are grouped per tile of a row). */
                float *b = render_with(scenes[i], name, aa, 1, W, H);
                CHECK(b && memcmp(a, b, n * 3 * sizeof *a) == 0);
                free(b);
            }
            if (a) {
                double sum = 0.0, worst = 0.0;
                for (size_t k = 0; k < n; k++) {
                    double x[3] = {ref[3 * k], ref[3 * k + 1], ref[3 * k + 2]};
                    double y[3] = {a[3 * k], a[3 * k + 1], a[3 * k + 2]};
                    double d = biref_delta_e00_xyz(x, y);
                    sum += d;
                    worst = fmax(worst, d);
                }
                printf("%s, %s, %s: dE00 to the scalar path mean %.2g, max %.2g\n", scenes[i], name,
                       aa == BIREF_ANTIALIAS_PREFILTER ? "prefiltered" : "point", sum / (double)n, worst);
                CHECK(sum / (double)n <= 0.02 && worst <= 0.5);
                /* Far tighter in fact: every path within 1e-3 (the float lanes measured <= 1e-4). */
                CHECK(worst <= 1e-3);
            }
            free(a);
        }
        free(ref);
    }
}

static void test_renders_per_isa(void) { renders_per_isa(BIREF_ANTIALIAS_NONE); }

/* The renderer's default: prefiltered look-ups in the kernel's lanes. */
static void test_prefiltered_renders_per_isa(void) { renders_per_isa(BIREF_ANTIALIAS_PREFILTER); }

/* A random complex light: partially polarized light with a circular part (C01 = (S2 + i S3) / 2) and
 * a circular analyzer of either hand, or an elliptical one with random complex entries. */
static void random_complex_light(test_rng *rng, biref_packet_light *l)
{
    const double S1 = test_uniform(rng, -0.4, 0.4), S2 = test_uniform(rng, -0.4, 0.4), S3 = test_uniform(rng, -0.8, 0.8);
    l->C[0] = 0.5 * (1 + S1), l->C[1] = 0.5 * S2, l->C[2] = 0.5 * (1 - S1), l->Ci = 0.5 * S3;
    if (test_uniform(rng, 0, 1) < 0.5) {
        const double h = test_uniform(rng, 0, 1) < 0.5 ? 0.5 : -0.5; /* 0.5 [[1, i h], [-i h, 1]] */
        l->P[0] = 0.5, l->P[1] = 0, l->P[2] = 0, l->P[3] = 0.5;
        l->Pi[0] = 0, l->Pi[1] = h, l->Pi[2] = -h, l->Pi[3] = 0;
        return;
    }
    for (int q = 0; q < 4; q++) l->P[q] = test_uniform(rng, -0.7, 0.7), l->Pi[q] = test_uniform(rng, -0.7, 0.7);
}

/* The hit kernels under a light per hit (world-fixed polarizers' form, or complex: circular light
 * and analyzers) against the scalar general terms (biref_analytic_general of the state and of its
 * flip, with and without footprints), on every instruction set and through the integrator's door
 * (biref_integrate_packet_hits_lit). Complex lights take point look-ups only: prefiltered, the
 * kernel declines them. */
static void light_per_hit_kernels_vs_scalar(int complex_light, int pairs)
{
    biref_spectral *sp = NULL;
    biref_phase_prefilter *pf = NULL;
    CHECK(biref_spectral_create(NULL, &sp, NULL, 0) == BIREF_OK);
    CHECK(biref_phase_prefilter_create(sp, &pf) == BIREF_OK);
    enum { N = 301 };
    static biref_packet_hit hits[N];
    static double cols[BIREF_PACKET_HIT_FIELDS * N];
    static biref_packet_hit_light lights[N];
    static biref_opl_footprint fps[N];
    static double want[2][N][2][3], T[N][3], R[N][3];
    static unsigned char scalar[N];
    test_rng rng = {0x6e7u};
    /* Start clean: the kernels mark the hits they decline, and a real light leaves the imaginary
     * parts a complex one set. */
    memset(scalar, 0, sizeof scalar);
    memset(lights, 0, sizeof lights);
    size_t n = 0;
    while (n < N) {
        biref_slab s;
        double theta;
        biref_slab_state st, fl;
        random_slab(&rng, (int)n, &s, &theta);
        if (biref_slab_prepare_trusted(&s, theta, &st) != BIREF_OK || !biref_packet_eligible(sp, &st)) continue;
        hits[n] = (biref_packet_hit){s.eta_o, s.eta_e, {0, 0, 0}, s.thickness_nm, s.eta_i, s.eta_i * sin(theta)};
        biref_axis_unit_unchecked(s.axis, hits[n].axis);
        if (complex_light) {
            random_complex_light(&rng, &lights[n].T);
            random_complex_light(&rng, &lights[n].R);
        } else {
            random_real_light(&rng, &lights[n].T);
            random_real_light(&rng, &lights[n].R);
        }
        random_footprint(&rng, pf, &fps[n]);
        biref_opl_footprint fpR;
        biref_opl_footprint_flip(&fps[n], &fpR);
        biref_slab_state_flip(&st, &fl);
        double complex C[2][2], P[2][2];
        for (int f = 0; f < 2; f++) {
            light_matrices(&lights[n].T, C, P);
            biref_analytic_general(sp, &st, f ? &fps[n] : NULL, BIREF_TRANSMISSION, pairs, (const double complex(*)[2])C,
                                   (const double complex(*)[2])P, want[f][n][0]);
            light_matrices(&lights[n].R, C, P);
            biref_analytic_general(sp, &fl, f ? &fpR : NULL, BIREF_REFLECTION, pairs, (const double complex(*)[2])C,
                                   (const double complex(*)[2])P, want[f][n][1]);
        }
        n++;
    }
    const biref_packet_hits H = columns(hits, n, cols);
    for (int isa = BIREF_SIMD_BASELINE; isa < BIREF_SIMD_COUNT; isa++) {
        if (!biref_simd_isa_supported((biref_simd_isa)isa)) continue;
        for (int f = 0; f < 2; f++) {
            path_kernel(isa, 0, pairs)(sp, NULL, NULL, &H, n, T, R, scalar, f ? fps : NULL, lights);
            double worst = 0.0;
            int taken = 0;
            for (size_t k = 0; k < n; k++) {
                if (scalar[k]) continue;
                taken++;
                for (int b = 0; b < 3; b++)
                    worst = fmax(worst, fmax(fabs(T[k][b] - want[f][k][0][b]), fabs(R[k][b] - want[f][k][1][b])));
            }
            printf("%s%s, light per hit: %d of %zu hits in lanes, max |packet - scalar| = %.3g\n",
                   biref_simd_isa_name((biref_simd_isa)isa), f ? " prefiltered" : "", taken, n, worst);
            CHECK(worst < 1e-11);
            CHECK(complex_light && f ? taken == 0 : taken >= (int)n - (int)n / 50);
        }
    }
    /* The integrator's door: the analytic method takes them (the expansion's and the numeric
     * methods' lanes take them too: tests/test_expansion_packet.c, tests/test_numeric_lanes.c). */
    biref_integrator_options o;
    biref_integrator_options_default(&o);
    if (pairs) o.method = BIREF_METHOD_ANALYTIC_PAIRS;
    biref_integrator *it = NULL;
    CHECK(biref_integrator_create(sp, &o, &it, NULL, 0) == BIREF_OK);
    biref_integrate_packet_hits_lit(it, &H, NULL, n, lights, T, R, scalar);
    int taken = 0;
    for (size_t k = 0; k < n; k++)
        if (!scalar[k]) {
            taken++;
            for (int b = 0; b < 3; b++) CHECK_NEAR(T[k][b], want[0][k][0][b], 1e-11);
        }
    CHECK(taken > 0);
    biref_integrator_destroy(it);
    biref_phase_prefilter_destroy(pf);
    biref_spectral_destroy(sp);
}

static void general_light_hit_kernels_vs_scalar(void) { light_per_hit_kernels_vs_scalar(0, 0); }
static void complex_light_hit_kernels_vs_scalar(void) { light_per_hit_kernels_vs_scalar(1, 0); }
static void pairs_general_light_hit_kernels_vs_scalar(void) { light_per_hit_kernels_vs_scalar(0, 1); }
static void pairs_complex_light_hit_kernels_vs_scalar(void) { light_per_hit_kernels_vs_scalar(1, 1); }

int main(int argc, char **argv)
{
    quick = getenv("BIREF_TEST_QUICK") != NULL;
    static const test_case cases[] = {
        {"packet_eligible_unless_total_reflection_or_coherent_regime",
         test_packet_eligible_unless_total_reflection_or_coherent_regime},
        {"unknown_simd_value_is_refused", unknown_simd_value_is_refused},
        {"general_light_hit_kernels_vs_scalar", general_light_hit_kernels_vs_scalar},
        {"complex_light_hit_kernels_vs_scalar", complex_light_hit_kernels_vs_scalar},
        {"hit_kernels_vs_scalar_set_up", test_hit_kernels_vs_scalar},
        {"analytic_pairs_hit_kernels_vs_scalar", pairs_hit_kernels_vs_scalar},
        {"analytic_pairs_general_light_hit_kernels_vs_scalar", pairs_general_light_hit_kernels_vs_scalar},
        {"analytic_pairs_complex_light_hit_kernels_vs_scalar", pairs_complex_light_hit_kernels_vs_scalar},
        {"prefiltered_hit_kernels_vs_scalar", prefiltered_hit_kernels_vs_scalar},
        {"float_lanes_vs_double_lanes_random_lights", float_lanes_vs_double_lanes_random_lights},
        {"renders_per_isa_vs_scalar", test_renders_per_isa},
        {"prefiltered_renders_per_isa_vs_scalar", test_prefiltered_renders_per_isa},
    };
    return test_run_cases("test_analytic_packet", cases, TEST_COUNT(cases), argc, argv);
}
