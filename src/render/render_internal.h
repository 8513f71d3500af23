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
    const biref_material *material; /* dispersive (the indices in base are stand-ins), or NULL */
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
    double *centre_sx; /* per column: render_camera_sx of its pixel centres (biref_render_camera_columns) */
};

/* camera.c */
void biref_render_camera_init(render_camera *c, const biref_camera *cam);
/* sx[x] = render_camera_sx(c, x + 0.5) for every column x: a row of pixel centres costs the tiles
 * no division per pixel. Neither offset has a multiply-add to contract, so the table holds the bits
 * the tiles would compute. */
void biref_render_camera_columns(const render_camera *c, double *sx);

/* The image-plane offsets (at unit distance, along right and up) of the image point (fx, fy), in
 * pixels: the one expression of the tiles, their footprints and the column table. */
static inline double render_camera_sx(const render_camera *c, double fx)
{
    return (2.0 * fx / c->width - 1.0) * c->tan_half_h;
}
static inline double render_camera_sy(const render_camera *c, double fy)
{
    return (1.0 - 2.0 * fy / c->height) * c->tan_half_v;
}

/* footprint.c: the change of each leg type's optical path between the unit ray dir and the unit
 * rays dir_x (right) and dir_y (below) of the neighbouring samples on the slab sl, in its
 * transmission frame (the per-ray form of footprint_legs.h, whose body the tiles share). */
void biref_render_footprint_rays(const biref_renderer *r, const render_slab *sl, const double dir[3],
                                 const double dir_x[3], const double dir_y[3], biref_opl_footprint *fp);

#endif
