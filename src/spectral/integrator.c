/* The spectral integrator (integrator.h): options checked and the worker picked at creation;
 * the workers wrap the method entry points of analytic.c, numeric.c and expansion.c. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "biref/integrator.h"
#include "error.h"
#include "optics/slab_internal.h"
#include "spectral/analytic_terms.h"
#include "spectral/expansion_packet.h"
#include "spectral/integrator_internal.h"
#include "spectral/numeric_lanes.h"
#include "spectral/phase_prefilter.h"
#include "spectral/spectral_internal.h"
#include "spectral/stack_internal.h"

/* One side (BIREF_TRANSMISSION or BIREF_REFLECTION) of one state under one light. */
typedef biref_status (*side_worker)(const biref_integrator *it, const biref_slab_state *st, const biref_opl_footprint *fp,
                                    int which, const biref_light *l, double xyz[3], int *order_used);

/* A stack of layers at a hit: one face's detected XYZ of a prepared stack under one light. */
typedef biref_status (*stack_worker)(const biref_integrator *it, const biref_stack_state *st, int which,
                                     const biref_light *l, double xyz[3]);

/* Where the media plug in. The medium at a hit is one slab of constant indices (a prepared
 * biref_slab_state) or a stack of layers (biref_stack_state, the stack worker), each with its
 * worker picked per method at creation (side, hits, stack). A dispersive material (wavelength-dependent indices: numeric_dispersive.c prepares the slab per
 * sample wavelength, biref_integrate_material) and a stack of layers are further kinds of medium:
 * each gets its workers per method here, picked at creation by (method, medium kind) next to the
 * ones below, so that the per-sample call never switches on the medium and the renderer, shader
 * and photoelastic callers keep one door (biref_integrate_hit / biref_integrate_packet_hits taking
 * "the medium at a hit"); a method without a worker for a kind says so once, at creation (today
 * biref_integrate_material refuses the closed-form methods on every call). */
struct biref_integrator {
    const biref_spectral *sp;
    biref_method method;
    int pairs; /* BIREF_METHOD_ANALYTIC_PAIRS: the analytic terms with transmission's pairs */
    biref_expansion_opts xopts;
    biref_numeric_plan *plan; /* numeric methods */
    side_worker side;
    biref_simd_isa isa;          /* analytic: the packet kernel's instruction set, picked at creation */
    biref_packet_hits_kernel hits; /* NULL: no packets */
    biref_expansion_hits_kernel xhits; /* the expansion's packets (NULL: none) */
    stack_worker stack;
};

void biref_integrator_options_default(biref_integrator_options *o)
{
    o->method = BIREF_METHOD_ANALYTIC;
    o->samples = 64;
    biref_expansion_opts_default(&o->expansion);
}

/* The analytic method per side: eq. 25, S = E + 2H, for the one side asked (half the work of
 * biref_spectrum_analytic), with the paper's light folded into the sums (analytic_mixed.c); any
 * other light through the general coherency/analyzer terms (analytic_general.c). */
static biref_status side_analytic(const biref_integrator *it, const biref_slab_state *st,
                                  const biref_opl_footprint *fp, int which,
                                  const biref_light *l, double xyz[3], int *order_used)
{
    if (!l->sp_model) {
        biref_analytic_general(it->sp, st, fp, which, it->pairs, (const double complex(*)[2])l->C,
                               l->has_analyzer ? (const double complex(*)[2])l->P : NULL, xyz);
        return BIREF_OK;
    }
    if (fp) {
        /* Prefiltered phase integrals: eq. 25 per pair with the averaged look-ups, then mixed. */
        double E[2][2][3], H[2][2][3], X[2][2][3];
        biref_analytic_terms_footprint(it->sp, st, fp, which, it->pairs, E, H);
        for (int i = 0; i < 2; i++)
            for (int o = 0; o < 2; o++)
                for (int j = 0; j < 3; j++) X[i][o][j] = E[i][o][j] + 2.0 * H[i][o][j];
        biref_spectrum_mix(X, l->w_in, l->mask, xyz);
        return BIREF_OK;
    }
    biref_analytic_mixed(it->sp, st, which, it->pairs, l->w_in, l->mask, xyz);
    return BIREF_OK;
}

static biref_status side_numeric(const biref_integrator *it, const biref_slab_state *st,
                                  const biref_opl_footprint *fp, int which,
                                 const biref_light *l, double xyz[3], int *order_used)
{
    biref_spectrum_numeric_polarized(it->plan, st, which, (const double complex(*)[2])l->C,
                                     l->has_analyzer ? (const double complex(*)[2])l->P : NULL, xyz);
    return BIREF_OK;
}

