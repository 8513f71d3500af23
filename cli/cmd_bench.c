/* biref bench: frame time of each spectral integration method on a scene (the paper's table 1). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <omp.h>

#include "cli_data.h"
#include "cli_gl.h"
#include "cli_opts.h"
#include "cli_render.h"
#include "cli_values.h"
#include "commands.h"
#include "json_out.h"

static const char *const CMD = "bench";

#define DEFAULT_METHODS "analytic,numeric-8,numeric-32,numeric-128,numeric-512,numeric-2048,ground-truth"
#define MAX_METHODS 32

typedef struct {
    char name[32];
    biref_render_options opt;
    double ms;     /* the median of the frames timed after the first, else the first */
    double cpu_ms; /* process CPU time, all threads: stable when other jobs share the cores */
    double first_ms, first_cpu_ms; /* the first whole frame (caches cold, threads waking) */
    int frames_timed;              /* whole frames after the first (0: ms is the first frame's) */
    int rows_timed;
    int extrapolated;
} bench_method;

static int parse_methods(const char *text, bench_method *m, int *n)
{
    char buf[512];
    if (strlen(text) >= sizeof buf) return cli_error(CMD, "--methods: list too long"), -1;
    strcpy(buf, text);
    *n = 0;
    char *save = NULL;
    for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (*n == MAX_METHODS) return cli_error(CMD, "--methods: at most %d methods", MAX_METHODS), -1;
        bench_method *b = &m[(*n)++];
        memset(b, 0, sizeof *b);
        biref_render_options_default(&b->opt);
        if (!strcmp(tok, "analytic")) {
            b->opt.method = BIREF_METHOD_ANALYTIC;
        } else if (!strcmp(tok, "analytic-pairs")) {
            b->opt.method = BIREF_METHOD_ANALYTIC_PAIRS;
        } else if (!strcmp(tok, "ground-truth")) {
            b->opt.method = BIREF_METHOD_GROUND_TRUTH;
        } else if (!strcmp(tok, "expansion")) {
            b->opt.method = BIREF_METHOD_EXPANSION;
        } else if (!strncmp(tok, "numeric-", 8)) {
            long s;
            if (cli_parse_int(CMD, "--methods numeric-N", tok + 8, 1, 65536, &s)) return -1;
            b->opt.method = BIREF_METHOD_NUMERIC;
            b->opt.samples = (int)s;
        } else {
            return cli_error(CMD,
                             "--methods: unknown method '%s' (expected analytic, analytic-pairs, expansion, numeric-N or "
                             "ground-truth)",
                             tok),
                   -1;
        }
        snprintf(b->name, sizeof b->name, "%s", tok);
    }
    /* strtok_r skips empty fields; reject them explicitly ("analytic,,numeric-8"). */
    if (*n == 0 || strstr(text, ",,") || text[0] == ',' || text[strlen(text) - 1] == ',')
        return cli_error(CMD, "--methods: expected a comma-separated list, got '%s'", text), -1;
    return 0;
}

/* Renders about k evenly spaced rows (every step-th row from step / 2, so the sample sees the
 * same mix of slab and background as the frame) in one parallel call; k >= H renders the
 * frame. Returns the wall time in s and sets *rows to the number of rows rendered. */
static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double time_rows(const biref_renderer *r, int H, int k, float *xyz, int *rows, double *cpu)
{
    int step = k >= H ? 1 : H / k;
    int y0 = step / 2;
    *rows = (H - y0 + step - 1) / step;
    double c0 = cpu_seconds(), t0 = biref_wall_seconds();
    biref_renderer_render(r, y0, H, step, xyz, NULL, NULL, NULL);
    double t = biref_wall_seconds() - t0;
    *cpu = cpu_seconds() - c0;
    return t;
}

static void format_time(double ms, char *buf, size_t n)
{
    if (ms < 1000.0)
        snprintf(buf, n, "%.2f ms", ms);
    else
        snprintf(buf, n, "%.2f s", ms / 1000.0);
}

