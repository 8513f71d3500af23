/*
 * biref — the shader, and shading surface hits in world space for renderers that trace their own
 * rays.
 *
 * A shader is the core object of every picture: a spectral context, an integrator of one method
 * and one light. biref's own renderer, the GPU data export and the Python bindings hold one.
 *
 * A renderer knows, at a hit, the surface normal and tangent, the slab's constants and optic
 * axis (in the surface's local frame, as in scene files) and the view direction. The library
 * builds the paper's two frames of that ray (transmission: light from behind; reflection: light
 * from the viewer's side, docs/SCENES.md "Frames"), evaluates the slab in each and returns the
 * band-normalised XYZ factors by which the radiance behind and the radiance along the mirror
 * direction are multiplied. biref's own ray caster uses the same code.
 */
#ifndef BIREF_SHADING_H
#define BIREF_SHADING_H

#include "biref/common.h"
#include "biref/integrator.h"
#include "biref/optics.h"
#include "biref/polarization.h"
#include "biref/spectral.h"
#include "biref/stack.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A slab at a surface hit, in world coordinates. The normal may face either side of the surface,
 * but the local frame is right-handed (z = x cross y), so flipping the normal also flips local z:
 * the same local optic axis then describes the plate turned over about its tangent. Under s/p
 * light (relative to each ray's plane of incidence) that changes nothing; under world-fixed
 * polarizers it is a different plate. Give the normal the orientation the axis was written for. */
typedef struct {
    double normal[3];  /* surface normal (local +y), normalised by biref; see above on its orientation */
    double tangent[3]; /* local +x; orthogonalised against the normal by biref */
    double axis[3];    /* optic axis in the local frame: x = tangent, y = normal, z = x cross y */
    double eta_o, eta_e;
    double thickness_nm;
    double eta_i;      /* surrounding medium, both sides (1 = vacuum) */
} biref_surface;

/* The paper's frames of one view ray at a hit, in world coordinates. */
typedef struct {
    double theta;             /* angle of incidence (rad), clamped just below pi/2 for grazing rays */
    double x_T[3], y_T[3];    /* transmission frame: y_T = normal pointing away from the viewer */
    double z[3];              /* shared z: the view ray's tangential direction (the tangent at normal incidence) */
    double x_R[3], y_R[3];    /* reflection frame: y_R = -y_T, x_R = -x_T */
    double k_view[3];         /* travel direction of the light reaching the viewer (-view_dir) */
    double mirror[3];         /* from the hit towards the light that reflects into the viewer */
    biref_slab slab;          /* the slab with its optic axis in the transmission frame */
} biref_hit_frames;

/* Frames of the ray travelling along view_dir (viewer -> hit, need not be unit) that hits s.
 * BIREF_ERR_INVALID for non-finite or zero vectors, a tangent parallel to the normal, or a view
 * direction in the surface plane (an edge-on thin slab is invisible). */
BIREF_API biref_status biref_hit_frames_make(const biref_surface *s, const double view_dir[3], biref_hit_frames *out);

/* The spectral method and the light shared by every hit; immutable, may be used by several
 * threads. sp is borrowed (it must outlive the shader; one context serves a whole process), opt
 * NULL means the analytic method (biref_integrator_options_default), light NULL unpolarized light
 * without analyzer. The light's s/p parts are relative to each ray's plane of incidence; its
 * world-fixed polarizers (biref_light_world_polarizer / _analyzer) are resolved at every hit (in the hit's frames)
 * (docs/SCENES.md "Polarisation"). BIREF_ERR_INVALID with one line in msg for bad options, a light
 * that is not finite or a light the method cannot integrate. */
typedef struct biref_shader biref_shader;

BIREF_API biref_status biref_shader_create(const biref_spectral *sp, const biref_integrator_options *opt,
                                           const biref_light *light, biref_shader **out, char *msg,
                                           size_t msg_len);
BIREF_API void biref_shader_destroy(biref_shader *sh);
/* The shader's method and light, as given at creation. */
BIREF_API biref_method biref_shader_method(const biref_shader *sh);
BIREF_API const biref_light *biref_shader_light(const biref_shader *sh);

/* Shades one hit: T_xyz multiplies the radiance arriving from behind the slab along view_dir,
 * R_xyz the radiance arriving from the mirror direction (frames->mirror; frames may be NULL).
 * Band-normalised XYZ: a white light behind an empty scene of radiance 1 gives T + R = (1, 1, 1)
 * for unpolarized light without analyzer (lossless slab). BIREF_ERR_INVALID for a bad surface or
 * direction (see biref_hit_frames_make); BIREF_ERR_ILLCOND when the evaluation breaks down
 * (outputs then undefined: biref's renderer shows a perfect mirror). No allocation. */
BIREF_API biref_status biref_shade_hit(const biref_shader *sh, const biref_surface *s, const double view_dir[3],
                                       double T_xyz[3], double R_xyz[3], biref_hit_frames *frames);

/* n hits at once (hit k: surfaces[k] seen along view_dirs[k]), the way biref's own renderer shades
 * its tiles: the analytic method evaluates them in SIMD packets, hits it cannot take one by one.
 * T_xyz[k], R_xyz[k] as biref_shade_hit gives them (up to roundings: the packet kernel sums in
 * another order, and on AVX2 and AVX-512 takes the paper's light in float lanes, within ~1e-7);
 * status[k] (may be NULL) each hit's code as biref_shade_hit's. Returns BIREF_OK or the first
 * failure's code. No allocation. */
BIREF_API biref_status biref_shade_hits(const biref_shader *sh, size_t n, const biref_surface *surfaces,
                                        const double (*view_dirs)[3], double (*T_xyz)[3], double (*R_xyz)[3],
                                        biref_status *status);

/* A stack of layers at a surface hit (docs/STACKS.md §5), in world coordinates: normal and tangent
 * as in biref_surface; the stack's layers listed from the face the normal points out of (local +y)
 * downwards, each optic axis in the local frame (x = tangent, y = normal, z = x cross y), eta_i the
 * surround on both sides. The stack is borrowed for the call. */
typedef struct {
    double normal[3];
    double tangent[3];
    const biref_stack *stack;
} biref_stack_surface;

/* Shades one hit on a stack as biref_shade_hit shades a slab (same T_xyz, R_xyz and frames; a
 * one-layer stack gives the slab's numbers to the method's accuracy). The stack's band integrals
 * (biref_stack_spectrum) in each side's frame: the analytic and expansion methods use the stack's
 * path expansion (it has no analytic method; adaptive numeric integration where the expansion does
 * not apply), the numeric methods their samples of the exact Jones matrices. Any light the shader
 * takes, world-fixed polarizers included. frames->slab is layer 0's constants, not the stack.
 * BIREF_ERR_INVALID for a bad surface, stack or direction; BIREF_ERR_ILLCOND when the evaluation
 * breaks down; BIREF_ERR_NOMEM (the expansion allocates). Costs about a millisecond per hit (the
 * stack's expansion, docs/STACKS.md §2), not the slab's microseconds. */
BIREF_API biref_status biref_shade_stack_hit(const biref_shader *sh, const biref_stack_surface *s,
                                             const double view_dir[3], double T_xyz[3], double R_xyz[3],
                                             biref_hit_frames *frames);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_SHADING_H */
