/* biref render: a scene file to an sRGB PNG (and optionally a linear PFM). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "chroma_map.h"
#include "cli_gl.h"
#include "cli_polarizer.h"
#include "cli_render.h"
#include "commands.h"
#include "json_out.h"

static const char *const CMD = "render";

static void help(void)
{
    printf("usage: biref render SCENE.json -o OUT.png [OPTIONS]\n\n"
           "Renders a scene of thin uniaxial slabs (schema: docs/SCENES.md): per pixel the light\n"
           "transmitted from behind and reflected from the camera side, integrated over the CIE 1931\n"
           "colour-matching functions (380-700 nm), written as an 8-bit sRGB PNG.\n\n"
           "Options:\n"
           "  -o, --output FILE    output PNG (required; \"-\" = standard output). Written to a\n"
           "                       temporary file and renamed into place, or through a symlink,\n"
           "                       FIFO or device\n"
           "  --method M           analytic (default; the paper's eq. 26), numeric, ground-truth\n"
           "                       (numeric with %d samples) or expansion (exact integral of the\n"
           "                       path-group expansion; any polarizer, docs/PHYSICS.md §5)\n"
           "  --backend B          cpu (default) or gl: the analytic method as a GLSL shader through\n"
           "                       EGL and OpenGL >= 4.3 (any polarizer; docs/GPU.md)\n"
           "  --spectral-samples N spectral samples for --method numeric (default 64)\n"
           "  --order N            expansion: every pair of path groups up to order N interferes,\n"
           "                       the rest adds incoherently, 0-8 (default adaptive)\n"
           "  --tolerance E        expansion: adaptive orders' target relative error (default 1e-3;\n"
           "                       docs/PHYSICS.md section 5)\n"
           "  --antialias A        prefilter (default for analytic and expansion): each pixel averages\n"
           "                       the phase integrals over its footprint in path difference (no moire\n"
           "                       rings); none: one point look-up per sample (docs/ANTIALIASING.md)\n"
           "  --supersample K      K x K stratified jittered samples per pixel, 1-64 (default 1)\n"
           "  --width W            image width in pixels (overrides the scene)\n"
           "  --height H           image height in pixels (overrides the scene)\n"
           "  --threads T          OpenMP threads (default: all cores); the image does not depend on T\n"
           "  --pfm FILE           also write linear sRGB floats as a PFM\n"
           "  --chroma-map FILE    also write each pixel's dE00 from the grey of its lightness (how\n"
           "                       visible its colour is, from the floats) on biref diff's scale\n"
           "  --json               print {width, height, method, samples, ms, mean_srgb, ...} on stdout\n"
           "  -q, --quiet          no progress on stderr (default: a bar on a terminal, otherwise a\n"
           "                       line every few seconds once the job has run 2 s)\n"
           "  --progress           progress from the start, also when stderr is not a terminal\n"
           "  -h, --help           this help\n\n"
           "Exit status: 0 success, 1 runtime failure (e.g. unwritable output), 2 bad usage or scene.\n\n"
           "Example:\n  biref render examples/fig9a.json -o fig9a.png --method numeric --spectral-samples 128\n",
           BIREF_GROUND_TRUTH_SAMPLES);
}

enum { OPT_METHOD = 2000, OPT_SAMPLES, OPT_WIDTH, OPT_HEIGHT, OPT_THREADS, OPT_PFM, OPT_JSON, OPT_ORDER, OPT_TOLERANCE, OPT_BACKEND,
       OPT_ANTIALIAS, OPT_SUPERSAMPLE, OPT_CHROMA_MAP };

int cmd_render(int argc, char **argv)
{
    static const struct option longopts[] = {{"output", required_argument, 0, 'o'},
                                             {"method", required_argument, 0, OPT_METHOD},
                                             {"backend", required_argument, 0, OPT_BACKEND},
                                             {"spectral-samples", required_argument, 0, OPT_SAMPLES},
                                             {"samples", required_argument, 0, OPT_SAMPLES}, /* old name */
                                             {"order", required_argument, 0, OPT_ORDER},
                                             {"tolerance", required_argument, 0, OPT_TOLERANCE},
                                             {"antialias", required_argument, 0, OPT_ANTIALIAS},
                                             {"supersample", required_argument, 0, OPT_SUPERSAMPLE},
                                             {"width", required_argument, 0, OPT_WIDTH},
                                             {"height", required_argument, 0, OPT_HEIGHT},
                                             {"threads", required_argument, 0, OPT_THREADS},
                                             {"pfm", required_argument, 0, OPT_PFM},
                                             {"chroma-map", required_argument, 0, OPT_CHROMA_MAP},
                                             {"json", no_argument, 0, OPT_JSON},
                                             {"quiet", no_argument, 0, 'q'},
                                             {"help", no_argument, 0, 'h'},
                                             {0, 0, 0, 0}};
    const char *out = NULL, *pfm = NULL, *chroma = NULL;
    long width = 0, height = 0, threads = 0, samples = 0, supersample = 1;
    int json = 0, quiet = 0, have_samples = 0, have_expansion_opt = 0, gl = 0, have_method = 0, antialias = -1;
    biref_render_options opt;
    biref_render_options_default(&opt);
    opterr = 0;
    optind = 1;
    int c;
    while ((c = getopt_long(argc, argv, ":ho:q", longopts, NULL)) != -1) {
        switch (c) {
        case 'h': help(); return CLI_EXIT_OK;
        case 'o': out = optarg; break;
        case 'q': quiet = 1; break;
        case OPT_METHOD:
            if (biref_method_from_name(optarg, &opt.method) != BIREF_OK)
                return cli_error(CMD, "--method: expected analytic, numeric, ground-truth or expansion, got '%s'",
                                 optarg),
                       CLI_EXIT_USAGE;
            have_method = 1;
            break;
        case OPT_BACKEND:
            if (cli_parse_backend(CMD, optarg, &gl)) return CLI_EXIT_USAGE;
            break;
        case OPT_SAMPLES:
            if (cli_parse_int(CMD, "--spectral-samples", optarg, 1, 65536, &samples)) return CLI_EXIT_USAGE;
            have_samples = 1;
            break;
        case OPT_WIDTH:
            if (cli_parse_int(CMD, "--width", optarg, 1, BIREF_SCENE_MAX_SIDE, &width)) return CLI_EXIT_USAGE;
            break;
        case OPT_HEIGHT:
            if (cli_parse_int(CMD, "--height", optarg, 1, BIREF_SCENE_MAX_SIDE, &height)) return CLI_EXIT_USAGE;
            break;
        case OPT_THREADS:
            if (cli_parse_int(CMD, "--threads", optarg, 1, 1024, &threads)) return CLI_EXIT_USAGE;
            break;
        case OPT_ORDER:
            if (cli_parse_expansion_order(CMD, optarg, &opt.expansion)) return CLI_EXIT_USAGE;
            have_expansion_opt = 1;
            break;
        case OPT_TOLERANCE:
            if (cli_parse_expansion_tolerance(CMD, optarg, &opt.expansion)) return CLI_EXIT_USAGE;
            have_expansion_opt = 1;
            break;
        case OPT_ANTIALIAS:
            if (!strcmp(optarg, "prefilter"))
                antialias = BIREF_ANTIALIAS_PREFILTER;
            else if (!strcmp(optarg, "none"))
                antialias = BIREF_ANTIALIAS_NONE;
            else
                return cli_error(CMD, "--antialias: expected prefilter or none, got '%s'", optarg), CLI_EXIT_USAGE;
            break;
        case OPT_SUPERSAMPLE:
            if (cli_parse_int(CMD, "--supersample", optarg, 1, BIREF_MAX_SUPERSAMPLE, &supersample))
                return CLI_EXIT_USAGE;
            break;
        case OPT_PFM: pfm = optarg; break;
        case OPT_CHROMA_MAP: chroma = optarg; break;
        case OPT_JSON: json = 1; break;
        default: cli_getopt_error(CMD, c, argv); return CLI_EXIT_USAGE;
        }
    }
    if (optind >= argc) return cli_error(CMD, "missing SCENE (see biref render --help)"), CLI_EXIT_USAGE;
    if (optind + 1 < argc) return cli_error(CMD, "unexpected argument '%s'", argv[optind + 1]), CLI_EXIT_USAGE;
    const char *scene_path = argv[optind];
    if (!out) return cli_error(CMD, "missing -o OUT.png"), CLI_EXIT_USAGE;
    if (json && (strcmp(out, "-") == 0 || (pfm && strcmp(pfm, "-") == 0)))
        return cli_error(CMD, "--json and an image on standard output ('-') exclude each other"), CLI_EXIT_USAGE;
    if (have_samples && opt.method != BIREF_METHOD_NUMERIC)
        return cli_error(CMD, "--spectral-samples only applies to --method numeric"), CLI_EXIT_USAGE;
    if (have_samples) opt.samples = (int)samples;
    if (have_expansion_opt && opt.method != BIREF_METHOD_EXPANSION)
        return cli_error(CMD, "--order/--tolerance only apply to --method expansion"), CLI_EXIT_USAGE;
    opt.threads = (int)threads;
    if (gl && ((have_method && opt.method != BIREF_METHOD_ANALYTIC) || threads))
        return cli_error(CMD, "--backend gl runs the analytic method only (no --method other than analytic, no --threads)"),
               CLI_EXIT_USAGE;
    opt.supersample = (int)supersample;
    /* The prefilter needs the phase table of the analytic method and the expansion (on the CPU). */
    int table_method = !gl && (opt.method == BIREF_METHOD_ANALYTIC || opt.method == BIREF_METHOD_EXPANSION);
    if (antialias == BIREF_ANTIALIAS_PREFILTER && !table_method)
        return cli_error(CMD, "--antialias prefilter needs --method analytic or expansion on the CPU"), CLI_EXIT_USAGE;
    if (gl && supersample > 1) return cli_error(CMD, "--supersample needs the CPU back-end"), CLI_EXIT_USAGE;
    opt.antialias = antialias >= 0 ? (biref_antialias)antialias
                                   : table_method ? BIREF_ANTIALIAS_PREFILTER : BIREF_ANTIALIAS_NONE;

    biref_scene scene;
    int rc = cli_load_scene(CMD, scene_path, &scene);
    if (!rc) rc = cli_scene_resize(CMD, &scene, width, height);
    if (rc) return rc;
    /* Fail on a bad output path before rendering for seconds, not after. */
    const char *inputs[2] = {scene_path, out};
    if ((rc = cli_check_output(CMD, out, inputs, 1)) || (pfm && (rc = cli_check_output(CMD, pfm, inputs, 2))) ||
        (chroma && (rc = cli_check_output(CMD, chroma, inputs, 2))))
        return rc;
    biref_renderer *r = NULL;
    /* The GL back-end handles world-fixed polarizers too (docs/GPU.md): no CPU renderer then. */
    if (!gl && (rc = cli_renderer_create(CMD, &scene, &opt, &r))) return rc;

    const int W = scene.camera.width, H = scene.camera.height;
    const size_t n = (size_t)W * H;
    float *xyz = malloc(n * 3 * sizeof *xyz);
    unsigned char *rgb = malloc(n * 3);
    if (!xyz || !rgb) {
        free(xyz);
        free(rgb);
        biref_renderer_destroy(r);
        return cli_error(CMD, "out of memory for a %dx%d image", W, H), CLI_EXIT_FAIL;
    }
    biref_progress_bar bar;
    biref_progress_bar_init(&bar, stderr, !gl && !quiet, "render");
    biref_render_stats stats;
    double t0 = biref_wall_seconds(), gpu_ms = 0;
    char device[256] = "";
    if (gl && (rc = cli_gl_render(CMD, &scene, xyz, &stats, &gpu_ms, device, sizeof device))) {
        free(xyz);
        free(rgb);
        return rc;
    }
    biref_status rs = gl ? BIREF_OK : biref_render_image(r, xyz, biref_progress_bar_update, &bar, &stats);
    double ms = 1e3 * (biref_wall_seconds() - t0);
    biref_progress_bar_finish(&bar);
    biref_renderer_destroy(r);
    if (rs != BIREF_OK) {
        free(xyz);
        free(rgb);
        return cli_error(CMD, "%s: %s", scene_path,
                         rs == BIREF_ERR_ILLCOND ? "some pixels came out non-finite (no image written)"
                                                 : biref_status_string(rs)),
               CLI_EXIT_FAIL;
    }

    biref_xyz_image_to_srgb8(xyz, n, rgb);
    char msg[600];
    rc = CLI_EXIT_OK;
    if (biref_png_write_rgb8(out, W, H, rgb, msg, sizeof msg) != BIREF_OK) {
        cli_error(CMD, "%s", msg);
        rc = CLI_EXIT_FAIL;
    }
    cli_chroma_stats cst;
    if (!rc && chroma) rc = cli_chroma_map_write(CMD, chroma, W, H, xyz, &cst);
    if (!rc && pfm) {
        /* Reuse the XYZ buffer in place: each pixel is read before it is overwritten. */
        biref_xyz_image_to_linear_srgb(xyz, n, xyz);
        if (biref_pfm_write(pfm, W, H, xyz, msg, sizeof msg) != BIREF_OK) {
            cli_error(CMD, "%s", msg);
            rc = CLI_EXIT_FAIL;
        }
    }
    double mean[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) mean[k] += rgb[3 * i + k];
    for (int k = 0; k < 3; k++) mean[k] /= 255.0 * (double)n;
    free(xyz);
    free(rgb);
    if (rc) return rc;

    int samples_used = opt.method == BIREF_METHOD_NUMERIC        ? opt.samples
                       : opt.method == BIREF_METHOD_GROUND_TRUTH ? BIREF_GROUND_TRUTH_SAMPLES
                                                                 : 0;
    if (json) {
        cJSON *root = cJSON_CreateObject();
        cJSON_AddNumberToObject(root, "width", W);
        cJSON_AddNumberToObject(root, "height", H);
        cJSON_AddStringToObject(root, "method", biref_method_name(opt.method));
        cJSON_AddStringToObject(root, "backend", gl ? "gl" : "cpu");
        if (gl) cJSON_AddNumberToObject(root, "gpu_ms", round(gpu_ms * 1000) / 1000);
        if (gl) cJSON_AddStringToObject(root, "device", device);
        if (samples_used)
            cJSON_AddNumberToObject(root, "samples", samples_used);
        else
            cJSON_AddNullToObject(root, "samples");
        cJSON_AddStringToObject(root, "antialias", opt.antialias == BIREF_ANTIALIAS_PREFILTER ? "prefilter" : "none");
        cJSON_AddNumberToObject(root, "supersample", opt.supersample);
        cJSON_AddNumberToObject(root, "ms", round(ms * 1000) / 1000);
        cJSON_AddItemToObject(root, "mean_srgb", json_vec3(mean));
        cJSON_AddNumberToObject(root, "slab_fraction", (double)stats.slab_pixels / (double)stats.pixels);
        cJSON_AddNumberToObject(root, "fallback_evaluations", (double)stats.fallback_evals);
        cJSON_AddStringToObject(root, "output", out);
        if (pfm) cJSON_AddStringToObject(root, "pfm", pfm);
        if (chroma) {
            cJSON *cm = cJSON_AddObjectToObject(root, "chroma_map");
            cJSON_AddStringToObject(cm, "path", chroma);
            cJSON_AddNumberToObject(cm, "mean", cst.mean);
            cJSON_AddNumberToObject(cm, "p99", cst.p99);
            cJSON_AddNumberToObject(cm, "max", cst.max);
        }
        return json_print_and_free(root) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
    }
    /* With the image on standard output ("-o -"), the summary goes to standard error. */
    FILE *info = strcmp(out, "-") == 0 ? stderr : stdout;
    fprintf(info, "wrote %s (%dx%d, %s%s", out, W, H, biref_method_name(opt.method), gl ? " on the GPU" : "");
    if (opt.method == BIREF_METHOD_NUMERIC) fprintf(info, " %d samples", samples_used);
    if (opt.antialias == BIREF_ANTIALIAS_PREFILTER) fprintf(info, ", prefiltered");
    if (opt.supersample > 1) fprintf(info, ", %dx%d samples/pixel", opt.supersample, opt.supersample);
    fprintf(info, ", %.0f ms)%s%s\n", ms, pfm ? " and " : "", pfm ? pfm : "");
    if (chroma)
        fprintf(info, "wrote %s (dE00 from grey: mean %.2f, 99th percentile %.2f, max %.2f)\n", chroma, cst.mean, cst.p99,
                cst.max);
    return CLI_EXIT_OK;
}
