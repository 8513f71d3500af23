/* Headless OpenGL >= 4.3 core through EGL, running the library's GLSL scene shader
 * (docs/GPU.md). libepoxy resolves EGL and GL at run time, so biref starts on machines without
 * them and gets a one-line error from gl_context_create instead. */
#ifndef BIREF_CLI_GL_CONTEXT_H
#define BIREF_CLI_GL_CONTEXT_H

#include <stddef.h>

#include "biref/biref.h"

typedef struct gl_context gl_context;

/* Hardware EGL devices first, then Mesa's surfaceless platform (no window system, no GPU
 * needed: llvmpipe), then the default display. On failure (no EGL, no OpenGL 4.3, shader build) BIREF_ERR_IO with one line
 * in msg. One object per thread. */
biref_status gl_context_create(gl_context **out, char *msg, size_t msg_len);
void gl_context_destroy(gl_context *g);

/* "vendor, renderer, version" of the context. */
const char *gl_context_description(const gl_context *g);

/* Renders the scene at its camera's size into xyz (width * height * 3 floats, top row first,
 * exposure applied: the layout of biref_render_image), by the analytic method (pairs 0) or
 * analytic-pairs (1: the shader's u_pairs). gpu_ms (may be NULL): GPU time of the
 * frame from timer queries; stats (may be NULL): pixel counts. */
biref_status gl_context_render(gl_context *g, const biref_scene *scene, int pairs, float *xyz, double *gpu_ms,
                               biref_render_stats *stats, char *msg, size_t msg_len);

#endif
