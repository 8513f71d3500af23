/* biref render: a scene file to an sRGB PNG (and optionally a linear PFM). */
#include <math.h>
#include <omp.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "chroma_map.h"
#include "cli_files.h"
#include "cli_gl.h"
#include "cli_mpi.h"
#include "cli_mpi_render.h"
#include "cli_opts.h"
#include "cli_polarizer.h"
#include "cli_render.h"
#include "cli_values.h"
#include "commands.h"
#include "json_out.h"

static const char *const CMD = "render";

#define STR_(x) #x
#define STR(x) STR_(x)

enum { OPT_METHOD = 1, OPT_BACKEND, OPT_ORDER, OPT_TOLERANCE, OPT_ANTIALIAS };

/* The command line, parsed. */
typedef struct {
    const char *out, *pfm, *chroma, *scene_path;
    long width, height, threads, samples, supersample;
    int json, gl, antialias;
    int stack_slabs; /* slabs given as stacks (layers) */
    biref_render_options opt;
} render_args;

static int handle(void *args, int code, const char *arg)
{
    render_args *a = args;
    switch (code) {
    case OPT_METHOD:
        if (biref_method_from_name(arg, &a->opt.method) != BIREF_OK)
            return cli_error(CMD, "--method: expected analytic, analytic-pairs, numeric, ground-truth or expansion, got '%s'",
                             arg),
                   -1;
        return 0;
    case OPT_BACKEND: return cli_parse_backend(CMD, arg, &a->gl);
    case OPT_ORDER: return cli_parse_expansion_order(CMD, arg, &a->opt.expansion);
    case OPT_TOLERANCE: return cli_parse_expansion_tolerance(CMD, arg, &a->opt.expansion);
    case OPT_ANTIALIAS: {
        int prefilter;
        if (cli_parse_antialias(CMD, arg, &prefilter)) return -1;
        a->antialias = prefilter ? BIREF_ANTIALIAS_PREFILTER : BIREF_ANTIALIAS_NONE;
        return 0;
    }
    default: return -1;
    }
}

#define F(field) offsetof(render_args, field)
static const cli_opt OPTS[] = {
    CLI_STRING("output", 'o', "FILE", F(out),
               "output PNG (required; \"-\" = standard output). Written to a\n"
               "temporary file and renamed into place, or through a symlink,\n"
               "FIFO or device"),
    CLI_CUSTOM("method", "M", OPT_METHOD,
               "analytic (default; the paper's eq. 26), analytic-pairs (eq. 26 plus\n"
               "transmission's sibling and entry pairs, beyond the paper; docs/PHYSICS.md),\n"
               "numeric, ground-truth\n"
               "(numeric with " STR(BIREF_GROUND_TRUTH_SAMPLES) " samples) or expansion (exact integral of the\n"
               "path-group expansion; any polarizer, docs/PHYSICS.md §5); stack slabs:\n"
               "analytic, analytic-pairs and expansion by the stack expansion (docs/STACKS.md §5)"),
    CLI_CUSTOM("backend", "B", OPT_BACKEND,
               "cpu (default) or gl: the analytic method (or analytic-pairs) as a GLSL shader through\n"
               "EGL and OpenGL >= 4.3 (any polarizer; docs/GPU.md)"),
    CLI_INT("spectral-samples", "N", F(samples), 1, 65536, "spectral samples for --method numeric (default 64)"),
    CLI_EXPANSION_OPTIONS(OPT_ORDER, OPT_TOLERANCE),
    CLI_CUSTOM("antialias", "A", OPT_ANTIALIAS,
               "prefilter (default for analytic, analytic-pairs and expansion): each pixel averages\n"
               "the phase integrals over its footprint in path difference (no moire\n"
               "rings); none: one point look-up per sample (docs/ANTIALIASING.md)"),
    CLI_INT("supersample", "K", F(supersample), 1, BIREF_MAX_SUPERSAMPLE,
            "K x K stratified jittered samples per pixel, 1-64 (default 1)"),
    CLI_INT("width", "W", F(width), 1, BIREF_SCENE_MAX_SIDE, "image width in pixels (overrides the scene)"),
    CLI_INT("height", "H", F(height), 1, BIREF_SCENE_MAX_SIDE, "image height in pixels (overrides the scene)"),
    CLI_INT("threads", "T", F(threads), 1, 1024,
            "OpenMP threads (default: all cores); the image does not depend on T"),
    CLI_STRING("pfm", 0, "FILE", F(pfm), "also write linear sRGB floats as a PFM"),
    CLI_STRING("chroma-map", 0, "FILE", F(chroma),
               "also write each pixel's dE00 from the grey of its lightness (how\n"
               "visible its colour is, from the floats) on biref diff's scale"),
    CLI_FLAG("json", 0, F(json), "print {width, height, method, samples, ms, mean_srgb, ...} on stdout"),
    {.name = "samples", .kind = CLI_OPT_INT, .value = "N", .offset = F(samples), .lo = 1, .hi = 65536,
     .old_of = "spectral-samples"},
};
#undef F