static biref_status side_expansion(const biref_integrator *it, const biref_slab_state *st,
                                  const biref_opl_footprint *fp, int which,
                                   const biref_light *l, double xyz[3], int *order_used)
{
    biref_status s = biref_expansion_polarized_footprint(it->sp, st, fp, which, (const double complex(*)[2])l->C,
                                                         l->has_analyzer ? (const double complex(*)[2])l->P : NULL,
                                                         &it->xopts, xyz, order_used);
    return s;
}

/* A stack by its closed form (docs/STACKS.md §2: the path expansion, adaptive numeric integration
 * where it does not apply) for the analytic and expansion methods: a stack has no eq. 26. */
static biref_status stack_closed_form(const biref_integrator *it, const biref_stack_state *st, int which,
                                      const biref_light *l, double xyz[3])
{
    return biref_stack_light_face(it->sp, st, l, which, xyz);
}

/* A stack by the numeric methods: the integrator's plan, exact Jones matrices per sample. */
static biref_status stack_numeric(const biref_integrator *it, const biref_stack_state *st, int which,
                                  const biref_light *l, double xyz[3])
{
    biref_spectrum out;
    double m[2][3];
    biref_stack_spectrum_numeric(it->plan, st, l, &out, m[0], m[1]);
    memcpy(xyz, m[which == BIREF_SIDE_REFLECTION], sizeof m[0]);
    return isfinite(xyz[0]) && isfinite(xyz[1]) && isfinite(xyz[2]) ? BIREF_OK : BIREF_ERR_ILLCOND;
}

static biref_status check_options(const biref_integrator_options *o, char *msg, size_t msg_len)
{
    switch (o->method) {
    case BIREF_METHOD_ANALYTIC:
    case BIREF_METHOD_ANALYTIC_PAIRS:
    case BIREF_METHOD_GROUND_TRUTH: return BIREF_OK;
    case BIREF_METHOD_NUMERIC:
        if (o->samples >= 1 && o->samples <= BIREF_NUMERIC_MAX_SAMPLES) return BIREF_OK;
        return biref_fail(msg, msg_len, "%d samples: the numeric method needs 1 to %d", o->samples,
                          BIREF_NUMERIC_MAX_SAMPLES);
    case BIREF_METHOD_EXPANSION: {
        const biref_expansion_opts *x = &o->expansion;
        if (x->order > BIREF_EXPANSION_MAX_ORDER || x->order < -1)
            return biref_fail(msg, msg_len, "expansion order %d: expected 0 to %d, or -1 for adaptive", x->order,
                              BIREF_EXPANSION_MAX_ORDER);
        if (x->order < 0 && !(x->tolerance > 0.0 && x->tolerance < 1.0))
            return biref_fail(msg, msg_len, "expansion tolerance %g: expected a number in (0, 1)", x->tolerance);
        return BIREF_OK;
    }
    }
    return biref_fail(msg, msg_len, "unknown integration method (%d)", (int)o->method);
}

biref_status biref_integrator_create(const biref_spectral *sp, const biref_integrator_options *o,
                                     biref_integrator **out, char *msg, size_t msg_len)
{
    if (!out) return biref_fail(msg, msg_len, "no output");
    *out = NULL;
    if (!sp || !o) return biref_fail(msg, msg_len, "no spectral context or options");
    biref_status s = check_options(o, msg, msg_len);
    if (s != BIREF_OK) return s;
    biref_simd_isa isa;
    s = biref_simd_isa_pick(&isa, msg, msg_len); /* an unknown BIREF_SIMD is refused, whatever the method */
    if (s != BIREF_OK) return s;
    biref_integrator *it = calloc(1, sizeof *it);
    if (!it) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    it->sp = sp;
    it->method = o->method;
    it->xopts = o->expansion;
    switch (o->method) {
    case BIREF_METHOD_ANALYTIC:
    case BIREF_METHOD_ANALYTIC_PAIRS:
        /* The two analytic methods differ only in transmission's sibling and entry pairs: one
         * flag for the scalar workers, a kernel compiled with or without them for the packets. */
        it->pairs = o->method == BIREF_METHOD_ANALYTIC_PAIRS;
        it->side = side_analytic;
        it->isa = isa;
        it->hits = it->pairs ? biref_simd_hits_kernel_pairs(isa) : biref_simd_hits_kernel(isa);
        it->stack = stack_closed_form;
        break;
    case BIREF_METHOD_EXPANSION:
        it->side = side_expansion;
        it->isa = isa;
        it->xhits = biref_simd_expansion_kernel(isa);
        it->stack = stack_closed_form;
        break;
    default:
        it->side = side_numeric;
        it->stack = stack_numeric;
        s = biref_numeric_plan_create(
            sp, o->method == BIREF_METHOD_GROUND_TRUTH ? BIREF_GROUND_TRUTH_SAMPLES : o->samples, &it->plan, msg, msg_len);
        if (s != BIREF_OK) {
            free(it);
            return s;
        }
    }
    *out = it;
    return BIREF_OK;
}

