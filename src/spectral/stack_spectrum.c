/* Band integrals of a stack: the entry point, and the path expansion (docs/STACKS.md §2): J(k) = sum_g M_g e^{ik phi_g}
 * over the path groups of stack_paths.c, so |J|^2 integrates exactly, pair by pair, with the
 * S(cos), S(sin) table; thick layers (pairs beyond the table's far limit) come out incoherent as
 * in the slab. Where the expansion does not apply, adaptive numeric integration instead. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "biref/stack.h"
#include "error.h"
#include "spectral/spectral_internal.h"
#include "spectral/stack_internal.h"

/* N = M P (the analyzer applied), for the light's intensity. */
static void analyzed(const biref_light *l, const double complex M[2][2], double complex N[2][2])
{
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++) N[i][o] = l->has_analyzer ? M[i][0] * l->P[0][o] + M[i][1] * l->P[1][o] : M[i][o];
}

/* sum_{i,j,o} C_ij N_g[i][o] conj(N_h[j][o]). */
static double complex light_pair(const biref_light *l, const double complex Ng[2][2], const double complex Nh[2][2])
{
    double complex c = 0.0;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int o = 0; o < 2; o++) c += l->C[i][j] * Ng[i][o] * conj(Nh[j][o]);
    return c;
}

/* Largest |M[i][o]| of a group. */
static double group_amplitude(const biref_stack_group *g)
{
    double a = 0.0;
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++) a = fmax(a, cabs(g->M[i][o]));
    return a;
}

/* Which bands a sum covers, and for a dispersive band the estimate of its linearisation error. */
typedef struct {
    int lo, hi;  /* bands lo .. hi - 1 */
    int pairs;   /* the four s/p pairs too (else only the light's intensity) */
    biref_stack_legs *legs;       /* dispersive: the pairs' phases by their leg counts; else NULL */
    int node;                     /* dispersive: under this node's weight (< 0: the whole band) */
    double *err;                  /* dispersive: the error estimate accumulates here; NULL otherwise */
} band_range;

/* A pair's phase integrals: by its group paths' difference delta, or a dispersive stack's by
 * the sub-band tangents of its exact phase difference (stack_legs.c), whose residual beyond the
 * finest sub-bands, times the pair's amplitudes, adds to the error estimate. */
static void pair_integrals(const biref_spectral *sp, const biref_stack_group *g, const biref_stack_group *h,
                           double delta, const band_range *r, double C[3], double S[3])
{
    if (!r->legs) {
        biref_spectral_phase_integrals(sp, delta, C, S);
        return;
    }
    double residual;
    biref_stack_legs_lag(r->legs, g->id, h->id, delta, r->node, C, S, &residual);
    if (residual > 0.0) *r->err += group_amplitude(g) * group_amplitude(h) * residual;
}

/* The band integrals of |sum_g M_g e^{ik phi_g}|^2 for one face: X[in][out][band] and, with a light,
 * its detected intensity (N: the groups' matrices with the analyzer applied, n of them). */
static void pair_sums(const biref_spectral *sp, const biref_stack_group *g, int n, const biref_light *light,
                      const double complex (*N)[2][2], const band_range *r, double X[2][2][3], double mixed[3])
{
    memset(X, 0, sizeof(double[2][2][3]));
    memset(mixed, 0, sizeof(double[3]));
    for (int a = 0; a < n; a++) {
        for (int i = 0; i < 2 * r->pairs; i++)
            for (int o = 0; o < 2; o++) {
                double p = creal(g[a].M[i][o] * conj(g[a].M[i][o]));
                for (int b = r->lo; b < r->hi; b++) X[i][o][b] += p;
            }
        if (light) {
            double p = creal(light_pair(light, N[a], N[a]));
            for (int b = r->lo; b < r->hi; b++) mixed[b] += p;
        }
        for (int h = a + 1; h < n; h++) {
            const double delta = g[h].phi - g[a].phi; /* >= 0: sorted */
            if (delta > sp->d_far) break;           /* S is 0 there, and for every later h */
            double C[3], S[3];
            pair_integrals(sp, &g[a], &g[h], delta, r, C, S);
            /* 2 Re(c S(e^{-ik delta})) with S(e^{-ik delta}) = C - i S. */
            for (int i = 0; i < 2 * r->pairs; i++)
                for (int o = 0; o < 2; o++) {
                    double complex c = g[a].M[i][o] * conj(g[h].M[i][o]);
                    for (int b = r->lo; b < r->hi; b++) X[i][o][b] += 2 * (creal(c) * C[b] + cimag(c) * S[b]);
                }
            if (light) {
                double complex c = light_pair(light, N[a], N[h]);
                for (int b = r->lo; b < r->hi; b++) mixed[b] += 2 * (creal(c) * C[b] + cimag(c) * S[b]);
            }
        }
    }
}

