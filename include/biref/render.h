/*
 * biref — a small ray caster for scenes of thin uniaxial slabs (scene files, rendering,
 * image I/O). Scene schema and frames: docs/SCENES.md.
 *
 * Per pixel: one perspective ray, the nearest slab it hits (a thin rectangle; lateral
 * offsets inside the slab ignored) and two spectral evaluations of that slab, one for
 * light transmitted from behind and one for light reflected from the camera side, each
 * in the paper's frame for that ray (docs/SCENES.md, "Frames").
 *
 * No global state. A biref_scene is plain data; a biref_renderer is immutable after
 * creation and may be used by several threads (it renders rows in parallel itself).
 */
#ifndef BIREF_RENDER_H
#define BIREF_RENDER_H

#include <stdio.h>

#include "biref/common.h"
#include "biref/material.h"
#include "biref/polarization.h"
#include "biref/spectral.h"
#include "biref/stack.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fixed capacities keep a scene plain data (copyable, no ownership rules). */
#define BIREF_SCENE_MAX_SLABS 32
#define BIREF_SCENE_MAX_PANELS 16
/* Largest accepted image side and pixel count (a 16k x 16k float image is 3 GiB). */
#define BIREF_SCENE_MAX_SIDE 16384
#define BIREF_SCENE_MAX_PIXELS (8192L * 8192L)

typedef struct {
    double position[3], look_at[3], up[3];
    double fov_deg;  /* vertical field of view, (0, 179] */
    int width, height;
    double exposure; /* multiplies every pixel's XYZ before encoding (default 1) */
} biref_camera;

typedef struct {
    double center[3];
    double size[2];     /* extent along tangent, along normal x tangent (scene units) */
    double normal[3];   /* unit; local +y */
    double tangent[3];  /* unit, orthogonal to normal; local +x */
    double axis[3];     /* optic axis in the local frame (x = tangent, y = normal, z = x cross y), unit */
    double eta_o, eta_e;
    double thickness_nm;
    /* A named dispersive material (scene key "material", material.h) instead of eta_o, eta_e
     * (then 0), or NULL. The renderer integrates its slabs with n(λ) (biref_integrate_material):
     * point look-ups (no prefilter); the GLSL shader does the same (biref_gl_scene_materials). */
    const biref_material *material;
    /* A stack slab (docs/STACKS.md §5): n_layers > 0 layers from the +normal face (local +y)
     * downwards, each optic axis in the local frame above, the scene's medium around; eta_o, eta_e,
     * axis and thickness_nm are then unused (thickness_nm: the layers' sum). 0: a plain slab. */
    int n_layers;
    biref_layer layers[BIREF_STACK_MAX_LAYERS];
} biref_scene_slab;

/* An emitting rectangle (both faces), seen along rays that leave a slab or the camera. */
typedef struct {
    double center[3];
    double size[2];
    double normal[3], tangent[3]; /* unit, orthogonal */
    double radiance[3];           /* linear sRGB, (1,1,1) = white E of unit radiance */
} biref_panel;

typedef enum { BIREF_ENV_GRADIENT = 0, BIREF_ENV_CHECKER = 1 } biref_env_type;

typedef struct {
    biref_env_type type;
    double up[3];                           /* unit */
    double zenith[3], horizon[3], ground[3]; /* linear sRGB radiances */
    double check_a[3], check_b[3];          /* checker: the two ground tile radiances */
    double check_size;                      /* checker: tile size, in units of the ground's depth below the eye */
} biref_environment;

typedef struct {
    biref_camera camera;
    double eta_medium; /* surrounding index, both sides of every slab */
    int n_slabs;
    biref_scene_slab slabs[BIREF_SCENE_MAX_SLABS];
    int n_panels;
    biref_panel panels[BIREF_SCENE_MAX_PANELS];
    biref_environment env;
    /* The scene file's "light.polarization" and "filter" as one light (polarization.h): s/p
     * fractions (relative to each ray's plane of incidence) or a world-fixed linear polarizer,
     * seen through no filter, an s or p filter or a world-fixed linear analyzer. */
    biref_light light;
} biref_scene;

/* Parses a scene (JSON text of len bytes, need not be NUL-terminated) and validates it.
 * On failure returns BIREF_ERR_INVALID and writes one line "FIELD: reason" into msg,
 * FIELD being the JSON path (e.g. "slabs[0].thickness_mm"). Vectors are normalised,
 * tangents orthogonalised, thickness converted to nm. */
BIREF_API biref_status biref_scene_parse(const char *text, size_t len, biref_scene *out, char *msg, size_t msg_len);

/* Reads and parses a file; msg is "FIELD: reason" as above, or "cannot read: ..."
 * with BIREF_ERR_IO. */
BIREF_API biref_status biref_scene_load(const char *path, biref_scene *out, char *msg, size_t msg_len);

/* Checks a scene built or modified in code (the same checks as biref_scene_parse, on
 * already-normalised data, with the same field names). */