/* The command line, parsed. */
typedef struct {
    const char *scene_path, *methods;
    long width, height, threads, frames;
    double max_seconds;
    int json, gl;
    int prefilter; /* --antialias prefilter: the analytic and expansion methods prefiltered */
} bench_args;

enum { OPT_BACKEND = 1, OPT_MAX_SECONDS, OPT_ANTIALIAS };

static int handle(void *args, int code, const char *arg)
{
    bench_args *a = args;
    if (code == OPT_BACKEND) return cli_parse_backend(CMD, arg, &a->gl);
    if (code == OPT_ANTIALIAS) return cli_parse_antialias(CMD, arg, &a->prefilter);
    if (cli_parse_double(CMD, "--max-seconds", arg, &a->max_seconds)) return -1;
    if (!(a->max_seconds > 0)) return cli_error(CMD, "--max-seconds: must be positive"), -1;
    return 0;
}

#define F(field) offsetof(bench_args, field)
static const cli_opt OPTS[] = {
    CLI_STRING("scene", 0, "FILE", F(scene_path),
               "scene (default examples/fig9a.json; $BIREF_DATA_DIR or the installed copy\n"
               "when not in the current directory)"),
    CLI_INT("width", "W", F(width), 1, BIREF_SCENE_MAX_SIDE, "frame width (default 1920)"),
    CLI_INT("height", "H", F(height), 1, BIREF_SCENE_MAX_SIDE, "frame height (default 1080)"),
    CLI_STRING("methods", 0, "LIST", F(methods),
               "comma-separated: analytic, analytic-pairs, expansion, ground-truth, numeric-N\n"
               "(default " DEFAULT_METHODS ")"),
    CLI_CUSTOM("max-seconds", "S", OPT_MAX_SECONDS, "time budget per method before extrapolating (default 10)"),
    CLI_INT("threads", "T", F(threads), 1, 1024, "OpenMP threads (default: all cores)"),
    CLI_CUSTOM("antialias", "A", OPT_ANTIALIAS,
               "none (default): point look-ups; prefilter: the analytic and expansion methods\n"
               "average the phase integrals over each pixel's footprint, as render's default\n"
               "(docs/ANTIALIASING.md)"),
    CLI_CUSTOM("backend", "B", OPT_BACKEND,
               "cpu (default) or gl: also time the analytic method as a GLSL shader\n"
               "(GPU time from timer queries, median of --frames frames; docs/GPU.md)"),
    CLI_INT("frames", "N", F(frames), 0, 1000,
            "whole frames timed back to back after the first, their median reported\n"
            "(default 5; fewer when they would pass --max-seconds; 0: the first frame\n"
            "alone); gl: frames timed after one warm-up (at least 1)"),
    CLI_FLAG("json", 0, F(json),
             "{width, height, threads, antialias, methods: [{method, ms_per_frame,\n"
             "cpu_ms_per_frame, frames_timed, first_frame_ms, first_frame_cpu_ms,\n"
             "ns_per_pixel, extrapolated, rows_timed}]}"),
};
#undef F

const cli_command_spec CLI_BENCH = {
    "bench",
    "usage: biref bench [OPTIONS]\n\n"
    "Times rendering frames of a scene with each spectral integration method, like the\n"
    "paper's table 1. Set-up (look-up tables, sample plans, the frame buffer's first\n"
    "touch) is not timed. The frame time is the median of --frames frames rendered back\n"
    "to back after the first, as a renderer draws an animation; the first frame (cold\n"
    "caches, threads waking) is reported apart. A method whose frame would take longer\n"
    "than --max-seconds is\n"
    "timed on evenly spaced rows and scaled to the full frame (reported as extrapolated;\n"
    "its frame time is then the sampled CPU time scaled to the frame and divided by the\n"
    "threads, as rows parallelise perfectly).\n\n"
    "Options:\n",
    OPTS,
    CLI_OPTS_COUNT(OPTS),
    "Frame time is wall-clock time; CPU time (all threads) is also shown because it hardly\n"
    "changes when other jobs share the cores.\n",
    0,
    handle,
    1,
    NULL,
};

