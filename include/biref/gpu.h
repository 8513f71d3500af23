/* biref — the analytic method on the GPU: one GLSL source (shaders/biref_analytic.glsl, also
 * compiled into the library) for desktop OpenGL >= 4.3 core and WebGL2 (GLSL ES 3.00).
 * docs/GPU.md shows how to embed it.
 *
 * The shader's data comes from this library, so the CPU and GPU paths share one source of
 * truth: the look-up table of S(cos kD), S(sin kD) (biref_gl_table) and a scene's uniforms
 * (biref_gl_scene_uniforms: the same frames, radiances and polarizers as biref_renderer).
 * Nothing here calls OpenGL: `biref render --backend gl` runs the shader through EGL. */
#ifndef BIREF_GPU_H
#define BIREF_GPU_H

#include "biref/common.h"
#include "biref/render.h"
#include "biref/spectral.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The GLSL source, without a #version line (its header comment lists the defines a loader adds). */
BIREF_API const char *biref_gl_shader_source(void);

/* Look-up table as an RGBA float texture of width x height (= 4) texels, row-major, row 0 first:
 * rows 0-2 hold band j's demodulated F_j at node m as (re, im, dre/dD, dim/dD), row 3 the
 * carrier e^{2 pi i nu_c m step} as (cos, sin, 0, 0), computed in double precision. */
typedef struct {
    int width, height;
    double step_nm, d_max_nm, d_far_nm, nu_c, lambda_min_nm, lambda_max_nm;
    double edge_lo[3], edge_hi[3], k_centroid[3];
} biref_gl_table_info;

/* Fills info and, if texels is not NULL, width * height * 4 floats. */
BIREF_API void biref_gl_table(const biref_spectral *sp, biref_gl_table_info *info, float *texels);

/* The midpoint plans of the coherent regime (thin slabs, evanescent coupling; the exact integral
 * of eq. 17, src/spectral/coherent.c) as an RGBA float texture of width x height texels, row-major:
 * plan i has first_samples * 2^i samples starting at texel first_samples * (2^i - 1), each texel
 * (lambda_nm, w_x, w_y, w_z). */
typedef struct {
    int width, height, plans, first_samples;
} biref_gl_plans_info;

/* Fills info and, if texels is not NULL, width * height * 4 floats (unused texels 0). */
BIREF_API void biref_gl_coherent_plans(const biref_spectral *sp, biref_gl_plans_info *info, float *texels);

/* Dispersive materials (docs/PHYSICS.md §7, docs/GPU.md "Dispersive materials"). The sub-band
 * tables as an RGBA float texture of width x height texels, row-major: table t = 2^L - 2 + b
 * (level L = 1..levels, sub-band b of 2^L, uniform in k^2) holds band j in row 3 t + j, texels as
 * biref_gl_table's rows 0-2 (same nodes, same carrier: row 3 of that table); points: the number
 * of sample points of the legs' phases (the finest level's edges and midpoints). Fills info and,
 * if texels is not NULL, width * height * 4 floats: then the tables are made on first use (12 MB
 * held by sp, ~50 ms), BIREF_ERR_NOMEM when they cannot be. */
typedef struct {
    int width, height, levels, points;
} biref_gl_subband_info;
BIREF_API biref_status biref_gl_subband_table(const biref_spectral *sp, biref_gl_subband_info *info, float *texels);

/* Per slab i of a scene, rows_per_slab rows of an RGBA float texture of width texels (rows
 * i * rows_per_slab ..., all zero for a slab of constant indices): first the plans' texture
 * layout (biref_gl_coherent_plans) with the material's (n_o, n_e, dn_o/dλ, dn_e/dλ) at each
 * sample wavelength, then one row with the same at the sub-band sample points (texels
 * 0..points-1, ascending wavenumber, uniform in k^2 over the band) and at the three band
 * centroids 2 pi / k_centroid[j] (texels points..points+2) and at band j's two Gauss nodes i
 * (texel points + 3 + 2 j + i; the wavenumbers of u_band_node_k). dispersive: how many slabs have a
 * material. Fills info and, if texels is not NULL, width * height * 4 floats; BIREF_ERR_INVALID
 * (texels NaN there) where a material is unphysical (biref_material_check_band says why). */
typedef struct {
    int width, height, rows_per_slab, dispersive;
} biref_gl_material_info;
BIREF_API biref_status biref_gl_scene_materials(const biref_scene *scene, const biref_spectral *sp,
                                                biref_gl_material_info *info, float *texels);

/* Every uniform of the scene shader except the samplers u_lut, u_plans, u_subbands and u_material, as (name, components 1-4, array
 * count, values): camera, slabs, panels, environment, polarizer and analyzer, look-up-table
 * constants and the XYZ -> linear sRGB matrix. The scene must be valid (biref_scene_validate). */
typedef void (*biref_gl_uniform_fn)(void *user, const char *name, int components, int count, const float *v);
BIREF_API void biref_gl_scene_uniforms(const biref_scene *scene, const biref_spectral *sp, biref_gl_uniform_fn fn,
                                       void *user);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_GPU_H */