BIREF_API biref_status biref_scene_validate(const biref_scene *scene, char *msg, size_t msg_len);

/* ------------------------------------------------------------------------ */
/* Rendering                                                                 */
/* ------------------------------------------------------------------------ */

/* Spatial anti-aliasing of the phase integrals (docs/ANTIALIASING.md). */
typedef enum {
    BIREF_ANTIALIAS_NONE = 0,     /* point look-ups at each sample's path differences (default) */
    BIREF_ANTIALIAS_PREFILTER = 1 /* S(cos kD), S(sin kD) averaged over each sample's footprint in D
                                     (analytic and expansion methods only) */
} biref_antialias;

#define BIREF_MAX_SUPERSAMPLE 64

typedef struct {
    biref_method method;
    int samples; /* BIREF_METHOD_NUMERIC: spectral samples (default 64); ignored otherwise */
    int threads; /* OpenMP threads; 0 = the OpenMP default */
    biref_expansion_opts expansion; /* BIREF_METHOD_EXPANSION: order / tolerance */
    biref_antialias antialias;      /* default BIREF_ANTIALIAS_NONE */
    int supersample; /* K x K stratified, jittered samples per pixel, box-filtered (default 1:
                        one ray through the pixel centre); 1 ... BIREF_MAX_SUPERSAMPLE */
} biref_render_options;

BIREF_API void biref_render_options_default(biref_render_options *opt);

typedef struct biref_renderer biref_renderer;

/* Precomputes everything per scene: its shader (shading.h: the method's integrator under the
 * scene's light, on the spectral context sp, which is borrowed and must outlive the renderer;
 * one context serves every renderer and shader of a process) and the per-slab frames.
 * BIREF_ERR_INVALID with a one-line msg if the scene or an option is invalid. */
BIREF_API biref_status biref_renderer_create(const biref_spectral *sp, const biref_scene *scene,
                                             const biref_render_options *opt, biref_renderer **out, char *msg,
                                             size_t msg_len);
BIREF_API void biref_renderer_destroy(biref_renderer *r);


typedef struct {
    long pixels;         /* pixels shaded */
    long slab_pixels;    /* of which hit a slab */
    long fallback_evals; /* slab evaluations that failed and used the fallback (no transmission, full reflection) */
} biref_render_stats;

/* Renders rows y_begin, y_begin + y_step, ... < y_end into xyz (the full image,
 * width * height * 3 floats, row-major from the top; rows not rendered are untouched).
 * XYZ is band-normalised (white E = (1,1,1)) and already multiplied by the exposure.
 * Deterministic: every pixel is independent of the thread count. No allocation per
 * pixel. stats and progress may be NULL. BIREF_ERR_ILLCOND if a pixel came out non-finite
 * (stored as 0; never expected for a validated scene); BIREF_ERR_INVALID for NULL arguments or
 * rows outside the image. One meaning per code, so no message buffer (common.h). */
BIREF_API biref_status biref_renderer_render(const biref_renderer *r, int y_begin, int y_end, int y_step, float *xyz,
                                             biref_progress_fn progress, void *progress_user, biref_render_stats *stats);

/* Convenience: the whole image. */
BIREF_API biref_status biref_render_image(const biref_renderer *r, float *xyz, biref_progress_fn progress,
                                          void *progress_user, biref_render_stats *stats);

BIREF_API int biref_renderer_width(const biref_renderer *r);
BIREF_API int biref_renderer_height(const biref_renderer *r);

/* ------------------------------------------------------------------------ */
/* Images                                                                    */
/* ------------------------------------------------------------------------ */

/* XYZ floats (3 per pixel) -> 8-bit encoded sRGB (clamped, NaN -> 0) / linear sRGB floats. */
BIREF_API void biref_xyz_image_to_srgb8(const float *xyz, size_t n_pixels, unsigned char *rgb);
BIREF_API void biref_xyz_image_to_linear_srgb(const float *xyz, size_t n_pixels, float *rgb);

/* Writes 8-bit RGB (top row first) as a PNG with an sRGB chunk. The file is written to
 * a temporary name in the same directory and renamed, so a failure leaves nothing behind.
 * BIREF_ERR_IO with a one-line msg on failure. */
BIREF_API biref_status biref_png_write_rgb8(const char *path, int width, int height, const unsigned char *rgb, char *msg,
                                            size_t msg_len);

/* Reads any PNG as 8-bit sRGB RGB (alpha composited on black); *rgb is malloc'ed. */
BIREF_API biref_status biref_png_read_rgb8(const char *path, int *width, int *height, unsigned char **rgb, char *msg,
                                           size_t msg_len);

/* Writes linear RGB floats (top row first) as a colour PFM (little-endian, rows stored
 * bottom to top as the format requires), atomically like biref_png_write_rgb8. */
BIREF_API biref_status biref_pfm_write(const char *path, int width, int height, const float *rgb, char *msg, size_t msg_len);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_RENDER_H */
