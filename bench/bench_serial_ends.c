/* The serial ends of `biref render`: the work per process before and after the frame.
 *
 *   bench_serial_ends [--scene FILE] [--width W] [--height H] [--threads T] [--runs N] [--json]
 *
 * Times, each the median of N runs (default 5) in wall and process CPU milliseconds:
 *   table      biref_spectral_create (the phase look-up table: once per process, borrowed by
 *              every renderer)
 *   prefilter  the renderer's set-up with the prefilter (the default of `biref render`) minus
 *              the one without: the prefiltered phase table
 *   srgb8      biref_xyz_image_to_srgb8 of the rendered frame
 *   png        biref_png_write_rgb8 of it (to a temporary file; the file size is printed)
 * The frame (default examples/fig9a.json at 1920 x 1080) is rendered once, untimed, so that the
 * encoders see a real picture. Wall times on a shared machine are noisy: compare runs made
 * together, or count instructions (valgrind --tool=callgrind, see docs/PERFORMANCE.md). */
#define _POSIX_C_SOURCE 200809L /* mkstemp, clock_gettime */
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "biref/biref.h"

static double clock_ms(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return 1e3 * (double)ts.tv_sec + 1e-6 * (double)ts.tv_nsec;
}

typedef struct {
    const biref_spectral *sp; /* the process's context, which renderers borrow */
    const biref_scene *scene;
    const float *xyz;
    unsigned char *rgb;
    const char *png_path;
    int width, height, threads;
} ends;

