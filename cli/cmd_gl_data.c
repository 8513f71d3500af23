/* biref gl-data: the browser viewer's data (web/biref_data.js) from the library: the GLSL
 * source, the look-up table and the uniforms of a set of scenes (docs/GPU.md). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_files.h"
#include "cli_gl.h"
#include "cli_render.h"
#include "commands.h"
#include "outfile.h"
#include "json_out.h"

static const char *const CMD = "gl-data";

typedef struct {
    const char *out;
} gl_data_args;

static const cli_opt OPTS[] = {
    CLI_STRING("output", 'o', "FILE", offsetof(gl_data_args, out), "the module to write (required)"),
};

const cli_command_spec CLI_GL_DATA = {
    "gl-data",
    "usage: biref gl-data -o FILE.js SCENE.json...\n\n"
    "Writes a JavaScript module for the WebGL2 viewer (web/index.html): the GLSL source of the\n"
    "analytic method (shaders/biref_analytic.glsl, as compiled into the library), the look-up\n"
    "table of S(cos kD), S(sin kD) and the coherent regime's sample plans as float texels, and\n"
    "each scene's shader uniforms as a\n"
    "preset named after its file. The repository's copy is made with\n"
    "  biref gl-data -o web/biref_data.js examples/*.json\n\n"
    "Options:\n",
    OPTS,
    CLI_OPTS_COUNT(OPTS),
    NULL,
    0,
    NULL,
    0,
    NULL,
};

static void add_uniform(void *user, const char *name, int comps, int count, const float *v)
{
    cJSON *u = cJSON_CreateArray();
    cJSON_AddItemToArray(u, cJSON_CreateNumber(comps));
    cJSON *vals = cJSON_CreateArray();
    for (int i = 0; i < comps * count; i++) {
        /* Shortest decimal that reads back as the same float. */
        char buf[32];
        snprintf(buf, sizeof buf, "%.9g", (double)v[i]);
        cJSON_AddItemToArray(vals, cJSON_CreateNumber(strtod(buf, NULL)));
    }
    cJSON_AddItemToArray(u, vals);
    cJSON_AddItemToObject((cJSON *)user, name, u);
}

static cJSON *vec3(const double v[3]) { return json_vec3(v); }

static const char *basename_of(const char *path, char *buf, size_t n)
{
    const char *b = strrchr(path, '/');
    b = b ? b + 1 : path;
    snprintf(buf, n, "%s", b);
    char *dot = strrchr(buf, '.');
    if (dot && !strcmp(dot, ".json")) *dot = '\0';
    return buf;
}

