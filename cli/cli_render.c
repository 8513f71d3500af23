#include "cli_render.h"

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

int cli_renderer_create(const char *cmd, const biref_scene *scene, const biref_render_options *opt,
                        biref_renderer **out)
{
    char msg[320];
    biref_status s = biref_renderer_create(scene, opt, out, msg, sizeof msg);
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
