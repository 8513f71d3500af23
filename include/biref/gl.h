/* biref — the analytic method on the GPU: one GLSL source (shaders/biref_analytic.glsl) for
 * desktop OpenGL >= 4.3 core (headless through EGL) and WebGL2. docs/GPU.md.
 *
 * The shader's data comes from this library, so the CPU and GPU paths share one source of
 * truth: the look-up table of S(cos kD), S(sin kD) (biref_gl_table) and the scene's uniforms
 * (biref_gl_scene_uniforms: the same frames, radiances and polarizers as biref_renderer). The
 * native back-end (biref_gl_*) is a separate library, biref_gl, linked to libepoxy; EGL and the
 * OpenGL driver are loaded at run time, so a program linked to it still starts where they are
 * missing and gets a one-line error from biref_gl_create instead. */
#ifndef BIREF_GL_H
#define BIREF_GL_H

#include <stddef.h>

#include "biref/common.h"
#include "biref/render.h"
#include "biref/spectral.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The GLSL source (without #version line; see its header comment for the defines). */
const char *biref_gl_shader_source(void);

/* Look-up table as an RGBA float texture of width x 4 texels (row-major, row 0 first): rows 0-2
 * hold band j's demodulated F_j at node m as (re, im, dre/dD, dim/dD), row 3 the carrier
 * e^{2 pi i nu_c m step} as (cos, sin, 0, 0) computed in double precision. */
typedef struct {
    int width, height;
    double step_nm, d_max_nm, d_far_nm, nu_c, lambda_min_nm, lambda_max_nm;
    double edge_lo[3], edge_hi[3], k_centroid[3];
} biref_gl_table_info;

/* Fills info and, if texels is not NULL, width * height * 4 floats. */
void biref_gl_table(const biref_spectral *sp, biref_gl_table_info *info, float *texels);

/* Every uniform of the shader except the sampler, as (name, components 1-4, array count, values):
 * camera, slabs, panels, environment, polarizer and analyzer, look-up-table constants and the
 * XYZ -> linear sRGB matrix. A scene with more slabs or panels than the shader's arrays hold is
 * the caller's to refuse. */
typedef void (*biref_gl_uniform_fn)(void *user, const char *name, int components, int count, const float *v);
void biref_gl_scene_uniforms(const biref_scene *scene, const biref_spectral *sp, biref_gl_uniform_fn fn, void *user);

/* ------------------------------------------------------------------------------------------ */
/* Native back-end (library biref_gl)                                                          */
/* ------------------------------------------------------------------------------------------ */
typedef struct biref_gl biref_gl;

/* Creates a headless OpenGL >= 4.3 core context through EGL (Mesa's surfaceless platform first,
 * then the default display), compiles the shader and uploads the look-up table. On failure
 * (no EGL, no OpenGL 4.3, shader build) returns BIREF_ERR_IO with one line in msg. One object
 * per thread. */
biref_status biref_gl_create(biref_gl **out, char *msg, size_t msg_len);
void biref_gl_destroy(biref_gl *g);

/* "vendor, renderer, version" of the context. */
const char *biref_gl_description(const biref_gl *g);

/* Renders the scene at its camera's size into xyz (width * height * 3 floats, top row first,
 * exposure applied: the layout of biref_render_image). gpu_ms (may be NULL) receives the GPU
 * time of the frame from a timer query; stats (may be NULL) the pixel counts. */
biref_status biref_gl_render(biref_gl *g, const biref_scene *scene, float *xyz, double *gpu_ms,
                             biref_render_stats *stats, char *msg, size_t msg_len);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_GL_H */
