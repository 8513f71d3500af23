/* The shader's inside (shading.h): what biref's renderer, the photoelastic pictures and the
 * public shading entry points share. The shader holds the integrator and the one light; world-fixed
 * polarizers are resolved here, per hit, and nowhere else. */
#ifndef BIREF_SHADER_INTERNAL_H
#define BIREF_SHADER_INTERNAL_H

#include <math.h>

#include "biref/shading.h"
#include "shading/packet_light.h"
#include "spectral/integrator_internal.h"
#include "spectral/phase_prefilter.h"

/* biref_slab_prepare needs theta < pi/2; a ray grazing a slab is clamped just below. */
#define BIREF_SHADING_THETA_MAX (0.5 * M_PI - 1e-7)

struct biref_shader {
    const biref_spectral *sp;
    biref_integrator *it;
    biref_light light;
    int world_fixed;    /* the light has a world-fixed polarizer or analyzer */
    double passthrough; /* not world-fixed: what the light passes with no slab, the same for every ray */
    /* A light outside the paper's s/p model with real matrices (world-fixed linear polarizers,
     * linear Stokes light and analyzers) in the packet kernel's form, resolved per hit
     * (packet_light.h); packet_lit 0 when the light is the paper's or has complex matrices. */
    int packet_lit;
    biref_packet_light_source packet_light;
};

/* The paper's frames of the unit view ray dir at a hit on a slab with unit normal, unit tangent
 * and unit world optic axis; base gives the slab's constants (its axis is replaced). */
void biref_shading_frames(const double normal[3], const double tangent[3], const double axis_world[3],
                          const biref_slab *base, const double dir[3], biref_hit_frames *f);

/* A hit's transmission and reflection factors from its frames, the phase integrals averaged over
 * the footprint fpT (in the transmission frame; NULL: point look-ups). The slab's constants must
 * have passed biref_slab_check. Outputs undefined unless BIREF_OK. */
biref_status biref_shader_eval(const biref_shader *sh, const biref_hit_frames *f, const biref_opl_footprint *fpT,
                               double T[3], double R[3]);

/* A stack slab's hit (shade_stack.c): the frames f of the ray, the slab's unit normal and tangent
 * and its stack with axes in that local frame, layers from the +normal face downwards. The codes of
 * biref_integrate_stack_hit and biref_stack_prepare. */
biref_status biref_shader_eval_stack(const biref_shader *sh, const biref_hit_frames *f, const double normal[3],
                                     const double tangent[3], const biref_stack *local, double T[3], double R[3]);

/* The light of one side of a hit in the basis s = x (both waves), p = k x s. */
void biref_shader_side_light(const biref_shader *sh, const double x[3], const double k_in[3], const double k_out[3],
                             biref_light *out);

/* The shader's light per hit in the packet kernel's form (packet_light.h), or NULL when the hits need
 * none (the paper's s/p light, the same for every hit) or the light has no real form (circular
 * light or analyzers: those hits go one by one). */
const biref_packet_light_source *biref_shader_packet_light(const biref_shader *sh);

/* Hits in the packet kernel's form (integrator_internal.h): T, R of the hits whose scalar[k] is 0;
 * scalar[k] = 1 for the hits to evaluate with biref_shader_eval. lights: each hit's light from
 * biref_packet_light_of with biref_shader_packet_light's source (NULL when that is NULL); without
 * them a light outside the paper's model sends every hit one by one. */
void biref_shader_packet(const biref_shader *sh, const biref_packet_hit *hits, const biref_packet_hit_light *lights,
                         const biref_opl_footprint *fp, size_t n, double (*T)[3], double (*R)[3],
                         unsigned char *scalar);

/* The factor of light that reaches the viewer along k without a slab, in the basis whose s is
 * perpendicular to k and the normal (the tangent when k is along the normal). */
double biref_shader_background(const biref_shader *sh, const double k[3], const double normal[3],
                               const double tangent[3]);

/* A hit whose evaluation failed: the slab shown as a perfect mirror seen through the analyzer. */
/* biref_shader_eval for a slab of a dispersive material (f->slab's indices are ignored): T and R by
 * biref_integrate_material with the shader's integrator, point look-ups. */
biref_status biref_shader_eval_material(const biref_shader *sh, const biref_material *m, const biref_hit_frames *f,
                                        double T[3], double R[3]);
void biref_shader_failed_hit(const biref_shader *sh, const biref_hit_frames *f, double T[3], double R[3]);

#endif