const cli_command_spec CLI_RENDER = {
    "render",
    "usage: biref render SCENE.json -o OUT.png [OPTIONS]\n\n"
    "Renders a scene of thin uniaxial slabs (schema: docs/SCENES.md): per pixel the light\n"
    "transmitted from behind and reflected from the camera side, integrated over the CIE 1931\n"
    "colour-matching functions (380-700 nm), written as an 8-bit sRGB PNG.\n\n"
    "Options:\n",
    OPTS,
    CLI_OPTS_COUNT(OPTS),
    "Exit status: 0 success, 1 runtime failure (e.g. unwritable output), 2 bad usage or scene.\n\n"
    "Example:\n  biref render examples/fig9a.json -o fig9a.png --method numeric --spectral-samples 128\n",
    0,
    handle,
    1,
    NULL,
};

/* Options that only make sense together. Returns 0, 1 after --help, or -1 (one error printed). */
static int parse(int argc, char **argv, render_args *a)
{
    memset(a, 0, sizeof *a);
    a->supersample = 1;
    a->antialias = -1;
    biref_render_options_default(&a->opt);
    cli_parsed p;
    int r = cli_opts_parse(&CLI_RENDER, a, argc, argv, &p);
    if (r) return r;
    if (p.n_args < 1) return cli_error(CMD, "missing SCENE (see biref render --help)"), -1;
    if (p.n_args > 1) return cli_error(CMD, "unexpected argument '%s'", argv[p.first_arg + 1]), -1;
    a->scene_path = argv[p.first_arg];
    biref_render_options *opt = &a->opt;
    if (!a->out) return cli_error(CMD, "missing -o OUT.png"), -1;
    if (a->json && (strcmp(a->out, "-") == 0 || (a->pfm && strcmp(a->pfm, "-") == 0)))
        return cli_error(CMD, "--json and an image on standard output ('-') exclude each other"), -1;
    const int have_samples = cli_opts_given(&CLI_RENDER, &p, "spectral-samples");
    if (have_samples && opt->method != BIREF_METHOD_NUMERIC)
        return cli_error(CMD, "--spectral-samples only applies to --method numeric"), -1;
    if (have_samples) opt->samples = (int)a->samples;
    if ((cli_opts_given(&CLI_RENDER, &p, "order") || cli_opts_given(&CLI_RENDER, &p, "tolerance")) &&
        opt->method != BIREF_METHOD_EXPANSION)
        return cli_error(CMD, "--order/--tolerance only apply to --method expansion"), -1;
    opt->threads = (int)a->threads;
    if (a->threads > 0) omp_set_num_threads((int)a->threads); /* also the sRGB encoding's loop */
    const int analytic = opt->method == BIREF_METHOD_ANALYTIC || opt->method == BIREF_METHOD_ANALYTIC_PAIRS;
    if (a->gl && ((cli_opts_given(&CLI_RENDER, &p, "method") && !analytic) || a->threads))
        return cli_error(CMD, "--backend gl runs the analytic methods only (no --method other than analytic or "
                              "analytic-pairs, no --threads)"),
               -1;
    opt->supersample = (int)a->supersample;
    /* The prefilter needs the phase table of the analytic method and the expansion (on the CPU). */
    int table_method = !a->gl && (analytic || opt->method == BIREF_METHOD_EXPANSION);
    if (a->antialias == BIREF_ANTIALIAS_PREFILTER && !table_method)
        return cli_error(CMD, "--antialias prefilter needs --method analytic, analytic-pairs or expansion on the CPU"), -1;
    if (a->gl && a->supersample > 1) return cli_error(CMD, "--supersample needs the CPU back-end"), -1;
    opt->antialias = a->antialias >= 0 ? (biref_antialias)a->antialias
                                       : table_method ? BIREF_ANTIALIAS_PREFILTER : BIREF_ANTIALIAS_NONE;
    return 0;
}

/* What was rendered. */
typedef struct {
    int W, H;
    double ms, gpu_ms, mean[3];
    biref_render_stats stats;
    char device[256];
    cli_chroma_stats chroma; /* --chroma-map */
} render_result;