static double median_of(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cli_cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Up to `frames` more whole frames back to back, as a renderer draws them, within what is left of
 * the budget: b->ms and b->cpu_ms become their medians. The first whole frame stays apart (its
 * caches are cold and the threads wake from sleep: on a virtual machine whose idle vCPU the host
 * has descheduled, their start varies by milliseconds). */
static void time_more_frames(const biref_renderer *r, int H, float *xyz, long frames, double left_s, bench_method *b)
{
    double wall[1000], cpu[1000]; /* --frames is at most 1000 */
    const double t_first = b->first_ms / 1e3;
    /* The budget may already be spent (a first frame longer than --max-seconds, or the probe
     * was the whole frame): no more frames then. */
    const long n = left_s > 0 ? (long)fmin(floor(left_s / fmax(t_first, 1e-9)), (double)frames) : 0;
    int rows = 0;
    for (long i = 0; i < n; i++) wall[i] = 1e3 * time_rows(r, H, H, xyz, &rows, &cpu[i]), cpu[i] *= 1e3;
    b->frames_timed = (int)n;
    if (n == 0) return;
    b->ms = median_of(wall, (int)n);
    b->cpu_ms = median_of(cpu, (int)n);
}

/* Times each method on the scene with n_threads threads. Returns a CLI exit code. */
static int time_methods(const biref_scene *scene, bench_method *m, int n_methods, int n_threads, double max_seconds,
                        long frames)
{
    const int W = scene->camera.width, H = scene->camera.height;
    float *xyz = malloc((size_t)W * H * 3 * sizeof *xyz);
    if (!xyz) return cli_error(CMD, "out of memory for a %dx%d frame", W, H), CLI_EXIT_FAIL;
    /* Set-up: the buffer's pages are touched before any frame is timed, as a renderer's buffer is
     * from its second frame on (their first touch, page faults and zeroing by the kernel, cost ~4 %
     * of the analytic 1080p frame's CPU time). */
    memset(xyz, 0, (size_t)W * H * 3 * sizeof *xyz);
    int rc = CLI_EXIT_OK;
    biref_progress_bar bar;
    biref_progress_bar_init(&bar, stderr, 1, "bench");
    for (int i = 0; i < n_methods && !rc; i++) {
        bench_method *b = &m[i];
        b->opt.threads = n_threads;
        biref_renderer *r = NULL;
        if ((rc = cli_renderer_create(CMD, scene, &b->opt, &r))) break;
        biref_progress_bar_note(&bar, b->name);
        biref_progress_bar_update(&bar, i, n_methods);
        /* Probe one row per thread, then spend the budget on as many evenly spaced rows as fit
         * (the whole frame if it fits). */
        int rows = 0, k = n_threads < H ? n_threads : H;
        double cpu = 0;
        const double t_start = biref_wall_seconds();
        double t = time_rows(r, H, k, xyz, &rows, &cpu);
        int want = (int)fmin((double)H, floor(max_seconds * rows / fmax(t, 1e-9)));
        /* A partial sample is a whole number of rows per thread, so no thread idles at the end
         * (3 slow rows on 2 threads would time as 2 rows). */
        if (want < H) want = want / k * k;
        if (want > rows) t = time_rows(r, H, want, xyz, &rows, &cpu);
        b->rows_timed = rows;
        b->extrapolated = rows < H;
        b->cpu_ms = 1e3 * cpu * H / rows;
        /* A handful of sampled rows on a few threads measures load imbalance, not the frame
         * (whose many rows are balanced dynamically: full frames measure a CPU/wall ratio of
         * ~1.98 on 2 threads). So an extrapolated frame time is the sampled CPU time scaled to
         * the frame and shared by the threads that have a core. */
        int cores = omp_get_num_procs();
        b->ms = b->extrapolated ? b->cpu_ms / (n_threads < cores ? n_threads : cores) : 1e3 * t * H / rows;
        b->first_ms = b->ms;
        b->first_cpu_ms = b->cpu_ms;
        b->frames_timed = 0;
        if (!b->extrapolated)
            time_more_frames(r, H, xyz, frames, max_seconds - (biref_wall_seconds() - t_start), b);
        biref_renderer_destroy(r);
    }
    if (!rc) biref_progress_bar_update(&bar, n_methods, n_methods);
    biref_progress_bar_finish(&bar);
    free(xyz);
    return rc;
}

/* The GL back-end's timing (--backend gl). */
typedef struct {
    double gpu_ms, wall_ms;
    char device[256];
} bench_gl;

static int print_json(const bench_args *a, int W, int H, int n_threads, const bench_method *m, int n_methods,
                      const bench_gl *g)
{
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "scene", a->scene_path);
    cJSON_AddNumberToObject(root, "width", W);
    cJSON_AddNumberToObject(root, "height", H);
    cJSON_AddNumberToObject(root, "threads", n_threads);
    cJSON_AddStringToObject(root, "antialias", a->prefilter ? "prefilter" : "none");
    cJSON *arr = cJSON_AddArrayToObject(root, "methods");
    for (int i = 0; i < n_methods; i++) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "method", m[i].name);
        cJSON_AddNumberToObject(o, "ms_per_frame", round(m[i].ms * 1000) / 1000);
        cJSON_AddNumberToObject(o, "cpu_ms_per_frame", round(m[i].cpu_ms * 1000) / 1000);
        cJSON_AddNumberToObject(o, "frames_timed", m[i].frames_timed);
        cJSON_AddNumberToObject(o, "first_frame_ms", round(m[i].first_ms * 1000) / 1000);
        cJSON_AddNumberToObject(o, "first_frame_cpu_ms", round(m[i].first_cpu_ms * 1000) / 1000);
        cJSON_AddNumberToObject(o, "ns_per_pixel", round(m[i].ms * 1e6 / ((double)W * H) * 10) / 10);
        cJSON_AddBoolToObject(o, "extrapolated", m[i].extrapolated);
        cJSON_AddNumberToObject(o, "rows_timed", m[i].rows_timed);
        cJSON_AddStringToObject(o, "backend", "cpu");
        cJSON_AddItemToArray(arr, o);
    }
    if (a->gl) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "method", "analytic");
        cJSON_AddStringToObject(o, "backend", "gl");
        cJSON_AddNumberToObject(o, "ms_per_frame", round(g->gpu_ms * 1000) / 1000);
        cJSON_AddNumberToObject(o, "gpu_ms_per_frame", round(g->gpu_ms * 1000) / 1000);
        cJSON_AddNumberToObject(o, "wall_ms_per_frame", round(g->wall_ms * 1000) / 1000);
        cJSON_AddNumberToObject(o, "ns_per_pixel", round(g->gpu_ms * 1e6 / ((double)W * H) * 10) / 10);
        cJSON_AddNumberToObject(o, "frames", (double)a->frames);
        cJSON_AddStringToObject(o, "device", g->device);
        cJSON_AddItemToArray(arr, o);
    }
    return json_print_and_free(root) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

