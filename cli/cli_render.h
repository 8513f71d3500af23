/* Plumbing shared by the image commands (render, bench, diff). */
#ifndef BIREF_CLI_RENDER_H
#define BIREF_CLI_RENDER_H

#include "cli_common.h"

/* Loads and validates a scene; prints "biref CMD: error: PATH: FIELD: reason" and returns
 * CLI_EXIT_USAGE on failure (a missing or unreadable scene is bad input), else 0. */
int cli_load_scene(const char *cmd, const char *path, biref_scene *scene);

/* The GLSL path covers no stack method: refuses (CLI_EXIT_USAGE, one line naming the slab) a scene
 * with a stack slab (layers) for the GL back-end and gl-data; 0 otherwise. */
int cli_gl_refuse_stacks(const char *cmd, const char *path, const biref_scene *scene);

/* Applies --width/--height overrides (0 = keep) and re-validates. */
int cli_scene_resize(const char *cmd, biref_scene *scene, long width, long height);

/* The default spectral context, one per process: created at the first call, destroyed at exit.
 * NULL (after one error line) if it cannot be created. */
const biref_spectral *cli_spectral(const char *cmd);

/* Creates a renderer on cli_spectral's context; an unsupported method/scene combination is bad usage (2), anything
 * else a runtime failure (1). Returns 0 on success. */
int cli_renderer_create(const char *cmd, const biref_scene *scene, const biref_render_options *opt,
                        biref_renderer **out);

/* Checks before a long computation that PATH's directory exists and is writable, so the user
 * learns about a typo immediately; the write itself is still checked. Returns 0 if fine. */
int cli_check_writable(const char *cmd, const char *path);
/* The same, and refuses (CLI_EXIT_USAGE) an output that is one of the command's input files. */
int cli_check_output(const char *cmd, const char *out, const char *const *inputs, int n_inputs);

#endif
