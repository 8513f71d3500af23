/* Internal layout of the renderer: everything per scene is precomputed here so that the
 * per-pixel code does no allocation and no repeated normalisation. */
#ifndef BIREF_RENDER_INTERNAL_H
#define BIREF_RENDER_INTERNAL_H

#include <complex.h>

#include "biref/integrator.h"
#include "biref/render.h"
#include "biref/shading.h"
#include "shading/shader_internal.h"
#include "spectral/phase_prefilter.h"

/* Rays leave surfaces from exactly on them; hits closer than this are the surface itself. */
#define BIREF_RENDER_RAY_EPS 1e-9
/* biref_slab_prepare needs theta < pi/2; a ray grazing a slab is clamped just below. */
#define BIREF_RENDER_THETA_MAX BIREF_SHADING_THETA_MAX

typedef struct {
    double origin[3];
    double forward[3], right[3], up[3]; /* orthonormal; right = forward x up_hint */
    double tan_half_h, tan_half_v;      /* image plane half extents at unit distance */
    int width, height;
} render_camera;

typedef struct {
    double center[3], normal[3], tangent[3], bitangent[3]; /* bitangent = tangent x normal (local z) */
    double half_w, half_h;
    double axis_world[3]; /* optic axis in world coordinates, unit */
    biref_slab base;      /* indices, thickness, eta_i; axis filled per ray */
    double center_n;      /* (center - camera origin) . normal: the camera ray's plane distance */
    int is_stack;         /* a stack slab: base unused (the packet kernel's work on it is discarded) */
    biref_stack stack;    /* is_stack: axes in the local frame, layers from the +normal face */
} render_slab;

typedef struct {
    double center[3], normal[3], tangent[3], bitangent[3];
    double half_w, half_h;
    double radiance_xyz[3];
} render_panel;

typedef struct {
    biref_env_type type;
    double up[3], e1[3], e2[3]; /* e1, e2 span the ground plane (checker) */
    double zenith[3], horizon[3], ground[3], check_a[3], check_b[3]; /* XYZ */
    double check_size;
} render_env;

struct biref_renderer {
    biref_render_options opt;
    render_camera cam;
    int n_slabs, n_panels;
    render_slab slabs[BIREF_SCENE_MAX_SLABS];
    render_panel panels[BIREF_SCENE_MAX_PANELS];
    render_env env;
    double exposure;
    biref_shader *shader;             /* the method's integrator under the scene's light */
    biref_phase_prefilter *prefilter; /* antialias prefilter: analytic and expansion */
    int tile_isa;                     /* biref_render_tile_isa */
};

/* camera.c */
void biref_render_camera_init(render_camera *c, const biref_camera *cam);
/* Unit direction through the centre of pixel (x, y), y = 0 at the top. */
void biref_render_camera_ray(const render_camera *c, int x, int y, double dir[3]);
/* Unit direction through the image point (fx, fy) in pixels (pixel (x, y) spans [x, x + 1) x [y, y + 1)). */
void biref_render_camera_ray_at(const render_camera *c, double fx, double fy, double dir[3]);

/* shade.c */
void biref_render_env_init(render_env *e, const biref_environment *env);
/* Radiance (XYZ) arriving along the ray from `from` in direction dir: the nearest panel in
 * front of `from`, else the environment. */
void biref_render_radiance(const biref_renderer *r, const double from[3], const double dir[3], double xyz[3]);
/* The whole pixel: nearest slab hit, transmission and reflection, or the filtered
 * background. Returns 1 if a slab was hit, and sets *fallback when a slab evaluation
 * failed and the fallback was used. dx, dy: the steps from dir to the neighbouring samples'
 * directions, for the prefilter's footprint (NULL: point phase integrals). */
int biref_render_shade_pixel(const biref_renderer *r, const double dir[3], const double dx[3], const double dy[3],
                             double xyz[3], int *fallback);
/* One hit's transmission and reflection factors: the slab's (footprint fp, may be NULL) or the
 * stack's (docs/STACKS.md §5). */
biref_status biref_render_eval(const biref_renderer *r, const render_slab *sl, const biref_hit_frames *fr,
                               const biref_opl_footprint *fp, double T[3], double R[3]);
/* The nearest slab along the camera ray dir (NULL: none), its distance in *t. */
const render_slab *biref_render_nearest_slab(const biref_renderer *r, const double dir[3], double *t);
/* A pixel that hits no slab: the background through the filter. */
void biref_render_background(const biref_renderer *r, const double dir[3], double xyz[3]);
/* A slab pixel's colour at hit point hp from the slab's transmission and reflection factors. */
void biref_render_hit_colour(const biref_renderer *r, const double hp[3], const double dir[3],
                             const biref_hit_frames *fr, const double tT[3], const double tR[3], double xyz[3]);

/* footprint.c: the change of each leg type's optical path between the ray dir and the rays
 * dir + dx, dir + dy (the neighbouring samples) on the slab sl, in its transmission frame. */
void biref_render_footprint(const biref_renderer *r, const render_slab *sl, const double dir[3], const double dx[3],
                            const double dy[3], biref_opl_footprint *fp);
/* The same from the neighbouring samples' unit rays dir_x (right) and dir_y (below). */
void biref_render_footprint_rays(const biref_renderer *r, const render_slab *sl, const double dir[3],
                                 const double dir_x[3], const double dir_y[3], biref_opl_footprint *fp);

#endif