/* One run of a step: 0 table, 1 renderer without prefilter, 2 with, 3 srgb8, 4 png. */
static int run_step(const ends *e, int step)
{
    char msg[512];
    if (step == 0) {
        biref_spectral *sp = NULL;
        biref_status s = biref_spectral_create(NULL, &sp, NULL, 0);
        biref_spectral_destroy(sp);
        return s == BIREF_OK;
    }
    if (step <= 2) {
        biref_render_options opt;
        biref_render_options_default(&opt);
        opt.threads = e->threads;
        opt.antialias = step == 2 ? BIREF_ANTIALIAS_PREFILTER : BIREF_ANTIALIAS_NONE;
        biref_renderer *r = NULL;
        biref_status s = biref_renderer_create(e->sp, e->scene, &opt, &r, msg, sizeof msg);
        biref_renderer_destroy(r);
        return s == BIREF_OK;
    }
    if (step == 3) {
        biref_xyz_image_to_srgb8(e->xyz, (size_t)e->width * e->height, e->rgb);
        return 1;
    }
    return biref_png_write_rgb8(e->png_path, e->width, e->height, e->rgb, msg, sizeof msg) == BIREF_OK;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median wall and CPU milliseconds of `runs` runs of a step. */
static int time_step(const ends *e, int step, int runs, double *wall, double *cpu)
{
    double w[64], c[64];
    for (int i = 0; i < runs; i++) {
        double w0 = clock_ms(CLOCK_MONOTONIC), c0 = clock_ms(CLOCK_PROCESS_CPUTIME_ID);
        if (!run_step(e, step)) return 0;
        w[i] = clock_ms(CLOCK_MONOTONIC) - w0;
        c[i] = clock_ms(CLOCK_PROCESS_CPUTIME_ID) - c0;
    }
    qsort(w, (size_t)runs, sizeof *w, cmp_double);
    qsort(c, (size_t)runs, sizeof *c, cmp_double);
    *wall = w[runs / 2];
    *cpu = c[runs / 2];
    return 1;
}

int main(int argc, char **argv)
{
    const char *scene_path = "examples/fig9a.json";
    int width = 1920, height = 1080, threads = 2, runs = 5, json = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--json")) json = 1;
        else if (v && !strcmp(a, "--scene")) scene_path = argv[++i];
        else if (v && !strcmp(a, "--width")) width = atoi(argv[++i]);
        else if (v && !strcmp(a, "--height")) height = atoi(argv[++i]);
        else if (v && !strcmp(a, "--threads")) threads = atoi(argv[++i]);
        else if (v && !strcmp(a, "--runs")) runs = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_serial_ends [--scene FILE] [--width W] [--height H] [--threads T] "
                            "[--runs N] [--json]\n");
            return strcmp(a, "-h") && strcmp(a, "--help") ? 2 : 0;
        }
    }
    if (width < 1 || height < 1 || threads < 1 || runs < 1 || runs > 64) {
        fprintf(stderr, "bench_serial_ends: width, height, threads >= 1 and 1 <= runs <= 64\n");
        return 2;
    }
    omp_set_num_threads(threads);
    char msg[512];
    biref_scene scene;
    if (biref_scene_load(scene_path, &scene, msg, sizeof msg) != BIREF_OK) {
        fprintf(stderr, "bench_serial_ends: %s\n", msg);
        return 1;
    }
    scene.camera.width = width;
    scene.camera.height = height;
    const size_t n = (size_t)width * height;
    float *xyz = malloc(n * 3 * sizeof *xyz);
    unsigned char *rgb = malloc(n * 3);
    char png_path[] = "/tmp/bench_serial_ends.XXXXXX";
    int fd = mkstemp(png_path);
    if (!xyz || !rgb || fd < 0) {
        fprintf(stderr, "bench_serial_ends: out of memory or no temporary file\n");
        return 1;
    }
    close(fd);
    biref_render_options opt;
    biref_render_options_default(&opt);
    opt.threads = threads;
    opt.antialias = BIREF_ANTIALIAS_PREFILTER;
    biref_renderer *r = NULL;
    biref_spectral *sp = NULL;
    if (biref_spectral_create(NULL, &sp, msg, sizeof msg) != BIREF_OK ||
        biref_renderer_create(sp, &scene, &opt, &r, msg, sizeof msg) != BIREF_OK ||
        biref_render_image(r, xyz, NULL, NULL, NULL) != BIREF_OK) {
        fprintf(stderr, "bench_serial_ends: cannot render %s: %s\n", scene_path, msg);
        return 1;
    }
    biref_renderer_destroy(r);

    const ends e = {sp, &scene, xyz, rgb, png_path, width, height, threads};
    static const char *const NAMES[] = {"table", "renderer", "renderer+prefilter", "srgb8", "png"};
    double wall[5], cpu[5];
    for (int s = 0; s < 5; s++)
        if (!time_step(&e, s, runs, &wall[s], &cpu[s])) {
            fprintf(stderr, "bench_serial_ends: step %s failed\n", NAMES[s]);
            unlink(png_path);
            return 1;
        }
    struct stat st;
    long png_bytes = stat(png_path, &st) == 0 ? (long)st.st_size : -1;
    unlink(png_path);
    const double pf_wall = wall[2] - wall[1], pf_cpu = cpu[2] - cpu[1];
    const double total_wall = wall[0] + wall[2] + wall[3] + wall[4], total_cpu = cpu[0] + cpu[2] + cpu[3] + cpu[4];
    if (json) {
        printf("{\"scene\":\"%s\",\"width\":%d,\"height\":%d,\"threads\":%d,\"runs\":%d,"
               "\"table_ms\":[%.2f,%.2f],\"prefilter_ms\":[%.2f,%.2f],\"srgb8_ms\":[%.2f,%.2f],"
               "\"png_ms\":[%.2f,%.2f],\"png_bytes\":%ld,\"total_ms\":[%.2f,%.2f]}\n",
               scene_path, width, height, threads, runs, wall[0], cpu[0], pf_wall, pf_cpu, wall[3], cpu[3], wall[4],
               cpu[4], png_bytes, total_wall, total_cpu);
    } else {
        printf("serial ends of biref render, %s at %d x %d, %d threads, median of %d runs (wall / CPU ms)\n",
               scene_path, width, height, threads, runs);
        printf("  look-up table (biref_spectral_create)  %8.1f / %8.1f\n", wall[0], cpu[0]);
        printf("  prefilter table                        %8.1f / %8.1f\n", pf_wall, pf_cpu);
        printf("  renderer set-up with prefilter         %8.1f / %8.1f\n", wall[2], cpu[2]);
        printf("  sRGB encoding                          %8.1f / %8.1f\n", wall[3], cpu[3]);
        printf("  PNG writing (%ld bytes)            %8.1f / %8.1f\n", png_bytes, wall[4], cpu[4]);
        printf("  total outside the frame                %8.1f / %8.1f\n", total_wall, total_cpu);
    }
    free(xyz);
    free(rgb);
    biref_spectral_destroy(sp);
    return 0;
}