biref_status biref_stack_face_sums(const biref_spectral *sp, const biref_stack_groups *g, const biref_light *light,
                                   const biref_stack_sums *what, biref_spectrum *out, double mixed[2][3], double *err)
{
    const int band = what->band;
    double complex(*N)[2][2] = NULL;
    const int most = g->n[0] > g->n[1] ? g->n[0] : g->n[1];
    if (light && most > 0) {
        N = malloc((size_t)most * sizeof *N);
        if (!N) return BIREF_ERR_NOMEM;
    }
    band_range r = {band < 0 ? 0 : band, band < 0 ? 3 : band + 1, what->pairs != 0, what->legs, what->node,
                    what->legs ? err : NULL};
    if (r.err) *r.err = 0.0;
    memset(out, 0, sizeof *out);
    memset(mixed, 0, sizeof(double[2][3]));
    for (int f = 0; f < 2; f++) {
        if (!(what->faces & (f ? BIREF_SIDE_REFLECTION : BIREF_SIDE_TRANSMISSION))) continue;
        if (light)
            for (int k = 0; k < g->n[f]; k++) analyzed(light, g->g[f][k].M, N[k]);
        pair_sums(sp, g->g[f], g->n[f], light, (const double complex(*)[2][2])N, &r, f ? out->R : out->T, mixed[f]);
    }
    free(N);
    return BIREF_OK;
}

void biref_stack_spectrum_opts_default(biref_stack_spectrum_opts *o)
{
    o->method = BIREF_METHOD_EXPANSION;
    o->samples = 64;
    o->tolerance = 1e-3;
    o->max_groups = 1024;
}

static biref_status check_opts(const biref_stack_spectrum_opts *o, char *msg, size_t msg_len)
{
    if (o->method == BIREF_METHOD_ANALYTIC || o->method == BIREF_METHOD_ANALYTIC_PAIRS)
        return biref_fail(msg, msg_len, "a stack has no %s method (the paper's eq. 26 is for one slab): use "
                                        "expansion, numeric or ground-truth", biref_method_name(o->method));
    if (o->method != BIREF_METHOD_EXPANSION && o->method != BIREF_METHOD_NUMERIC &&
        o->method != BIREF_METHOD_GROUND_TRUTH)
        return biref_fail(msg, msg_len, "unknown method %d", (int)o->method);
    if (o->method == BIREF_METHOD_NUMERIC && (o->samples < 1 || o->samples > (1 << 24)))
        return biref_fail(msg, msg_len, "%d samples: the numeric method needs 1 to %d", o->samples, 1 << 24);
    if (!(o->tolerance >= 1e-9 && o->tolerance <= 0.1))
        return biref_fail(msg, msg_len, "tolerance %g: expected 1e-9 to 0.1", o->tolerance);
    if (o->max_groups < 1 || o->max_groups > (1 << 16))
        return biref_fail(msg, msg_len, "max_groups %d: expected 1 to %d", o->max_groups, 1 << 16);
    return BIREF_OK;
}

/* A fixed number of samples (numeric, ground truth). */
static biref_status numeric_fixed(const biref_spectral *sp, const biref_stack_state *st, int samples,
                                  const biref_light *light, biref_spectrum *out, double mixed[2][3], char *msg,
                                  size_t msg_len)
{
    biref_numeric_plan *plan = NULL;
    biref_status s = biref_numeric_plan_create(sp, samples, &plan, msg, msg_len);
    if (s != BIREF_OK) return s;
    biref_stack_spectrum_numeric(plan, st, light, out, mixed[0], mixed[1]);
    biref_numeric_plan_destroy(plan);
    return BIREF_OK;
}

/* The path expansion, or the adaptive numeric integration where it does not apply. */
static biref_status expansion(const biref_spectral *sp, const biref_stack_state *st,
                              const biref_stack_spectrum_opts *o, const biref_light *light, biref_spectrum *out,
                              double mixed[2][3], biref_stack_spectrum_info *info, char *msg, size_t msg_len)
{
    if (st->dispersive) {
        biref_status s = biref_stack_expansion_dispersive(sp, st, o, light, out, mixed, info);
        if (s == BIREF_ERR_NOMEM) return biref_fail_status(s, msg, msg_len, "out of memory");
        if (s != BIREF_OK) return biref_fail_status(s, msg, msg_len, "a layer's material is unphysical in the band");
        return s;
    }
    biref_stack_groups g;
    biref_status s = biref_stack_path_groups(st, NULL, NULL, o->tolerance, o->max_groups, &g);
    if (s != BIREF_OK) return biref_fail_status(s, msg, msg_len, "out of memory");
    info->legs = g.legs;
    info->bound = g.bound;
    if (!g.reason) {
        info->groups[0] = g.n[0];
        info->groups[1] = g.n[1];
        const biref_stack_sums all = {BIREF_SIDE_BOTH, 1, -1, NULL, -1};
        s = biref_stack_face_sums(sp, &g, light, &all, out, mixed, NULL);
        biref_stack_groups_free(&g);
        return s == BIREF_OK ? s : biref_fail_status(s, msg, msg_len, "out of memory");
    }
    info->fallback = 1;
    info->reason = g.reason;
    int converged;
    s = biref_stack_numeric_adaptive(sp, st, light, o->tolerance, out, mixed, &info->samples, &converged);
    if (s != BIREF_OK) return biref_fail_status(s, msg, msg_len, "out of memory");
    info->bound = converged ? o->tolerance : NAN;
    return BIREF_OK;
}

