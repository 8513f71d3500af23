/* The numeric methods in lanes across wavelengths (numeric_lanes.c) against the scalar double
 * path: their sincos against libm's; on seeded random slabs the four pair intensities, the
 * polarized sides and a hit's transmission with its flipped reflection against the sums of
 * biref_slab_jones_at one wavelength at a time, on every instruction set this processor runs. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "biref/biref.h"
#include "spectral/analytic_packet.h"
#include "spectral/numeric_lanes.h"
#include "spectral/spectral_internal.h"
#include "test_cases.h"
#include "test_render_util.h"

enum { SEED = 11 };

typedef void (*sincos_fn)(const double *x, int n, double *s, double *c);
static const sincos_fn SINCOS[BIREF_SIMD_COUNT] = {NULL, biref_numeric_lanes_sincos_baseline,
                                                   biref_numeric_lanes_sincos_avx2,
                                                   biref_numeric_lanes_sincos_avx512};

/* sin and cos of the same double as libm to 1e-15 absolute (libm is within an ulp), from tiny
 * arguments to 2^29 rad (a 1.4e9 nm path at 380 nm), negative ones too. */
static void sincos_matches_libm(void)
{
    enum { N = 4096 };
    static double x[N], s[N], c[N];
    test_rng r = {SEED};
    static const double SCALE[] = {1e-6, 1.0, 4.0, 1e3, 1e6, 0x1p29};
    for (int i = 0; i < N; i++) x[i] = test_uniform(&r, -1.0, 1.0) * SCALE[i % 6];
    x[0] = 0.0, x[1] = M_PI / 4, x[2] = -M_PI / 2, x[3] = 3 * M_PI / 4; /* quadrant edges */
    for (int isa = BIREF_SIMD_BASELINE; isa < BIREF_SIMD_COUNT; isa++) {
        if (!biref_simd_isa_supported((biref_simd_isa)isa)) continue;
        SINCOS[isa](x, N, s, c);
        double worst = 0.0;
        for (int i = 0; i < N; i++) worst = fmax(worst, fmax(fabs(s[i] - sin(x[i])), fabs(c[i] - cos(x[i]))));
        printf("sincos, %s: largest difference from libm %.3g\n", biref_simd_isa_name((biref_simd_isa)isa), worst);
        CHECK(worst <= 1e-15);
    }
}

/* A random slab as test_numeric_block draws them (indices 1.2-1.8, random axis, 10 nm - 5 mm,
 * a third in a dense surround with total reflection and evanescent legs). */
static int random_state(test_rng *r, int i, biref_slab_state *st)
{
    biref_slab s;
    s.eta_o = test_uniform(r, 1.2, 1.8);
    s.eta_e = test_uniform(r, 1.2, 1.8);
    test_random_axis(r, s.axis);
    s.thickness_nm = exp(test_uniform(r, log(10.0), log(5e6)));
    s.eta_i = i % 3 == 0 ? 1.9 : 1.0;
    return biref_slab_prepare(&s, test_uniform(r, 0.0, 1.55), st) == BIREF_OK;
}

/* The intensity under C through P of one Jones matrix, written out independently. */
static double detected(const biref_jones *J, const double complex C[2][2], const double complex P[2][2])
{
    double complex M[2][2];
    for (int a = 0; a < 2; a++)
        for (int c = 0; c < 2; c++) M[a][c] = J->m[a][0] * P[0][c] + J->m[a][1] * P[1][c];
    double v = 0.0;
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++)
            for (int c = 0; c < 2; c++) v += creal(C[a][b] * M[a][c] * conj(M[b][c]));
    return v;
}

/* The scalar path's sums: pairs of T and R, and the detected T, R and R of the flipped state. */
typedef struct {
    biref_spectrum pairs;
    double T[3], R[3], Rflip[3];
} sums;

