#include "cli_gl.h"

#include <stdlib.h>
#include <string.h>

#include "gl_context.h"

int cli_parse_backend(const char *cmd, const char *text, int *gl)
{
    if (!strcmp(text, "cpu")) *gl = 0;
    else if (!strcmp(text, "gl")) *gl = 1;
    else return cli_error(cmd, "--backend: expected cpu or gl, got '%s'", text), -1;
    return 0;
}

static int open_gl(const char *cmd, gl_context **g)
{
    char msg[400];
    if (gl_context_create(g, msg, sizeof msg) != BIREF_OK) return cli_error(cmd, "--backend gl: %s", msg), CLI_EXIT_FAIL;
    return 0;
}

int cli_gl_render(const char *cmd, const biref_scene *scene, int pairs, float *xyz, biref_render_stats *stats,
                  double *gpu_ms, char *device, size_t device_len)
{
    gl_context *g = NULL;
    int rc = open_gl(cmd, &g);
    if (rc) return rc;
    snprintf(device, device_len, "%s", gl_context_description(g));
    char msg[400];
    if (gl_context_render(g, scene, pairs, xyz, gpu_ms, stats, msg, sizeof msg) != BIREF_OK) {
        cli_error(cmd, "--backend gl: %s", msg);
        rc = CLI_EXIT_FAIL;
    }
    gl_context_destroy(g);
    return rc;
}

int cli_gl_bench(const char *cmd, const biref_scene *scene, int frames, double *gpu_ms, double *wall_ms, char *device,
                 size_t device_len)
{
    gl_context *g = NULL;
    int rc = open_gl(cmd, &g);
    if (rc) return rc;
    snprintf(device, device_len, "%s", gl_context_description(g));
    float *xyz = malloc((size_t)scene->camera.width * scene->camera.height * 3 * sizeof *xyz);
    double *gpu = malloc((size_t)(frames + 1) * sizeof *gpu), *wall = malloc((size_t)(frames + 1) * sizeof *wall);
    char msg[400];
    if (!xyz || !gpu || !wall) {
        cli_error(cmd, "out of memory");
        rc = CLI_EXIT_FAIL;
    }
    for (int i = 0; i <= frames && !rc; i++) {
        double t0 = biref_wall_seconds();
        if (gl_context_render(g, scene, 0, xyz, &gpu[i], NULL, msg, sizeof msg) != BIREF_OK) {
            cli_error(cmd, "--backend gl: %s", msg);
            rc = CLI_EXIT_FAIL;
        }
        wall[i] = 1e3 * (biref_wall_seconds() - t0);
    }
    if (!rc) {
        /* Frame 0 is the warm-up (shader JIT, first texture upload). */
        qsort(gpu + 1, (size_t)frames, sizeof *gpu, cli_cmp_double);
        qsort(wall + 1, (size_t)frames, sizeof *wall, cli_cmp_double);
        *gpu_ms = gpu[1 + frames / 2];
        *wall_ms = wall[1 + frames / 2];
    }
    free(xyz);
    free(gpu);
    free(wall);
    gl_context_destroy(g);
    return rc;
}