static void print_table(const bench_args *a, int W, int H, int n_threads, const bench_method *m, int n_methods,
                        const bench_gl *g)
{
    printf("Scene %s, %dx%d, %d thread%s\n\n", a->scene_path, W, H, n_threads, n_threads == 1 ? "" : "s");
    printf("%-34s %14s %12s %14s %14s\n", "Spectral integration method", "Frame time", "ns/pixel", "CPU time",
           "First frame");
    /* Grouped as in table 1: analytic first, then numeric by sample count, then ground truth;
     * analytic-pairs and the path-group expansion (beyond the paper) last. */
    int beyond = 0;
    for (int pass = 0; pass < 5; pass++) {
        static const biref_method order[5] = {BIREF_METHOD_ANALYTIC, BIREF_METHOD_NUMERIC, BIREF_METHOD_GROUND_TRUTH,
                                              BIREF_METHOD_ANALYTIC_PAIRS, BIREF_METHOD_EXPANSION};
        const biref_method want = order[pass];
        int header = 0;
        for (int i = 0; i < n_methods; i++) {
            if (m[i].opt.method != want) continue;
            if (!header && pass && !(pass >= 3 && beyond))
                printf("%s\n", pass == 1 ? "Numeric integration" : pass == 2 ? "Ground truth" : "Beyond the paper");
            header = 1;
            beyond |= pass >= 3;
            char label[48], tm[32], cpu[32], first[32] = "-";
            if (want == BIREF_METHOD_ANALYTIC)
                snprintf(label, sizeof label, "Analytic approximation");
            else if (want == BIREF_METHOD_ANALYTIC_PAIRS)
                snprintf(label, sizeof label, "  analytic + sibling pairs");
            else if (want == BIREF_METHOD_EXPANSION)
                snprintf(label, sizeof label, "  path-group expansion");
            else
                snprintf(label, sizeof label, "  %d spectral samples",
                         want == BIREF_METHOD_NUMERIC ? m[i].opt.samples : BIREF_GROUND_TRUTH_SAMPLES);
            format_time(m[i].ms, tm, sizeof tm);
            format_time(m[i].cpu_ms, cpu, sizeof cpu);
            if (m[i].frames_timed) format_time(m[i].first_ms, first, sizeof first);
            printf("%-34s %14s %12.0f %14s %14s", label, tm, m[i].ms * 1e6 / ((double)W * H), cpu, first);
            if (m[i].extrapolated) printf("   (extrapolated from %d rows)", m[i].rows_timed);
            else if (m[i].frames_timed) printf("   (median of %d frames after the first)", m[i].frames_timed);
            printf("\n");
        }
    }
    if (a->gl) {
        char tm[32], wall[32];
        format_time(g->gpu_ms, tm, sizeof tm);
        format_time(g->wall_ms, wall, sizeof wall);
        printf("GPU (OpenGL: %s)\n%-34s %14s %12.1f %14s\n", g->device, "  analytic, GPU time", tm,
               g->gpu_ms * 1e6 / ((double)W * H), "-");
        printf("%-34s %14s   (median of %ld frames, draw to read-back)\n", "  analytic, wall time", wall, a->frames);
    }
}