static void scalar_sums(const biref_numeric_plan *plan, const biref_slab_state *st, const double complex C[2][2],
                        const double complex P[2][2], sums *s)
{
    memset(s, 0, sizeof *s);
    biref_slab_state fl;
    biref_slab_state_flip(st, &fl);
    for (int n = 0; n < plan->samples; n++) {
        biref_jones T, R, Tf, Rf;
        biref_slab_jones_at(st, plan->lambda[n], &T, &R);
        biref_slab_jones_at(&fl, plan->lambda[n], &Tf, &Rf);
        double PT[2][2], PR[2][2];
        biref_jones_intensity(&T, PT);
        biref_jones_intensity(&R, PR);
        const double dT = detected(&T, C, P), dR = detected(&R, C, P), dRf = detected(&Rf, C, P);
        for (int j = 0; j < 3; j++) {
            const double w = plan->weight[n][j];
            for (int a = 0; a < 2; a++)
                for (int o = 0; o < 2; o++) {
                    s->pairs.T[a][o][j] += w * PT[a][o];
                    s->pairs.R[a][o][j] += w * PR[a][o];
                }
            s->T[j] += w * dT, s->R[j] += w * dR, s->Rflip[j] += w * dRf;
        }
    }
}

static double max_diff(const double *a, const double *b, size_t n)
{
    double d = 0.0;
    for (size_t i = 0; i < n; i++) d = fmax(d, fabs(a[i] - b[i]));
    return d;
}

/* Complex interface coefficients with real paths do not occur in a slab with the same medium on
 * both sides (a complex coefficient means an evanescent wave); to check the lanes' complex
 * instantiation, each matrix is turned by a random phase (the comparison is algebra on the
 * state's data). */
static void complex_coefficients(test_rng *r, biref_slab_state *st)
{
    biref_complex(*m[])[2] = {st->top.t_down, st->top.r_down, st->top.r_up, st->top.t_up,
                              st->bottom.t_down, st->bottom.r_down, st->bottom.r_up, st->bottom.t_up};
    for (size_t k = 0; k < sizeof m / sizeof m[0]; k++) {
        const double complex turn = cexp(I * test_uniform(r, -M_PI, M_PI));
        for (int a = 0; a < 2; a++)
            for (int b = 0; b < 2; b++) m[k][a][b] *= turn;
    }
}

/* Every output of the lanes within 1e-12 of the scalar sums (band-normalised XYZ, at most ~1),
 * on each instruction set; most states must take the lanes (the rest, with evanescent legs,
 * the per-wavelength blocks). */
static void lanes_match_scalar_path(void)
{
    biref_spectral *sp = NULL;
    CHECK(biref_spectral_create(NULL, &sp, NULL, 0) == BIREF_OK);
    if (!sp) return;
    static const int SAMPLES[] = {1, 5, 8, 33, 100};
    const int states_per_plan = test_quick() ? 20 : 80;
    test_rng r = {SEED + 1};
    for (int isa = BIREF_SIMD_BASELINE; isa < BIREF_SIMD_COUNT; isa++) {
        if (!biref_simd_isa_supported((biref_simd_isa)isa)) continue;
        double worst = 0.0;
        int compared = 0, in_lanes = 0;
        for (size_t ns = 0; ns < sizeof SAMPLES / sizeof SAMPLES[0]; ns++) {
            biref_numeric_plan *plan = NULL;
            CHECK(biref_numeric_plan_create(sp, SAMPLES[ns], &plan, NULL, 0) == BIREF_OK);
            if (!plan) continue;
            plan->isa = isa;
            for (int i = 0; i < states_per_plan; i++) {
                biref_slab_state st;
                if (!random_state(&r, i, &st)) continue;
                /* a random coherency (Hermitian, trace 1) and analyzer, or none */
                const double a = test_uniform(&r, 0, 1), g = test_uniform(&r, -0.5, 0.5);
                const double complex C[2][2] = {{a, g * sqrt(a * (1 - a)) * (0.6 + 0.8 * I)},
                                                {g * sqrt(a * (1 - a)) * (0.6 - 0.8 * I), 1 - a}};
                double complex P[2][2] = {{test_uniform(&r, -1, 1), test_uniform(&r, -1, 1) * I},
                                                {test_uniform(&r, -1, 1), test_uniform(&r, -1, 1)}};
                /* i % 4: no analyzer, a complex one, a real one */
                const int analyzer = i % 4 != 0;
                if (i % 4 == 3) P[0][1] = creal(P[0][1]) + 0.3, P[1][0] = creal(P[1][0]);
                if (i % 5 == 1) complex_coefficients(&r, &st);
                const double complex Id[2][2] = {{1, 0}, {0, 1}};
                sums want;
                scalar_sums(plan, &st, C, analyzer ? P : Id, &want);
                biref_spectrum got;
                double T[3], R[3], hT[3], hR[3];
                biref_spectrum_numeric(plan, &st, &got);
                biref_spectrum_numeric_polarized(plan, &st, BIREF_TRANSMISSION, C, analyzer ? P : NULL, T);
                biref_spectrum_numeric_polarized(plan, &st, BIREF_REFLECTION, C, analyzer ? P : NULL, R);
                biref_numeric_hit(plan, &st, C, analyzer ? P : NULL, hT, hR);
                double d = max_diff(&got.T[0][0][0], &want.pairs.T[0][0][0], 12);
                d = fmax(d, max_diff(&got.R[0][0][0], &want.pairs.R[0][0][0], 12));
                d = fmax(d, fmax(max_diff(T, want.T, 3), max_diff(R, want.R, 3)));
                d = fmax(d, fmax(max_diff(hT, want.T, 3), max_diff(hR, want.Rflip, 3)));
                worst = fmax(worst, d);
                biref_numeric_lanes_job job;
                job.outputs = BIREF_NL_T;
                job.pairs = 1;
                in_lanes += biref_numeric_lanes_run(plan, &st, &job);
                compared++;
            }
            biref_numeric_plan_destroy(plan);
        }
        printf("%s: %d states (%d in lanes), largest difference from the scalar sums %.3g\n",
               biref_simd_isa_name((biref_simd_isa)isa), compared, in_lanes, worst);
        CHECK(compared > 3 * states_per_plan && in_lanes > compared / 2);
        CHECK(worst <= 1e-12);
    }
    biref_spectral_destroy(sp);
}

