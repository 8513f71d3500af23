#include "cli_render.h"

#include <stdlib.h>

#include "outfile.h"

int cli_load_scene(const char *cmd, const char *path, biref_scene *scene)
{
    char msg[320];
    biref_status s = biref_scene_load(path, scene, msg, sizeof msg);
    if (s != BIREF_OK) {
        cli_error(cmd, "%s: %s", path, msg);
        return CLI_EXIT_USAGE;
    }
    return 0;
}

int cli_gl_refuse_stacks(const char *cmd, const char *path, const biref_scene *scene)
{
    for (int i = 0; i < scene->n_slabs; i++)
        if (scene->slabs[i].n_layers > 0)
            return cli_error(cmd, "%s: slabs[%d] is a stack (layers), which the GLSL path does not render (use the "
                                  "CPU back-end)",
                             path, i),
                   CLI_EXIT_USAGE;
    return 0;
}

int cli_scene_resize(const char *cmd, biref_scene *scene, long width, long height)
{
    if (width > 0) scene->camera.width = (int)width;
    if (height > 0) scene->camera.height = (int)height;
    char msg[320];
    if (biref_scene_validate(scene, msg, sizeof msg) != BIREF_OK) {
        cli_error(cmd, "%s", msg);
        return CLI_EXIT_USAGE;
    }
    return 0;
}

/* The process's spectral context: created at the first use, destroyed at exit. */
static biref_spectral *process_sp;

static void destroy_process_sp(void) { biref_spectral_destroy(process_sp); }

const biref_spectral *cli_spectral(const char *cmd)
{
    if (process_sp) return process_sp;
    char why[BIREF_MSG_SIZE];
    if (biref_spectral_create(NULL, &process_sp, why, sizeof why) != BIREF_OK) {
        cli_error(cmd, "cannot create the spectral tables: %s", why);
        return NULL;
    }
    atexit(destroy_process_sp);
    return process_sp;
}

int cli_renderer_create(const char *cmd, const biref_scene *scene, const biref_render_options *opt,
                        biref_renderer **out)
{
    const biref_spectral *sp = cli_spectral(cmd);
    if (!sp) return CLI_EXIT_FAIL;
    char msg[320];
    biref_status s = biref_renderer_create(sp, scene, opt, out, msg, sizeof msg);
    if (s == BIREF_OK) return 0;
    cli_error(cmd, "%s", msg);
    return s == BIREF_ERR_INVALID ? CLI_EXIT_USAGE : CLI_EXIT_FAIL;
}

int cli_check_writable(const char *cmd, const char *path)
{
    char msg[600];
    if (biref_outfile_check(path, msg, sizeof msg) != BIREF_OK) return cli_error(cmd, "%s", msg), CLI_EXIT_FAIL;
    return 0;
}

int cli_check_output(const char *cmd, const char *out, const char *const *inputs, int n_inputs)
{
    for (int i = 0; i < n_inputs; i++)
        if (inputs[i] && biref_outfile_is_file(out, inputs[i]))
            return cli_error(cmd, "%s: output would overwrite the input file %s", out, inputs[i]), CLI_EXIT_USAGE;
    return cli_check_writable(cmd, out);
}