biref_status biref_stack_spectrum(const biref_spectral *sp, const biref_stack_state *st,
                                  const biref_stack_spectrum_opts *opts, const biref_light *light, biref_spectrum *out,
                                  double mixed_T[3], double mixed_R[3], biref_stack_spectrum_info *info, char *msg,
                                  size_t msg_len)
{
    biref_stack_spectrum_opts o;
    if (opts)
        o = *opts;
    else
        biref_stack_spectrum_opts_default(&o);
    if (!sp || !st || !out) return biref_fail(msg, msg_len, "no spectral context, state or output");
    biref_status s = check_opts(&o, msg, msg_len);
    if (s != BIREF_OK) return s;
    biref_stack_spectrum_info local;
    if (!info) info = &local;
    memset(info, 0, sizeof *info);
    info->reason = "";
    for (int i = 0; st->dispersive && i < st->stack.n_layers; i++) {
        const biref_material *m = st->stack.layers[i].material;
        char why[BIREF_MSG_SIZE];
        if (m && biref_material_check_band(m, sp->cfg.lambda_min_nm, sp->cfg.lambda_max_nm, why, sizeof why) != BIREF_OK)
            return biref_fail(msg, msg_len, "layers[%d]: %s", i, why);
    }
    double mixed[2][3] = {{0, 0, 0}, {0, 0, 0}};
    if (o.method == BIREF_METHOD_EXPANSION) {
        s = expansion(sp, st, &o, light, out, mixed, info, msg, msg_len);
    } else {
        info->samples = o.method == BIREF_METHOD_GROUND_TRUTH ? BIREF_GROUND_TRUTH_SAMPLES : o.samples;
        s = numeric_fixed(sp, st, info->samples, light, out, mixed, msg, msg_len);
    }
    if (s != BIREF_OK) return s;
    if (mixed_T) memcpy(mixed_T, mixed[0], sizeof mixed[0]);
    if (mixed_R) memcpy(mixed_R, mixed[1], sizeof mixed[1]);
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 2; k++)
            for (int b = 0; b < 3; b++)
                if (!isfinite(out->T[i][k][b]) || !isfinite(out->R[i][k][b]))
                    return biref_fail_status(BIREF_ERR_ILLCOND, msg, msg_len, "numerical failure (non-finite result)");
    return BIREF_OK;
}

biref_status biref_stack_light_face(const biref_spectral *sp, const biref_stack_state *st, const biref_light *light,
                                    int which, double xyz[3])
{
    biref_stack_spectrum_opts o;
    biref_stack_spectrum_opts_default(&o);
    biref_spectrum out;
    double mixed[2][3];
    const int face = which == BIREF_SIDE_REFLECTION;
    biref_stack_groups g = {0};
    biref_status s = st->dispersive ? BIREF_OK : biref_stack_path_groups(st, NULL, NULL, o.tolerance, o.max_groups, &g);
    if (s != BIREF_OK) return s;
    if (st->dispersive || g.reason) {
        /* The per-band expansion and the fallbacks: the whole integration, one face kept. */
        s = biref_stack_spectrum(sp, st, &o, light, &out, mixed[0], mixed[1], NULL, NULL, 0);
    } else {
        /* The pairs of the one face the hit sees, and the light's intensity alone (the same sums
         * in the same order as biref_stack_spectrum's). */
        const biref_stack_sums one = {which, 0, -1, NULL, -1};
        s = biref_stack_face_sums(sp, &g, light, &one, &out, mixed, NULL);
        biref_stack_groups_free(&g);
    }
    if (s != BIREF_OK) return s;
    for (int b = 0; b < 3; b++) {
        xyz[b] = mixed[face][b];
        if (!isfinite(xyz[b])) return BIREF_ERR_ILLCOND;
    }
    return BIREF_OK;
}