/* The renderer's door: packets of random hits (the analytic kernel's set-up in lanes across hits,
 * then each hit's wavelengths in lanes) against the per-wavelength path (biref_slab_prepare, a
 * scalar plan), under the paper's s/p light, a complex light and each hit's own real lights (as
 * the renderer resolves world-fixed polarizers). */
static void packet_hits_match_scalar_path(void)
{
    biref_spectral *sp = NULL;
    CHECK(biref_spectral_create(NULL, &sp, NULL, 0) == BIREF_OK);
    biref_numeric_plan *plan = NULL, *ref = NULL;
    if (!sp || biref_numeric_plan_create(sp, 40, &plan, NULL, 0) != BIREF_OK ||
        biref_numeric_plan_create(sp, 40, &ref, NULL, 0) != BIREF_OK) {
        CHECK(0);
        biref_numeric_plan_destroy(plan);
        biref_spectral_destroy(sp);
        return;
    }
    ref->isa = BIREF_SIMD_SCALAR;
    enum { N = 203 };
    static biref_packet_hit hits[N];
    static double cols[BIREF_PACKET_HIT_FIELDS * N];
    const biref_packet_hits H = {cols, N};
    static double T[N][3], R[N][3];
    static unsigned char scalar[N];
    static biref_packet_hit_light lit[N];
    test_rng r = {SEED + 2};
    const double complex C_sp[2][2] = {{0.75, 0}, {0, 0.25}}, P_s[2][2] = {{1, 0}, {0, 0}};
    const double complex C_gen[2][2] = {{0.6, 0.1 + 0.2 * I}, {0.1 - 0.2 * I, 0.4}};
    const double complex P_gen[2][2] = {{0.5, 0.5 * I}, {-0.5 * I, 0.5}};
    for (int isa = BIREF_SIMD_BASELINE; isa < BIREF_SIMD_COUNT; isa++) {
        if (!biref_simd_isa_supported((biref_simd_isa)isa)) continue;
        plan->isa = isa;
        double worst = 0.0;
        int taken = 0;
        /* the s/p light through an s analyzer, a complex one, each hit's own, the complex one without analyzer */
        for (int light = 0; light < 4; light++) {
            for (int k = 0; k < N; k++) {
                biref_packet_hit *h = &hits[k];
                h->eta_o = test_uniform(&r, 1.2, 1.8);
                h->eta_e = test_uniform(&r, 1.2, 1.8);
                test_random_axis(&r, h->axis);
                h->thickness_nm = exp(test_uniform(&r, log(10.0), log(5e6)));
                h->eta_i = k % 5 == 0 ? 1.9 : 1.0;
                h->K = h->eta_i * sin(test_uniform(&r, 0.0, 1.55));
                for (int side = 0; side < 2; side++) { /* a real coherency e e^T + diag and a real analyzer */
                    biref_packet_light *pl = side ? &lit[k].R : &lit[k].T;
                    const double e0 = test_uniform(&r, -1, 1), e1 = test_uniform(&r, -1, 1), u = test_uniform(&r, 0, 0.5);
                    pl->C[0] = e0 * e0 + u, pl->C[1] = e0 * e1, pl->C[2] = e1 * e1 + u;
                    for (int q = 0; q < 4; q++) pl->P[q] = test_uniform(&r, -1, 1);
                    if ((k + side) % 3 == 0) { /* a linear analyzer: the projector a a^T (one term) */
                        const double t = test_uniform(&r, 0, M_PI), a0 = cos(t), a1 = sin(t);
                        pl->P[0] = a0 * a0, pl->P[1] = pl->P[2] = a0 * a1, pl->P[3] = a1 * a1;
                    }
                }
            }
            const double complex(*C)[2] = light ? C_gen : C_sp, (*P)[2] = light == 3 ? NULL : light ? P_gen : P_s;
            for (size_t k = 0; k < N; k++) biref_packet_hit_put(cols, N, k, &hits[k]);
            biref_numeric_packet_hits(plan, C, P, light == 2 ? lit : NULL, &H, N, T, R, scalar);
            for (int k = 0; k < N; k++) {
                if (scalar[k]) continue;
                const biref_slab s = {hits[k].eta_o, hits[k].eta_e, {hits[k].axis[0], hits[k].axis[1], hits[k].axis[2]},
                                      hits[k].thickness_nm, hits[k].eta_i};
                biref_slab_state st;
                if (biref_slab_prepare(&s, asin(hits[k].K / hits[k].eta_i), &st) != BIREF_OK) continue;
                double wT[3], wR[3];
                if (light == 2) { /* each side under its own light, the reflection on the flipped state */
                    double complex L[2][2][2], A[2][2][2];
                    for (int side = 0; side < 2; side++) {
                        const biref_packet_light *pl = side ? &lit[k].R : &lit[k].T;
                        L[side][0][0] = pl->C[0], L[side][0][1] = L[side][1][0] = pl->C[1], L[side][1][1] = pl->C[2];
                        for (int q = 0; q < 4; q++) A[side][q / 2][q % 2] = pl->P[q];
                    }
                    biref_slab_state fl;
                    biref_slab_state_flip(&st, &fl);
                    biref_spectrum_numeric_polarized(ref, &st, BIREF_TRANSMISSION, L[0], A[0], wT);
                    biref_spectrum_numeric_polarized(ref, &fl, BIREF_REFLECTION, L[1], A[1], wR);
                } else {
                    biref_numeric_hit(ref, &st, C, P, wT, wR);
                }
                worst = fmax(worst, fmax(max_diff(T[k], wT, 3), max_diff(R[k], wR, 3)));
                taken++;
            }
        }
        printf("packet hits, %s: %d of %d in lanes, largest difference from the scalar path %.3g\n",
               biref_simd_isa_name((biref_simd_isa)isa), taken, 4 * N, worst);
        /* about half the hits: thin slabs (the coherent regime) and evanescent legs go the scalar way */
        CHECK(taken > 4 * N / 5);
        /* the set-ups differ in rounding (and θ = asin(K / η_i) here), which thick slabs' phases amplify */
        CHECK(worst <= 1e-11);
    }
    plan->isa = BIREF_SIMD_SCALAR;
    biref_numeric_packet_hits(plan, C_sp, P_s, NULL, &H, N, T, R, scalar);
    int all = 1;
    for (int k = 0; k < N; k++) all &= scalar[k];
    CHECK(all); /* BIREF_SIMD=scalar: every hit the scalar way */
    biref_numeric_plan_destroy(plan);
    biref_numeric_plan_destroy(ref);
    biref_spectral_destroy(sp);
}