/* Renders the scene into xyz (W x H x 3). Returns a CLI exit code (one error printed unless OK). */
static int render_xyz(const render_args *a, const biref_scene *scene, float *xyz, render_result *res)
{
    biref_renderer *r = NULL;
    int rc;
    /* The GL back-end handles world-fixed polarizers too (docs/GPU.md): no CPU renderer then. */
    if (!a->gl && (rc = cli_renderer_create(CMD, scene, &a->opt, &r))) return rc;
    /* In an MPI job: every process is ready, or all stop with the first failure's line. */
    if ((rc = cli_mpi_agree(0))) return biref_renderer_destroy(r), rc;
    biref_progress_bar bar;
    biref_progress_bar_init(&bar, stderr, !a->gl, "render");
    double t0 = biref_wall_seconds();
    const int pairs = a->opt.method == BIREF_METHOD_ANALYTIC_PAIRS;
    if (a->gl && (rc = cli_gl_render(CMD, scene, pairs, xyz, &res->stats, &res->gpu_ms, res->device, sizeof res->device)))
        return rc;
    biref_status rs = a->gl              ? BIREF_OK
                      : cli_mpi_active() ? cli_mpi_render(r, xyz, biref_progress_bar_update, &bar, &res->stats)
                                         : biref_render_image(r, xyz, biref_progress_bar_update, &bar, &res->stats);
    res->ms = 1e3 * (biref_wall_seconds() - t0);
    biref_progress_bar_finish(&bar);
    biref_renderer_destroy(r);
    /* Not an error (the image is finite), but never silent. */
    if (rs == BIREF_OK && res->stats.fallback_evals > 0)
        fprintf(stderr,
                "biref render: warning: %s: %ld slab evaluations failed and show no transmission, full reflection "
                "(fallback_evaluations in --json)\n",
                a->scene_path, (long)res->stats.fallback_evals);
    if (rs != BIREF_OK)
        return cli_error(CMD, "%s: %s", a->scene_path,
                         rs == BIREF_ERR_ILLCOND ? "some pixels came out non-finite (no image written)"
                                                 : biref_status_string(rs)),
               CLI_EXIT_FAIL;
    return CLI_EXIT_OK;
}

/* Writes the PNG (and the PFM, reusing xyz) and the mean sRGB. Returns a CLI exit code. */
static int write_images(const render_args *a, float *xyz, unsigned char *rgb, render_result *res)
{
    const size_t n = (size_t)res->W * res->H;
    biref_xyz_image_to_srgb8(xyz, n, rgb);
    char msg[600];
    int rc = CLI_EXIT_OK;
    if (biref_png_write_rgb8(a->out, res->W, res->H, rgb, msg, sizeof msg) != BIREF_OK) {
        cli_error(CMD, "%s", msg);
        rc = CLI_EXIT_FAIL;
    }
    if (!rc && a->chroma) rc = cli_chroma_map_write(CMD, a->chroma, res->W, res->H, xyz, &res->chroma);
    if (!rc && a->pfm) {
        /* Reuse the XYZ buffer in place: each pixel is read before it is overwritten. */
        biref_xyz_image_to_linear_srgb(xyz, n, xyz);
        if (biref_pfm_write(a->pfm, res->W, res->H, xyz, msg, sizeof msg) != BIREF_OK) {
            cli_error(CMD, "%s", msg);
            rc = CLI_EXIT_FAIL;
        }
    }
    double *mean = res->mean;
    mean[0] = mean[1] = mean[2] = 0;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) mean[k] += rgb[3 * i + k];
    for (int k = 0; k < 3; k++) mean[k] /= 255.0 * (double)n;
    return rc;
}

