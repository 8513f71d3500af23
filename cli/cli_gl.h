/* The OpenGL back-end for render and bench (docs/GPU.md). */
#ifndef BIREF_CLI_GL_H
#define BIREF_CLI_GL_H

#include "cli_common.h"

/* Parses --backend: 0 = cpu, 1 = gl; prints the error and returns -1 otherwise. */
int cli_parse_backend(const char *cmd, const char *text, int *gl);

/* Renders the scene with the GL back-end into xyz (layout of biref_render_image). *gpu_ms is
 * the GPU time (timer query), device the context's "vendor, renderer, version". Returns 0, or prints one line and returns CLI_EXIT_FAIL (no EGL /
 * OpenGL 4.3, or a GL failure). */
int cli_gl_render(const char *cmd, const biref_scene *scene, int pairs, float *xyz, biref_render_stats *stats,
                  double *gpu_ms, char *device, size_t device_len);

/* Times `frames` frames after one warm-up: median GPU time (timer queries) and median wall time
 * per frame (draw to read-back), and the context's description. Returns 0 or as above. */
int cli_gl_bench(const char *cmd, const biref_scene *scene, int frames, double *gpu_ms, double *wall_ms, char *device,
                 size_t device_len);

#endif