/* The plan's scalar path (BIREF_SIMD=scalar) never takes the lanes, and a complex path never. */
static void lanes_refuse_scalar_plans_and_evanescent_legs(void)
{
    biref_spectral *sp = NULL;
    CHECK(biref_spectral_create(NULL, &sp, NULL, 0) == BIREF_OK);
    biref_numeric_plan *plan = NULL;
    if (!sp || biref_numeric_plan_create(sp, 16, &plan, NULL, 0) != BIREF_OK) {
        CHECK(0);
        biref_spectral_destroy(sp);
        return;
    }
    biref_slab s = {.eta_o = 1.5, .eta_e = 1.6, .axis = {0, 0, 1}, .thickness_nm = 1e4, .eta_i = 1.0};
    biref_slab_state st;
    CHECK(biref_slab_prepare(&s, 0.3, &st) == BIREF_OK);
    biref_numeric_lanes_job job;
    job.outputs = BIREF_NL_T;
    job.pairs = 1;
    plan->isa = BIREF_SIMD_BASELINE;
    CHECK(biref_numeric_lanes_run(plan, &st, &job) == 1);
    plan->isa = BIREF_SIMD_SCALAR;
    CHECK(biref_numeric_lanes_run(plan, &st, &job) == 0);
    plan->isa = BIREF_SIMD_BASELINE;
    st.opl_up[1] += 1e-3 * I; /* an evanescent leg */
    CHECK(biref_numeric_lanes_run(plan, &st, &job) == 0);
    biref_numeric_plan_destroy(plan);
    biref_spectral_destroy(sp);
}

