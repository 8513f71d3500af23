/* biref — the spectral integrator: one front door to every integration method.
 *
 * An integrator is created once from a spectral context, a method and its options; it picks its
 * worker then (as a colour-management transform does), so the per-sample call has no method
 * switch and no allocation. One call integrates a prepared slab state (optics.h) for
 * transmission and/or reflection under one light (polarization.h) and returns band-normalised
 * XYZ with a status.
 *
 * Immutable after creation and shareable between threads. The spectral context is borrowed: it
 * must outlive the integrator. */
#ifndef BIREF_INTEGRATOR_H
#define BIREF_INTEGRATOR_H

#include <stddef.h>

#include "biref/common.h"
#include "biref/optics.h"
#include "biref/polarization.h"
#include "biref/spectral.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Which light to integrate: flags, combinable. */
typedef enum {
    BIREF_SIDE_TRANSMISSION = 1,
    BIREF_SIDE_REFLECTION = 2,
    BIREF_SIDE_BOTH = 3
} biref_sides;

/* The numeric plan holds two arrays of this many entries. */
#define BIREF_NUMERIC_MAX_SAMPLES (1 << 24)

typedef struct {
    biref_method method;            /* default BIREF_METHOD_ANALYTIC */
    int samples;                    /* BIREF_METHOD_NUMERIC: midpoint samples, 1..BIREF_NUMERIC_MAX_SAMPLES
                                       (default 64) */
    biref_expansion_opts expansion; /* BIREF_METHOD_EXPANSION (default biref_expansion_opts_default) */
} biref_integrator_options;

BIREF_API void biref_integrator_options_default(biref_integrator_options *o);

typedef struct biref_integrator biref_integrator;

/* BIREF_ERR_INVALID for an unknown method, samples out of range or expansion options out of
 * their domain (order > BIREF_EXPANSION_MAX_ORDER; adaptive with tolerance outside (0, 1)),
 * BIREF_ERR_NOMEM; one line saying which in msg (common.h). */
BIREF_API biref_status biref_integrator_create(const biref_spectral *sp, const biref_integrator_options *o,
                                               biref_integrator **out, char *msg, size_t msg_len);
BIREF_API void biref_integrator_destroy(biref_integrator *it);
BIREF_API biref_method biref_integrator_method(const biref_integrator *it);
/* Samples per integral of the numeric methods (ground truth: BIREF_GROUND_TRUTH_SAMPLES), 0 else. */
BIREF_API int biref_integrator_samples(const biref_integrator *it);

typedef struct {
    double T[3], R[3];   /* band-normalised XYZ; only the requested sides are written */
    int order_used[2];   /* the expansion's pair order for T and R, -1 where not used */
} biref_integration;

/* Integrates a prepared slab for the requested sides under `light` (every method takes every
 * light: the analytic method integrates a light outside the paper's s/p model with the general
 * coherency/analyzer terms of the GPU shader, docs/GPU.md). BIREF_ERR_INVALID for no side or a
 * light with world-fixed polarizers (a shader resolves those per hit, shading.h); BIREF_ERR_ILLCOND
 * where the method breaks down or the result is not finite (the caller decides what to show). No allocation; the expansion needs about 250 KB of stack. A per-sample
 * entry point: no message buffer (common.h), each code has the one meaning given here. */
BIREF_API biref_status biref_integrate(const biref_integrator *it, const biref_slab_state *st, biref_sides sides,
                             const biref_light *light, biref_integration *out);

/* All four s/p input/output pair intensities of transmission and reflection (the paper's
 * quantities, eq. 17), from which any light of the paper's model mixes (biref_light_mix).
 * Returns the method's status; the values are not checked for finiteness. */
BIREF_API biref_status biref_integrate_spectrum(const biref_integrator *it, const biref_slab_state *st, biref_spectrum *out);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_INTEGRATOR_H */