void biref_integrator_destroy(biref_integrator *it)
{
    if (!it) return;
    biref_numeric_plan_destroy(it->plan);
    free(it);
}

biref_method biref_integrator_method(const biref_integrator *it) { return it->method; }

int biref_integrator_samples(const biref_integrator *it) { return it->plan ? biref_numeric_plan_samples(it->plan) : 0; }

static int finite3(const double v[3]) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

biref_status biref_integrate(const biref_integrator *it, const biref_slab_state *st, biref_sides sides,
                             const biref_light *light, biref_integration *out)
{
    return biref_integrate_footprint(it, st, NULL, sides, light, out);
}

biref_status biref_integrate_footprint(const biref_integrator *it, const biref_slab_state *st,
                                       const biref_opl_footprint *fp, biref_sides sides, const biref_light *light,
                                       biref_integration *out)
{
    out->order_used[0] = out->order_used[1] = -1;
    if (!(sides & BIREF_SIDE_BOTH) || (sides & ~BIREF_SIDE_BOTH)) return BIREF_ERR_INVALID;
    /* World-fixed polarizers have no matrices until a shader resolves them for a ray. */
    if (biref_light_is_world_fixed(light)) return BIREF_ERR_INVALID;
    if (it->plan && light->sp_model && sides == BIREF_SIDE_BOTH) {
        /* Both sides of the paper's light: one pass over the wavelengths gives all four pairs of
         * both, cheaper than two polarized passes (one Jones evaluation per wavelength). */
        biref_spectrum x;
        biref_spectrum_numeric(it->plan, st, &x);
        biref_spectrum_mix(x.T, light->w_in, light->mask, out->T);
        biref_spectrum_mix(x.R, light->w_in, light->mask, out->R);
        return finite3(out->T) && finite3(out->R) ? BIREF_OK : BIREF_ERR_ILLCOND;
    }
    for (int w = 0; w < 2; w++) {
        if (!(sides & (w ? BIREF_SIDE_REFLECTION : BIREF_SIDE_TRANSMISSION))) continue;
        double *xyz = w ? out->R : out->T;
        biref_status s = it->side(it, st, fp, w ? BIREF_REFLECTION : BIREF_TRANSMISSION, light, xyz, &out->order_used[w]);
        if (s != BIREF_OK) return s;
        if (!finite3(xyz)) return BIREF_ERR_ILLCOND;
    }
    return BIREF_OK;
}

biref_status biref_integrate_spectrum(const biref_integrator *it, const biref_slab_state *st, biref_spectrum *out)
{
    biref_status s = BIREF_OK;
    switch (it->method) {
    case BIREF_METHOD_ANALYTIC: biref_spectrum_analytic(it->sp, st, out); break;
    case BIREF_METHOD_ANALYTIC_PAIRS: biref_spectrum_analytic_pairs(it->sp, st, out); break;
    case BIREF_METHOD_EXPANSION: s = biref_spectrum_expansion(it->sp, st, &it->xopts, out); break;
    default: biref_spectrum_numeric(it->plan, st, out); break;
    }
    if (s != BIREF_OK) return s;
    /* A result that is not finite is an error, never an output. */
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++)
            if (!finite3(out->T[i][o]) || !finite3(out->R[i][o])) return BIREF_ERR_ILLCOND;
    return BIREF_OK;
}

biref_simd_isa biref_integrator_simd(const biref_integrator *it) { return it->isa; }

/* One state at a time (the renderer's packets go through biref_integrate_packet_hits). */
biref_status biref_integrate_batch(const biref_integrator *it, const biref_slab_state *states, size_t n,
                                   biref_sides sides, const biref_light *lights, size_t light_stride,
                                   biref_integration *out, biref_status *status)
{
    if (light_stride > 1) return BIREF_ERR_INVALID;
    biref_status first = BIREF_OK;
    for (size_t i = 0; i < n; i++) {
        biref_status s = biref_integrate(it, &states[i], sides, &lights[i * light_stride], &out[i]);
        if (status) status[i] = s;
        if (s != BIREF_OK && first == BIREF_OK) first = s;
    }
    return first;
}

/* One hit the scalar way: transmission of st, reflection of its flip (with the flipped footprint:
 * the flip swaps the down and up legs). */