/* A render of the scene at w x h with the method on the instruction set isa (BIREF_SIMD). */
static float *render_numeric(const char *scene, biref_method method, int samples, const char *isa, int threads,
                             int w, int h)
{
    biref_scene sc;
    if (test_load_scene(scene, &sc, w, h)) return NULL;
    biref_render_options opt;
    biref_render_options_default(&opt);
    opt.method = method;
    opt.samples = samples;
    opt.threads = threads;
    opt.antialias = BIREF_ANTIALIAS_NONE;
    setenv("BIREF_SIMD", isa, 1);
    float *xyz = test_render_xyz(&sc, &opt, NULL);
    unsetenv("BIREF_SIMD");
    return xyz;
}

/* Renders with numeric-32 and the ground truth in lanes against the scalar double path
 * (BIREF_SIMD=scalar): ΔE00 mean <= 0.02, max <= 0.5, and the same image on one and two threads.
 * fig9a has the paper's s/p light, fig9c_analyzer45 world-fixed polarizers. */
static void renders_match_scalar_path(void)
{
    const char *scenes[] = {"examples/fig9a.json", "examples/fig9c_analyzer45.json"};
    const char *isa = biref_simd_isa_name(biref_simd_isa_choose());
    for (int i = 0; i < 2; i++)
        for (int gt = 0; gt < (test_quick() ? 1 : 2); gt++) { /* the sanitizer build: numeric-32 only */
            const int W = test_quick() ? 16 : gt ? 24 : 64, H = test_quick() ? 9 : gt ? 14 : 36;
            const biref_method m = gt ? BIREF_METHOD_GROUND_TRUTH : BIREF_METHOD_NUMERIC;
            float *ref = render_numeric(scenes[i], m, 32, "scalar", 2, W, H);
            float *a = render_numeric(scenes[i], m, 32, isa, 2, W, H);
            float *b = render_numeric(scenes[i], m, 32, isa, 1, W, H);
            CHECK(ref && a && b);
            if (ref && a && b) {
                const size_t n = (size_t)W * H;
                CHECK(memcmp(a, b, n * 3 * sizeof *a) == 0);
                double sum = 0.0, worst = 0.0;
                for (size_t k = 0; k < n; k++) {
                    const double x[3] = {ref[3 * k], ref[3 * k + 1], ref[3 * k + 2]};
                    const double y[3] = {a[3 * k], a[3 * k + 1], a[3 * k + 2]};
                    const double d = biref_delta_e00_xyz(x, y);
                    sum += d;
                    worst = fmax(worst, d);
                }
                printf("%s, %s, %s: dE00 to the scalar path mean %.2g, max %.2g\n", scenes[i],
                       gt ? "ground truth" : "numeric-32", isa, sum / (double)n, worst);
                CHECK(sum / (double)n <= 0.02 && worst <= 0.5);
            }
            free(ref);
            free(a);
            free(b);
        }
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"sincos_matches_libm", sincos_matches_libm},
        {"lanes_match_scalar_path", lanes_match_scalar_path},
        {"lanes_refuse_scalar_plans_and_evanescent_legs", lanes_refuse_scalar_plans_and_evanescent_legs},
        {"packet_hits_match_scalar_path", packet_hits_match_scalar_path},
        {"renders_match_scalar_path", renders_match_scalar_path},
    };
    return test_run_cases("test_numeric_lanes", cases, TEST_COUNT(cases), argc, argv);
}