int cmd_gl_data(int argc, char **argv)
{
    gl_data_args args = {NULL};
    cli_parsed parsed;
    int r = cli_opts_parse(&CLI_GL_DATA, &args, argc, argv, &parsed);
    if (r) return r > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    const char *out = args.out;
    const int first_arg = parsed.first_arg;
    if (!out) return cli_error(CMD, "missing -o FILE.js"), CLI_EXIT_USAGE;
    if (first_arg >= argc) return cli_error(CMD, "missing SCENE.json (see biref gl-data --help)"), CLI_EXIT_USAGE;
    cli_files files;
    cli_files_init(&files);
    for (int i = first_arg; i < argc; i++) cli_files_read(&files, "SCENE", argv[i]);
    cli_files_write(&files, "-o", "js", out);
    int rc = cli_files_check(CMD, &files);
    cli_files_free(&files);
    if (rc) return rc;
    biref_spectral *sp = NULL;
    char why[BIREF_MSG_SIZE];
    if (biref_spectral_create(NULL, &sp, why, sizeof why) != BIREF_OK)
        return cli_error(CMD, "cannot build the look-up table: %s", why), CLI_EXIT_FAIL;

    cJSON *presets = cJSON_CreateObject();
    for (int i = first_arg; i < argc && !rc; i++) {
        biref_scene scene;
        if ((rc = cli_load_scene(CMD, argv[i], &scene)) || (rc = cli_gl_refuse_stacks(CMD, argv[i], &scene)))
            break;
        for (int k = 0; k < scene.n_slabs && !rc; k++)
            if (scene.slabs[k].material) {
                cli_error(CMD, "%s: slabs[%d].material: the browser viewer takes constant indices only (eta_o, eta_e); "
                          "render dispersive materials with biref render (--backend gl or cpu)", argv[i], k);
                rc = CLI_EXIT_USAGE;
            }
        if (rc) break;
        char name[256];
        basename_of(argv[i], name, sizeof name);
        if (cJSON_GetObjectItemCaseSensitive(presets, name)) {
            cli_error(CMD, "%s: two scenes named '%s'", argv[i], name);
            rc = CLI_EXIT_USAGE;
            break;
        }
        cJSON *p = cJSON_CreateObject(), *u = cJSON_CreateObject();
        biref_gl_scene_uniforms(&scene, sp, add_uniform, u);
        cJSON *cam = cJSON_CreateObject();
        cJSON_AddItemToObject(cam, "position", vec3(scene.camera.position));
        cJSON_AddItemToObject(cam, "look_at", vec3(scene.camera.look_at));
        cJSON_AddItemToObject(cam, "up", vec3(scene.camera.up));
        cJSON_AddNumberToObject(cam, "fov_deg", scene.camera.fov_deg);
        cJSON_AddNumberToObject(cam, "width", scene.camera.width);
        cJSON_AddNumberToObject(cam, "height", scene.camera.height);
        cJSON *axes = cJSON_CreateArray();
        for (int k = 0; k < scene.n_slabs; k++) {
            double a[3];
            biref_axis_normalize(scene.slabs[k].axis, a);
            cJSON_AddItemToArray(axes, vec3(a));
        }
        cJSON_AddItemToObject(p, "camera", cam);
        cJSON_AddItemToObject(p, "axes", axes);
        cJSON_AddItemToObject(p, "uniforms", u);
        cJSON_AddItemToObject(presets, name, p);
    }
    biref_gl_table_info info;
    biref_gl_table(sp, &info, NULL);
    float *tex = rc ? NULL : malloc((size_t)info.width * info.height * 4 * sizeof *tex);
    if (!rc && !tex) {
        cli_error(CMD, "out of memory");
        rc = CLI_EXIT_FAIL;
    }
    if (!rc) {
        biref_gl_table(sp, &info, tex);
        cJSON *src = cJSON_CreateString(biref_gl_shader_source());
        char *src_text = cJSON_PrintUnformatted(src), *preset_text = cJSON_PrintUnformatted(presets);
        cJSON_Delete(src);
        char msg[600] = "";
        biref_outfile *of = src_text && preset_text ? biref_outfile_open(out, msg, sizeof msg) : NULL;
        FILE *f = of ? biref_outfile_stream(of) : NULL;
        if (!f) {
            cli_error(CMD, "%s", msg[0] ? msg : "out of memory");
            rc = CLI_EXIT_FAIL;
        } else {
            fprintf(f, "// Generated by `biref gl-data` from the biref library: the GLSL source, the look-up table\n"
                       "// and the example scenes' uniforms. Do not edit; regenerate (docs/GPU.md).\n");
            fprintf(f, "export const shaderSource = %s;\n", src_text);
            fprintf(f, "export const table = {width: %d, height: %d, texels: new Float32Array([", info.width, info.height);
            const size_t n = (size_t)info.width * info.height * 4;
            for (size_t k = 0; k < n; k++) fprintf(f, "%s%.9g", k ? (k % 16 ? "," : ",\n") : "\n", (double)tex[k]);
            fprintf(f, "])};\n");
            /* The coherent regime's sample plans (thin slabs, evanescent coupling). */
            biref_gl_plans_info pl;
            biref_gl_coherent_plans(sp, &pl, NULL);
            float *pt = malloc((size_t)pl.width * pl.height * 4 * sizeof *pt);
            if (pt) {
                biref_gl_coherent_plans(sp, &pl, pt);
                fprintf(f, "export const plans = {width: %d, height: %d, texels: new Float32Array([", pl.width, pl.height);
                const size_t np = (size_t)pl.width * pl.height * 4;
                for (size_t k = 0; k < np; k++) fprintf(f, "%s%.9g", k ? (k % 16 ? "," : ",\n") : "\n", (double)pt[k]);
                fprintf(f, "])};\n");
                free(pt);
            } else {
                rc = CLI_EXIT_FAIL;
                cli_error(CMD, "out of memory");
            }
            fprintf(f, "export const presets = %s;\n", preset_text);
            /* Put in place only when complete: a failed run leaves the previous module intact. */
            if (biref_outfile_close(of, !rc, msg, sizeof msg) != BIREF_OK) {
                cli_error(CMD, "%s", msg);
                rc = CLI_EXIT_FAIL;
            }
        }
        free(src_text);
        free(preset_text);
    }
    free(tex);
    cJSON_Delete(presets);
    biref_spectral_destroy(sp);
    if (!rc) printf("wrote %s (%d texels, %d presets)\n", out, info.width * info.height, argc - first_arg);
    return rc;
}
