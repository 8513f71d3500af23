#include "cli_render.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

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
    size_t n = strlen(path);
    char *dir = malloc(n + 2);
    if (!dir) return cli_error(cmd, "out of memory"), CLI_EXIT_FAIL;
    memcpy(dir, path, n + 1);
    char *slash = strrchr(dir, '/');
    if (!slash)
        strcpy(dir, ".");
    else if (slash == dir)
        dir[1] = '\0';
    else
        *slash = '\0';
    struct stat st;
    int rc = 0;
    if (n == 0 || path[n - 1] == '/') {
        cli_error(cmd, "%s: cannot write: not a file name", path);
        rc = CLI_EXIT_FAIL;
    } else if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        cli_error(cmd, "%s: cannot write: directory '%s' does not exist", path, dir);
        rc = CLI_EXIT_FAIL;
    } else if (access(dir, W_OK | X_OK) != 0) {
        cli_error(cmd, "%s: cannot write: %s", path, strerror(errno));
        rc = CLI_EXIT_FAIL;
    } else if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
        cli_error(cmd, "%s: cannot write: is a directory", path);
        rc = CLI_EXIT_FAIL;
    }
    free(dir);
    return rc;
}