int cmd_bench(int argc, char **argv)
{
    bench_args a = {NULL, DEFAULT_METHODS, 1920, 1080, 0, 5, 10.0, 0, 0, 0};
    cli_parsed p;
    int r = cli_opts_parse(&CLI_BENCH, &a, argc, argv, &p);
    if (r) return r > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    if (p.n_args) return cli_error(CMD, "unexpected argument '%s'", argv[p.first_arg]), CLI_EXIT_USAGE;
    bench_method m[MAX_METHODS];
    int n_methods = 0;
    if (parse_methods(a.methods, m, &n_methods)) return CLI_EXIT_USAGE;
    for (int i = 0; i < n_methods; i++)
        if (a.prefilter && (m[i].opt.method == BIREF_METHOD_ANALYTIC || m[i].opt.method == BIREF_METHOD_ANALYTIC_PAIRS ||
                            m[i].opt.method == BIREF_METHOD_EXPANSION))
            m[i].opt.antialias = BIREF_ANTIALIAS_PREFILTER;
    biref_scene scene;
    char default_scene[4096];
    if (!a.scene_path) a.scene_path = cli_data_path("examples/fig9a.json", default_scene, sizeof default_scene);
    int rc = cli_load_scene(CMD, a.scene_path, &scene);
    if (!rc) rc = cli_scene_resize(CMD, &scene, a.width, a.height);
    if (rc) return rc;
    const int W = scene.camera.width, H = scene.camera.height;
    const int n_threads = a.threads > 0 ? (int)a.threads : omp_get_max_threads();
    if (a.gl && a.frames < 1) return cli_error(CMD, "--frames: the gl backend times at least 1 frame"), CLI_EXIT_USAGE;
    if ((rc = time_methods(&scene, m, n_methods, n_threads, a.max_seconds, a.frames)))
        return rc;
    bench_gl g = {0, 0, ""};
    if (a.gl && (rc = cli_gl_bench(CMD, &scene, (int)a.frames, &g.gpu_ms, &g.wall_ms, g.device, sizeof g.device)))
        return rc;
    if (a.json) return print_json(&a, W, H, n_threads, m, n_methods, &g);
    print_table(&a, W, H, n_threads, m, n_methods, &g);
    return CLI_EXIT_OK;
}
