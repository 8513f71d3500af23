/* biref — the light model: what enters the slab and what the detector looks through.
 *
 * One description for every caller: the incident light as a coherency matrix (from a Stokes
 * vector, or the paper's incoherent s/p fractions) and an optional analyzer as a Jones matrix.
 * The paper's model (fig. 9: fractions w_in of s and p light, an analyzer that passes mask[s],
 * mask[p]) is the constructor biref_light_sp; it is a diagonal coherency and analyzer. Bases: s/p
 * of the incident wave for the coherency, of the outgoing wave for the analyzer
 * (docs/CONVENTIONS.md). A polarizer or analyzer may instead be fixed in the world (a linear
 * polarizer along a world axis, as in a scene): its matrix then differs from ray to ray, and a
 * shader (shading.h) resolves it for every hit. Plain data, no allocation; see
 * integrator.h for how a light is used. */
#ifndef BIREF_POLARIZATION_H
#define BIREF_POLARIZATION_H

#include <stddef.h>

#include "biref/common.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    biref_complex C[2][2]; /* incident coherency C[i][j] = <e_i conj(e_j)>, trace = intensity */
    biref_complex P[2][2]; /* analyzer [in][out]; ignored when has_analyzer is 0 */
    int has_analyzer;
    /* 1 when built by biref_light_sp and left so: C = diag(w_in), P = diag(sqrt(mask)), and the
     * detected colour of a slab is a mix of its four s/p pair intensities (biref_light_mix). */
    int sp_model;
    double w_in[2], mask[2];
    /* World-fixed linear polarizers (biref_light_world_polarizer / _analyzer): when set, the
     * incident light is polarized along polarizer_axis (C is then built per ray) and / or the
     * analyzer passes analyzer_axis (P per ray). Unit world vectors. */
    int world_polarizer, world_analyzer;
    double polarizer_axis[3], analyzer_axis[3];
} biref_light;

/* The paper's light: incoherent fractions w_in[s], w_in[p] (>= 0) through an analyzer passing
 * the power fractions mask[s], mask[p] (in [0, 1]; its Jones matrix is diag(sqrt(mask))); mask
 * (1, 1) means no analyzer. BIREF_ERR_INVALID otherwise. */
BIREF_API biref_status biref_light_sp(const double w_in[2], const double mask[2], biref_light *out);

/* Incident light from Stokes parameters (biref_stokes_to_coherency), no analyzer. */
BIREF_API biref_status biref_light_stokes(const double stokes[4], biref_light *out);

/* Incident light from a coherency matrix (Hermitian, non-negative; not checked), no analyzer. */
BIREF_API void biref_light_coherency(const biref_complex C[2][2], biref_light *out);

/* Puts an analyzer (Jones matrix [in][out]) behind the slab, or removes it (P = NULL). The
 * light leaves the paper's model unless P is diag(sqrt(mask)) of its mask. */
BIREF_API void biref_light_set_analyzer(biref_light *l, const biref_complex P[2][2]);

/* A world-fixed linear polarizer in front of the slab along the world axis `axis` (normalised here):
 * in the basis (s, p) of a wave travelling along k it passes the amplitude (axis.s, axis.p), so
 * light along the axis itself is blocked (Malus at oblique incidence). Replaces the incident
 * coherency; the light leaves the paper's model. BIREF_ERR_INVALID for a zero or non-finite axis. */
BIREF_API biref_status biref_light_world_polarizer(biref_light *l, const double axis[3]);

/* A world-fixed linear analyzer behind the slab along `axis` (normalised here): it passes the
 * amplitude E.a_t polarized along a_t (a_t: the axis' part transverse to the outgoing wave,
 * |a_t| <= 1 acting as a transmission factor). Replaces the analyzer. BIREF_ERR_INVALID as above. */
BIREF_API biref_status biref_light_world_analyzer(biref_light *l, const double axis[3]);

/* 1 when the light has a world-fixed polarizer or analyzer (a shader resolves it per hit). */
BIREF_API int biref_light_is_world_fixed(const biref_light *l);

/* A polarizer in its text form, as the command line and the Python bindings take it:
 * "linear:DEG" (linear, DEG degrees from s towards p) or "circular:+1" / "circular:-1" (also
 * "circular:1"; the handedness is the sign of S3, docs/CONVENTIONS.md). Gives the fully polarized
 * state it lets through as a Stokes vector of unit intensity and the analyzer it makes (Jones
 * matrix [in][out], biref_analyzer_linear / _circular). BIREF_ERR_INVALID with one line in msg
 * for any other text. */
typedef struct {
    double stokes[4];
    biref_complex analyzer[2][2];
} biref_polarizer;

BIREF_API biref_status biref_polarizer_parse(const char *text, biref_polarizer *out, char *msg, size_t msg_len);

/* The detected XYZ of a light mixing the four s/p pair intensities X[in][out][band] of a
 * spectrum (transmission or reflection): sum w_in[i] mask[o] X[i][o]. Only for the paper's
 * model (BIREF_ERR_INVALID otherwise: a general light needs the amplitudes, integrator.h). */
BIREF_API biref_status biref_light_mix(const biref_light *l, const double X[2][2][3], double xyz[3]);

/* Coherency matrix C[i][j] = <e_i conj(e_j)> in the s/p basis of a wave from Stokes parameters
 * (S0 intensity, S1 = |e_s|^2 - |e_p|^2, S2 = 2 Re(e_s conj e_p), S3 = -2 Im(e_s conj e_p)):
 * S3 > 0 for e = (1, i)/sqrt2, whose field turns from s towards p (docs/CONVENTIONS.md).
 * BIREF_ERR_INVALID unless S0 >= 0 and S1^2 + S2^2 + S3^2 <= S0^2 (physical light). */
BIREF_API biref_status biref_stokes_to_coherency(const double stokes[4], biref_complex C[2][2]);

/* Analyzers as Jones matrices [in][out] in the s/p basis of the outgoing wave: projection onto
 * the unit Jones vector u, P[k][o] = conj(u_k) u_o. Linear at angle psi from s towards p;
 * circular with handedness +1 (u = (1, i)/sqrt2, S3 = +1) or -1. */
BIREF_API void biref_analyzer_linear(double psi_rad, biref_complex P[2][2]);
BIREF_API void biref_analyzer_circular(int handedness, biref_complex P[2][2]);

/* Polarisation mixing of the paper's light model: incident light with fractions w_in[s],
 * w_in[p] (incoherent), detected through an analyzer passing out_mask[s], out_mask[p].
 * xyz = sum w_in[i] out_mask[j] X[i][j]. */
BIREF_API void biref_spectrum_mix(const double X[2][2][3], const double w_in[2], const double out_mask[2], double xyz[3]);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_POLARIZATION_H */