static biref_status scalar_hit(const biref_integrator *it, const biref_slab_state *st, const biref_opl_footprint *fp,
                               const biref_light *light, double T[3], double R[3])
{
    if (it->plan && !biref_light_is_world_fixed(light)) {
        /* Numeric methods: both sides in one pass, sharing the phases and the round trip. */
        biref_numeric_hit(it->plan, st, (const double complex(*)[2])light->C,
                          light->has_analyzer ? (const double complex(*)[2])light->P : NULL, T, R);
        return finite3(T) && finite3(R) ? BIREF_OK : BIREF_ERR_ILLCOND;
    }
    biref_integration res;
    biref_status s = biref_integrate_footprint(it, st, fp, BIREF_SIDE_TRANSMISSION, light, &res);
    if (s != BIREF_OK) return s;
    memcpy(T, res.T, sizeof res.T);
    biref_slab_state fl;
    biref_slab_state_flip(st, &fl);
    biref_opl_footprint fpR;
    if (fp) biref_opl_footprint_flip(fp, &fpR);
    s = biref_integrate_footprint(it, &fl, fp ? &fpR : NULL, BIREF_SIDE_REFLECTION, light, &res);
    memcpy(R, res.R, sizeof res.R);
    return s;
}

/* Can the packet kernel take these footprints? All of one prefilter (the kernel reads one table). */
static int one_prefilter(const biref_opl_footprint *fp, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (!fp[k].pf || fp[k].pf != fp[0].pf) return 0;
    return 1;
}

void biref_integrate_packet_hits(const biref_integrator *it, const biref_packet_hits *hits,
                                 const biref_opl_footprint *fp, size_t n, const biref_light *light, double (*T)[3],
                                 double (*R)[3], unsigned char *scalar)
{
    if (it->plan && !biref_light_is_world_fixed(light)) { /* numeric methods (no footprints) */
        biref_numeric_packet_hits(it->plan, (const double complex(*)[2])light->C,
                                  light->has_analyzer ? (const double complex(*)[2])light->P : NULL, NULL, hits, n, T,
                                  R, scalar);
        return;
    }
    if (it->hits && light->sp_model && (!fp || one_prefilter(fp, n)))
        it->hits(it->sp, light->w_in, light->mask, hits, n, T, R, scalar, fp, NULL);
    else if (it->xhits && light->sp_model && (!fp || one_prefilter(fp, n))) {
        /* Power weights, as P = diag(sqrt(mask)) gives the scalar expansion. */
        it->xhits(it->sp, &it->xopts, light->w_in, light->mask, hits, n, T, R, scalar, fp, NULL);
    } else
        memset(scalar, 1, n);
}

/* Lights without imaginary parts (the expansion's and the numeric lanes take real lights only). */
static int real_lights(const biref_packet_hit_light *lights, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        const biref_packet_light *s[2] = {&lights[k].T, &lights[k].R};
        for (int d = 0; d < 2; d++)
            if (s[d]->Ci != 0.0 || s[d]->Pi[0] != 0.0 || s[d]->Pi[1] != 0.0 || s[d]->Pi[2] != 0.0 || s[d]->Pi[3] != 0.0)
                return 0;
    }
    return 1;
}

void biref_integrate_packet_hits_lit(const biref_integrator *it, const biref_packet_hits *hits,
                                     const biref_opl_footprint *fp, size_t n, const biref_packet_hit_light *lights,
                                     double (*T)[3], double (*R)[3], unsigned char *scalar)
{
    if (it->plan) { /* numeric methods (no footprints; real lights: their lanes take no others) */
        if (real_lights(lights, n))
            biref_numeric_packet_hits(it->plan, NULL, NULL, lights, hits, n, T, R, scalar);
        else
            memset(scalar, 1, n);
        return;
    }
    if (it->hits && (!fp || one_prefilter(fp, n)))
        it->hits(it->sp, NULL, NULL, hits, n, T, R, scalar, fp, lights);
    else if (it->xhits && (!fp || one_prefilter(fp, n)) && real_lights(lights, n))
        it->xhits(it->sp, &it->xopts, NULL, NULL, hits, n, T, R, scalar, fp, lights);
    else
        memset(scalar, 1, n);
}

biref_status biref_integrate_hit(const biref_integrator *it, const biref_slab_hit *hit, const biref_opl_footprint *fp,
                                 const biref_light *light, double T[3], double R[3])
{
    biref_slab_state st;
    biref_status s = biref_slab_prepare_trusted(&hit->slab, hit->theta, &st);
    return s != BIREF_OK ? s : scalar_hit(it, &st, fp, light, T, R);
}

biref_status biref_integrate_stack_hit(const biref_integrator *it, const biref_stack_state *stT,
                                       const biref_stack_state *stR, const biref_light *lT, const biref_light *lR,
                                       double T[3], double R[3])
{
    biref_status s = it->stack(it, stT, BIREF_SIDE_TRANSMISSION, lT, T);
    return s ? s : it->stack(it, stR, BIREF_SIDE_REFLECTION, lR, R);
}

const biref_numeric_plan *biref_integrator_plan(const biref_integrator *it) { return it->plan; }

const biref_spectral *biref_integrator_spectral(const biref_integrator *it) { return it->sp; }

const biref_expansion_opts *biref_integrator_expansion_opts(const biref_integrator *it) { return &it->xopts; }