static int print_report(const render_args *a, const render_result *res)
{
    const biref_render_options *opt = &a->opt;
    int samples_used = opt->method == BIREF_METHOD_NUMERIC        ? opt->samples
                       : opt->method == BIREF_METHOD_GROUND_TRUTH ? BIREF_GROUND_TRUTH_SAMPLES
                                                                  : 0;
    if (a->json) {
        cJSON *root = cJSON_CreateObject();
        cJSON_AddNumberToObject(root, "width", res->W);
        cJSON_AddNumberToObject(root, "height", res->H);
        cJSON_AddStringToObject(root, "method", biref_method_name(opt->method));
        cJSON_AddStringToObject(root, "backend", a->gl ? "gl" : "cpu");
        if (a->gl) cJSON_AddNumberToObject(root, "gpu_ms", round(res->gpu_ms * 1000) / 1000);
        if (a->gl) cJSON_AddStringToObject(root, "device", res->device);
        if (samples_used)
            cJSON_AddNumberToObject(root, "samples", samples_used);
        else
            cJSON_AddNullToObject(root, "samples");
        /* A stack has no analytic method: the analytic method renders stacks by their expansion. */
        cJSON_AddNumberToObject(root, "stack_slabs", a->stack_slabs);
        if (a->stack_slabs)
            cJSON_AddStringToObject(root, "stack_method", opt->method == BIREF_METHOD_ANALYTIC ||
                                                                      opt->method == BIREF_METHOD_ANALYTIC_PAIRS
                                                              ? "expansion"
                                                              : biref_method_name(opt->method));
        else
            cJSON_AddNullToObject(root, "stack_method");
        cJSON_AddStringToObject(root, "antialias", opt->antialias == BIREF_ANTIALIAS_PREFILTER ? "prefilter" : "none");
        cJSON_AddNumberToObject(root, "supersample", opt->supersample);
        cJSON_AddNumberToObject(root, "ms", round(res->ms * 1000) / 1000);
        cJSON_AddItemToObject(root, "mean_srgb", json_vec3(res->mean));
        cJSON_AddNumberToObject(root, "slab_fraction", (double)res->stats.slab_pixels / (double)res->stats.pixels);
        cJSON_AddNumberToObject(root, "fallback_evaluations", (double)res->stats.fallback_evals);
        cJSON_AddStringToObject(root, "output", a->out);
        if (a->pfm) cJSON_AddStringToObject(root, "pfm", a->pfm);
        if (a->chroma) {
            cJSON *cm = cJSON_AddObjectToObject(root, "chroma_map");
            cJSON_AddStringToObject(cm, "path", a->chroma);
            cJSON_AddNumberToObject(cm, "mean", res->chroma.mean);
            cJSON_AddNumberToObject(cm, "p99", res->chroma.p99);
            cJSON_AddNumberToObject(cm, "max", res->chroma.max);
        }
        return json_print_and_free(root) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
    }
    /* With the image on standard output ("-o -"), the summary goes to standard error. */
    FILE *info = strcmp(a->out, "-") == 0 ? stderr : stdout;
    fprintf(info, "wrote %s (%dx%d, %s%s", a->out, res->W, res->H, biref_method_name(opt->method),
            a->gl ? " on the GPU" : "");
    if (opt->method == BIREF_METHOD_NUMERIC) fprintf(info, " %d samples", samples_used);
    if (opt->antialias == BIREF_ANTIALIAS_PREFILTER) fprintf(info, ", prefiltered");
    if (opt->supersample > 1) fprintf(info, ", %dx%d samples/pixel", opt->supersample, opt->supersample);
    fprintf(info, ", %.0f ms)%s%s\n", res->ms, a->pfm ? " and " : "", a->pfm ? a->pfm : "");
    if (a->chroma)
        fprintf(info, "wrote %s (dE00 from grey: mean %.2f, 99th percentile %.2f, max %.2f)\n", a->chroma,
                res->chroma.mean, res->chroma.p99, res->chroma.max);
    return CLI_EXIT_OK;
}

int cmd_render(int argc, char **argv)
{
    render_args a;
    int r = parse(argc, argv, &a);
    if (r) return r > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    biref_scene scene;
    int rc = cli_load_scene(CMD, a.scene_path, &scene);
    if (!rc) rc = cli_scene_resize(CMD, &scene, a.width, a.height);
    if (!rc && a.gl) rc = cli_gl_refuse_stacks(CMD, a.scene_path, &scene);
    if (!rc && a.gl && cli_mpi_active())
        rc = (cli_error(CMD, "--backend gl renders in one process (no mpirun -n N)"), CLI_EXIT_USAGE);
    if (rc) return rc;
    for (int i = 0; i < scene.n_slabs; i++)
        if (scene.slabs[i].n_layers) {
            a.stack_slabs++;
            if (a.antialias == BIREF_ANTIALIAS_PREFILTER)
                return cli_error(CMD, "%s: slabs[%d] is a stack (layers), whose integration has no prefilter: "
                                      "anti-alias by --supersample",
                                 a.scene_path, i),
                       CLI_EXIT_USAGE;
        }
    /* Fail on a bad output path before rendering for seconds, not after. */
    cli_files files;
    cli_files_init(&files);
    cli_files_read(&files, "SCENE", a.scene_path);
    cli_files_write(&files, "-o", "png", a.out);
    cli_files_write(&files, "--pfm", "pfm", a.pfm);
    cli_files_write(&files, "--chroma-map", "png", a.chroma);
    /* In an MPI job rank 0 alone writes, on its own file system. */
    const int root = cli_mpi_rank() == 0;
    rc = root ? cli_files_check(CMD, &files) : 0;
    cli_files_free(&files);
    if (rc) return rc;
    render_result res = {.W = scene.camera.width, .H = scene.camera.height};
    const size_t n = (size_t)res.W * res.H;
    float *xyz = root ? malloc(n * 3 * sizeof *xyz) : NULL;
    unsigned char *rgb = root ? malloc(n * 3) : NULL;
    if (root && (!xyz || !rgb)) {
        free(xyz);
        free(rgb);
        return cli_error(CMD, "out of memory for a %dx%d image", res.W, res.H), CLI_EXIT_FAIL;
    }
    rc = render_xyz(&a, &scene, xyz, &res);
    if (!rc && root) rc = write_images(&a, xyz, rgb, &res);
    free(xyz);
    free(rgb);
    return rc || !root ? rc : print_report(&a, &res);
}
