/* biref figure: regenerates the paper's figures 5, 6c, 7, 9 and table 1 as PNG plots (PLplot,
 * cairo for the image grids) with the underlying numbers as CSV next to each plot.
 * What each figure shows and how it compares with the paper: docs/REPRODUCTION.md. */
#include <cairo.h>
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "biref/render.h"
#include "cli_common.h"
#include "cli_data.h"
#include "cli_files.h"
#include "cli_mpi.h"
#include "cli_mpi_render.h"
#include "commands.h"
#include "de_scale.h"
#include "fig_aliasing.h"
#include "fig_common.h"
#include "fig_stacks.h"
#include "fig_plot.h"
#include "outfile.h"



/* ------------------------------------------------------------------------ */
/* Small utilities                                                           */
/* ------------------------------------------------------------------------ */

typedef struct {
    const char *name;
    biref_method method;
    int samples;
} method_spec;

/* The paper's methods, and analytic-pairs (eq. 26 plus transmission's sibling and entry pairs,
 * beyond the paper) beside its analytic method. */
static const method_spec FIG9_METHODS[] = {
    {"analytic", BIREF_METHOD_ANALYTIC, 0},      {"analytic-pairs", BIREF_METHOD_ANALYTIC_PAIRS, 0},
    {"numeric 3", BIREF_METHOD_NUMERIC, 3},      {"numeric 8", BIREF_METHOD_NUMERIC, 8},
    {"numeric 32", BIREF_METHOD_NUMERIC, 32},    {"numeric 128", BIREF_METHOD_NUMERIC, 128},
    {"ground truth", BIREF_METHOD_GROUND_TRUTH, 0},
};
enum { FIG9_NMETHODS = 7, FIG9_GT = 6 };

static int load_scene(const fig_ctx *c, const char *scenes, const char *name, int w, int h, biref_scene *sc)
{
    char path[4096], msg[256];
    snprintf(path, sizeof path, "%s/%s.json", scenes, name);
    if (biref_scene_load(path, sc, msg, sizeof msg) != BIREF_OK)
        return cli_error(FIG_CMD, "%s: %s", path, msg), -1;
    sc->camera.width = w;
    sc->camera.height = h;
    if (biref_scene_validate(sc, msg, sizeof msg) != BIREF_OK) return cli_error(FIG_CMD, "%s: %s", path, msg), -1;
    return 0;
}

/* Renders rows y0, y0 + step, ... (all rows: step 1) and returns the wall time, or -1. */
static double render_rows(const fig_ctx *c, const biref_scene *sc, const method_spec *ms, int y0, int step,
                          float *xyz, const char *label)
{
    biref_render_options opt;
    biref_render_options_default(&opt);
    opt.method = ms->method;
    if (ms->samples) opt.samples = ms->samples;
    opt.threads = c->threads;
    biref_renderer *r = NULL;
    char msg[256];
    if (biref_renderer_create(c->sp, sc, &opt, &r, msg, sizeof msg) != BIREF_OK)
        return cli_error(FIG_CMD, "%s: %s", ms->name, msg), -1.0;
    biref_progress_bar bar;
    char what[48];
    snprintf(what, sizeof what, "figure %s", label);
    biref_progress_bar_init(&bar, stderr, 1, what);
    double t0 = biref_wall_seconds();
    /* A whole frame in an MPI job: every process renders tiles of it (rank 0 gets the image). */
    biref_status s = cli_mpi_active() && y0 == 0 && step == 1
                         ? cli_mpi_render(r, xyz, biref_progress_bar_update, &bar, NULL)
                         : biref_renderer_render(r, y0, sc->camera.height, step, xyz, biref_progress_bar_update, &bar, NULL);
    double t = biref_wall_seconds() - t0;
    biref_progress_bar_finish(&bar);
    biref_renderer_destroy(r);
    if (s != BIREF_OK) return cli_error(FIG_CMD, "%s: render failed: %s", ms->name, biref_status_string(s)), -1.0;
    return t;
}

static int fig9_scene(const fig_ctx *c, const char *scenes, const char *name, FILE *csv)
{
    const int w = c->quick ? 64 : 240, h = c->quick ? 36 : 135;
    biref_scene sc;
    if (load_scene(c, scenes, name, w, h, &sc)) return CLI_EXIT_USAGE;
    size_t npx = (size_t)w * h;
    float *xyz = malloc(sizeof(float) * npx * 3 * FIG9_NMETHODS);
    unsigned char *rgb = malloc(npx * 3 * (FIG9_NMETHODS * 2));
    double *de = malloc(sizeof(double) * npx * FIG9_NMETHODS), *sorted = malloc(sizeof(double) * npx);
    if (!xyz || !rgb || !de || !sorted)
        return free(xyz), free(rgb), free(de), free(sorted), cli_error(FIG_CMD, "out of memory"), CLI_EXIT_FAIL;
    double secs[FIG9_NMETHODS];
    for (int m = 0; m < FIG9_NMETHODS; m++) {
        char label[32];
        snprintf(label, sizeof label, "%s %s", name, FIG9_METHODS[m].name);
        fprintf(stderr, "biref figure: fig9: %s, %s (%dx%d)\n", name, FIG9_METHODS[m].name, w, h);
        secs[m] = render_rows(c, &sc, &FIG9_METHODS[m], 0, 1, xyz + (size_t)m * npx * 3, label);
        if (secs[m] < 0) return free(xyz), free(rgb), free(de), free(sorted), CLI_EXIT_FAIL;
        biref_xyz_image_to_srgb8(xyz + (size_t)m * npx * 3, npx, rgb + (size_t)m * npx * 3);
    }
    /* The other processes of an MPI job have rendered their tiles; rank 0 has the images. */
    if (cli_mpi_rank() > 0) return free(xyz), free(rgb), free(de), free(sorted), CLI_EXIT_OK;
    const float *gt = xyz + (size_t)FIG9_GT * npx * 3;
    for (int m = 0; m < FIG9_NMETHODS; m++) {
        const float *im = xyz + (size_t)m * npx * 3;
        double sum = 0, mx = 0;
        long above1 = 0;
        unsigned char *map = rgb + (size_t)(FIG9_NMETHODS + m) * npx * 3;
        for (size_t i = 0; i < npx; i++) {
            const double a[3] = {im[3 * i], im[3 * i + 1], im[3 * i + 2]}, g[3] = {gt[3 * i], gt[3 * i + 1], gt[3 * i + 2]};
            double e = biref_delta_e00_xyz(a, g);
            de[(size_t)m * npx + i] = e;
            sorted[i] = e;
            sum += e;
            mx = fmax(mx, e);
            above1 += e > 1.0;
            cli_de_color(e, map + 3 * i);
        }
        qsort(sorted, npx, sizeof(double), cli_cmp_double);
        double p95 = sorted[(size_t)floor(0.95 * (double)(npx - 1))];
        fprintf(csv, "%s,%s,%d,%d,%.4f,%.4f,%.4f,%.4f,%.3f\n", name, FIG9_METHODS[m].name, w, h, sum / (double)npx, p95,
                mx, (double)above1 / (double)npx, secs[m]);
    }

    /* Grid: one column per method; renders on top, ΔE00 maps below; a colour bar at the bottom. */
    double scale = w >= 240 ? 1.0 : floor(240.0 / w);
    int tw = (int)(w * scale), thh = (int)(h * scale), gap = 8, head = 22, bar = 46;
    int W = FIG9_NMETHODS * (tw + gap) + gap, H = head + 2 * (thh + gap) + head + bar;
    cairo_surface_t *out = cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, H);
    cairo_t *cr = cairo_create(out);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 13);
    for (int m = 0; m < FIG9_NMETHODS; m++) {
        double x = gap + m * (tw + gap);
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_move_to(cr, x, head - 6);
        cairo_show_text(cr, FIG9_METHODS[m].name);
        fig_draw_rgb_tile(cr, rgb + (size_t)m * npx * 3, w, h, x, head, scale);
        if (m == FIG9_GT) continue; /* its map against itself is empty */
        fig_draw_rgb_tile(cr, rgb + (size_t)(FIG9_NMETHODS + m) * npx * 3, w, h, x, head + thh + gap, scale);
    }
    double by = head + 2 * (thh + gap) + 6;
    cli_de_legend(cr, gap, by, 640, "ΔE00 vs ground truth (second row; the scale of biref diff):");
    char path[4096], file[64];
    snprintf(file, sizeof file, "fig9_%s.png", name + strlen(name) - 1);
    fig_out_path(c, file, path, sizeof path);
    cairo_surface_flush(out);
    biref_outfile *png = fig_open_out(path);
    cairo_status_t cs = png ? cairo_surface_write_to_png_stream(out, fig_write_stream, biref_outfile_stream(png))
                            : CAIRO_STATUS_WRITE_ERROR;
    cairo_destroy(cr);
    cairo_surface_destroy(out);
    free(xyz), free(rgb), free(de), free(sorted);
    if (!png) return CLI_EXIT_FAIL;
    if (cs != CAIRO_STATUS_SUCCESS) {
        fig_discard(png);
        return cli_error(FIG_CMD, "cannot write %s: %s", path, cairo_status_to_string(cs)), CLI_EXIT_FAIL;
    }
    return fig_close_csv(png, path) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

/* The other processes of an MPI job: the same renders as rank 0's fig9, in the same order. */
static int fig9_share(const fig_ctx *c, const char *scenes)
{
    static const char *const names[3] = {"fig9a", "fig9b", "fig9c"};
    for (int i = 0; i < 3; i++) {
        char sp[4096];
        snprintf(sp, sizeof sp, "%s/%s.json", scenes, names[i]);
        int rc = access(sp, R_OK) == 0 ? fig9_scene(c, scenes, names[i], NULL) : CLI_EXIT_OK;
        if (rc) return rc;
    }
    return CLI_EXIT_OK;
}

static int fig9(const fig_ctx *c, const char *scenes)
{
    if (cli_mpi_rank() > 0) return fig9_share(c, scenes);
    char path[4096];
    biref_outfile *out = fig_open_csv(c, "fig9.csv", path, sizeof path);
    if (!out) return CLI_EXIT_FAIL;
    FILE *f = biref_outfile_stream(out);
    fprintf(f, "scene,method,width,height,dE00_mean,dE00_p95,dE00_max,fraction_dE00_gt_1,render_seconds\n");
    static const char *const names[3] = {"fig9a", "fig9b", "fig9c"};
    int done = 0;
    for (int i = 0; i < 3; i++) {
        /* The scene files come with the renderer; a missing one is skipped (and said so) so
         * that the others still regenerate. */
        char sp[4096];
        snprintf(sp, sizeof sp, "%s/%s.json", scenes, names[i]);
        if (access(sp, R_OK) != 0) {
            fprintf(stderr, "biref figure: fig9: %s not found, skipped\n", sp);
            continue;
        }
        int rc = fig9_scene(c, scenes, names[i], f);
        if (rc) return fig_discard(out), rc;
        done++;
    }
    if (!done) return fig_discard(out), cli_error(FIG_CMD, "fig9: no scene found in %s (fig9a/b/c.json)", scenes), CLI_EXIT_USAGE;
    return fig_close_csv(out, path) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

/* ------------------------------------------------------------------------ */
/* Table 1: frame times at 1920x1080                                         */
/* ------------------------------------------------------------------------ */

static int table1(const fig_ctx *c, const char *scenes)
{
    static const method_spec methods[] = {
        {"analytic", BIREF_METHOD_ANALYTIC, 0},        {"analytic-pairs", BIREF_METHOD_ANALYTIC_PAIRS, 0},
        {"numeric 3", BIREF_METHOD_NUMERIC, 3},        {"numeric 8", BIREF_METHOD_NUMERIC, 8},
        {"numeric 32", BIREF_METHOD_NUMERIC, 32},      {"numeric 128", BIREF_METHOD_NUMERIC, 128},
        {"numeric 512", BIREF_METHOD_NUMERIC, 512},    {"numeric 2048", BIREF_METHOD_NUMERIC, 2048},
        {"ground truth", BIREF_METHOD_GROUND_TRUTH, 0},
    };
    /* The paper's frame times (table 1, mobile GeForce 1070), in seconds; analytic-pairs is not the
     * paper's (NaN: none). */
    static const double paper[] = {1.09e-3, NAN, 1.30e-3, 1.73e-3, 3.84e-3, 12.2e-3, 45.5e-3, 0.20, 2.00};
    enum { NMETH = 9 };
    const int W = 1920, H = 1080;
    /* Seconds of measurement per method: a full frame when it fits, else every k-th row, whose
     * time scales to the frame because rows are spread evenly over the image. */
    const double budget = c->quick ? 1.0 : 20.0;
    biref_scene sc;
    if (load_scene(c, scenes, "fig9a", W, H, &sc)) return CLI_EXIT_USAGE;
    float *xyz = malloc(sizeof(float) * (size_t)W * H * 3);
    if (!xyz) return cli_error(FIG_CMD, "out of memory"), CLI_EXIT_FAIL;
    char path[4096], mdpath[4096];
    biref_outfile *out = fig_open_csv(c, "table1.csv", path, sizeof path);
    if (!out) return free(xyz), CLI_EXIT_FAIL;
    FILE *f = biref_outfile_stream(out);
    fig_out_path(c, "table1.md", mdpath, sizeof mdpath);
    biref_outfile *mdout = fig_open_out(mdpath);
    if (!mdout) return fig_discard(out), free(xyz), CLI_EXIT_FAIL;
    FILE *md = biref_outfile_stream(mdout);
    int threads = c->threads > 0 ? c->threads : omp_get_max_threads();
    fprintf(f, "method,samples,rows_rendered,rows_total,measured_seconds,frame_seconds,extrapolated,threads,"
               "paper_frame_seconds\n");
    fprintf(md, "| method | frame time (this machine, %d threads) | rows rendered | paper (GeForce 1070) |\n"
                "|---|---|---|---|\n", threads);
    for (int m = 0; m < NMETH; m++) {
        /* Pilot: a few rows spread over the frame (quick: the middle row alone, which crosses
         * the slab) estimate the cost per row; ground truth costs seconds per row. */
        int step = c->quick ? H : H / 4, y0 = c->quick ? H / 2 : step / 2;
        char label[32];
        snprintf(label, sizeof label, "table1 %s", methods[m].name);
        fprintf(stderr, "biref figure: table1: %s\n", methods[m].name);
        double t = render_rows(c, &sc, &methods[m], y0, step, xyz, label);
        if (t < 0) return fig_discard(out), fig_discard(mdout), free(xyz), CLI_EXIT_FAIL;
        int rows = (H - y0 + step - 1) / step;
        double per_row = t / rows;
        if (per_row * H <= budget) {
            t = render_rows(c, &sc, &methods[m], 0, 1, xyz, label);
            if (t < 0) return fig_discard(out), fig_discard(mdout), free(xyz), CLI_EXIT_FAIL;
            rows = H;
        } else if ((int)(budget / per_row) > rows) {
            step = H / (int)(budget / per_row);
            y0 = step / 2;
            t = render_rows(c, &sc, &methods[m], y0, step, xyz, label);
            if (t < 0) return fig_discard(out), fig_discard(mdout), free(xyz), CLI_EXIT_FAIL;
            rows = (H - y0 + step - 1) / step;
        }
        double frame = t * H / rows;
        int extrap = rows < H;
        char theirs[32] = "–", paper_csv[32] = "";
        if (!isnan(paper[m])) {
            snprintf(theirs, sizeof theirs, paper[m] < 0.1 ? "%.2f ms" : "%.2f s", paper[m] < 0.1 ? paper[m] * 1e3 : paper[m]);
            snprintf(paper_csv, sizeof paper_csv, "%g", paper[m]);
        }
        fprintf(f, "%s,%d,%d,%d,%.4f,%.4f,%d,%d,%s\n", methods[m].name,
                methods[m].method == BIREF_METHOD_GROUND_TRUTH ? BIREF_GROUND_TRUTH_SAMPLES : methods[m].samples, rows,
                H, t, frame, extrap, threads, paper_csv);
        char ours[64];
        snprintf(ours, sizeof ours, frame < 1 ? "%.0f ms%s" : "%.1f s%s", frame < 1 ? frame * 1e3 : frame,
                 extrap ? " (extrapolated)" : "");
        fprintf(md, "| %s | %s | %d / %d | %s |\n", methods[m].name, ours, rows, H, theirs);
        fprintf(stderr, "biref figure: table1: %s: %.3f s per frame%s\n", methods[m].name, frame,
                extrap ? " (extrapolated)" : "");
    }
    free(xyz);
    if (fig_close_csv(mdout, mdpath)) return fig_discard(out), CLI_EXIT_FAIL;
    return fig_close_csv(out, path) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

/* ------------------------------------------------------------------------ */
/* Command                                                                   */
/* ------------------------------------------------------------------------ */

/* Creates DIR if missing and proves it writable by creating a file in it: access(W_OK) says
 * yes to root even on read-only mounts. */
static int prepare_dir(const char *dir)
{
    struct stat stt;
    if (mkdir(dir, 0777) != 0 && errno != EEXIST)
        return cli_error(FIG_CMD, "cannot create output directory %s: %s", dir, strerror(errno)), -1;
    if (stat(dir, &stt) != 0 || !S_ISDIR(stt.st_mode))
        return cli_error(FIG_CMD, "output path %s is not a directory", dir), -1;
    char probe[4096];
    snprintf(probe, sizeof probe, "%s/.biref-figure-probe", dir);
    FILE *f = fopen(probe, "w");
    if (!f) return cli_error(FIG_CMD, "output directory %s is not writable: %s", dir, strerror(errno)), -1;
    fclose(f);
    remove(probe);
    return 0;
}

/* fig9 needs at least one of its scenes, table1 needs fig9a; a scene that is present must load. */
static int check_scenes(const char *scenes, int fig9_on, int table1_on)
{
    struct stat st;
    if (stat(scenes, &st) != 0 || !S_ISDIR(st.st_mode))
        return cli_error(FIG_CMD, "--scenes: '%s' is not a directory", scenes), -1;
    static const char *const names[3] = {"fig9a", "fig9b", "fig9c"};
    int found = 0;
    for (int i = 0; i < 3; i++) {
        char path[4096], msg[256];
        snprintf(path, sizeof path, "%s/%s.json", scenes, names[i]);
        if (access(path, F_OK) != 0) {
            if (i == 0 && table1_on) return cli_error(FIG_CMD, "table1: %s not found", path), -1;
            continue;
        }
        biref_scene sc;
        if (biref_scene_load(path, &sc, msg, sizeof msg) != BIREF_OK)
            return cli_error(FIG_CMD, "%s: %s", path, msg), -1;
        found++;
    }
    if (fig9_on && !found) return cli_error(FIG_CMD, "fig9: no scene found in %s (fig9a/b/c.json)", scenes), -1;
    return 0;
}

/* What each figure reads (relative to --scenes) and writes (in DIR), checked against each other
 * before the first figure is computed (docs/CLI.md, "Files"). */
static const struct {
    const char *reads[5], *writes[4];
} FIGURE_FILES[] = {
    {{NULL}, {"fig5.csv", "fig5.png"}},
    {{NULL}, {"fig6c.csv", "fig6c.png"}},
    {{NULL}, {"fig7.csv", "fig7.png"}},
    {{"fig9a.json", "fig9b.json", "fig9c.json"}, {"fig9.csv", "fig9_a.png", "fig9_b.png", "fig9_c.png"}},
    {{"fig9a.json"}, {"table1.csv", "table1.md"}},
    {{"fig9c.json", "aliasing/thick_grazing.json"}, {"aliasing.csv", "aliasing.png"}},
    {{NULL}, {"dispersion.csv", "dispersion_summary.csv", "dispersion.png"}},
    {{"stacks/lyot_stage1.json", "stacks/solc_folded.json", "stacks/film_on_glass.json",
      "stacks/quartz_zero_order_halfwave.json", "stacks/quartz_multi_order_halfwave.json"},
     {"filters.csv", "filters.png"}},
    {{NULL}, {"tape_art.csv", "tape_art.png"}},
    {{NULL}, {"stress_thickness.csv", "stress_thickness.png"}},
};

static int check_files(const char *dir, const char *scenes, const int *sel, int n)
{
    cli_files files;
    cli_files_init(&files);
    for (int i = 0; i < n; i++) {
        if (!sel[i]) continue;
        for (int k = 0; k < 5 && FIGURE_FILES[i].reads[k]; k++) {
            char path[4096];
            snprintf(path, sizeof path, "%s/%s", scenes, FIGURE_FILES[i].reads[k]);
            cli_files_read(&files, "--scenes", path);
        }
        for (int k = 0; k < 4 && FIGURE_FILES[i].writes[k]; k++) {
            const char *name = FIGURE_FILES[i].writes[k];
            cli_files_write_in_dir(&files, "-o", strrchr(name, '.') + 1, dir, name);
        }
    }
    int rc = cli_files_check(FIG_CMD, &files);
    cli_files_free(&files);
    return rc;
}

/* The command line, parsed. */
typedef struct {
    const char *dir, *scenes;
    int quick;
    long threads;
} figure_args;

#define F(field) offsetof(figure_args, field)
static const cli_opt OPTS[] = {
    CLI_STRING("output", 'o', "DIR", F(dir), "output directory (created if missing; its parent must exist)"),
    CLI_FLAG("quick", 0, F(quick), "fewer samples and smaller images (seconds instead of minutes)"),
    CLI_INT("threads", "T", F(threads), 1, 1024, "OpenMP threads (default: all cores)"),
    CLI_STRING("scenes", 0, "DIR", F(scenes),
               "where fig9a/b/c.json are (default: examples, from $BIREF_DATA_DIR\n"
               "or the installed copy when not in the current directory)"),
    {.name = "out", .kind = CLI_OPT_STRING, .value = "DIR", .offset = F(dir), .old_of = "output",
     .help = "-o, --output DIR"},
};
#undef F

const cli_command_spec CLI_FIGURE = {
    "figure",
    "usage: biref figure NAME -o DIR [--quick] [--threads T]\n\n"
    "Regenerates a figure or table of the paper as PNG plots plus CSV numbers in DIR.\n\n"
    "NAME:\n"
    "  fig5     |J|, |J_s|, |J_p| of transmission vs angle (random polarisation, 550 nm)\n"
    "  fig6c    chromaticity vs angle of the s->p transmission, analytic vs ground truth\n"
    "  fig7     CIEDE2000 of analytic vs ground truth as a function of angle and birefringence\n"
    "           (and of analytic-pairs between crossed polarisers)\n"
    "  fig9     renders of examples/fig9{a,b,c}.json with every method (the paper's and\n"
    "           analytic-pairs), with error maps\n"
    "  table1   time per 1920x1080 frame of each method (and analytic-pairs) on examples/fig9a.json\n"
    "  aliasing plain, prefiltered (--antialias) and 4x4 super-sampled renders of scenes made\n"
    "           to alias against a 32x32 super-sampled reference, with dE00 maps and costs\n"
    "  dispersion  five crystal plates over 0-70 deg, exact, with the indices fixed at 550 nm\n"
    "           and with n(lambda): colours side by side, dE00 between them (docs/MATERIALS.md)\n"
    "  filters  transmission spectra of a Lyot and a folded Solc filter (stacks/ under --scenes)\n"
    "  tape-art cellophane patches between crossed polarizers: a stained-glass picture\n"
    "  stress-thickness  a disk whose stress varies through its thickness, dark-field\n"
    "           polariscope: uniform, parabolic profile, principal directions turning\n"
    "  all      everything above\n\n"
    "Options:\n",
    OPTS,
    CLI_OPTS_COUNT(OPTS),
    NULL,
    0,
    NULL,
    1,
    NULL,
};

int cmd_figure(int argc, char **argv)
{
    figure_args a = {NULL, NULL, 0, 0};
    cli_parsed p;
    int r = cli_opts_parse(&CLI_FIGURE, &a, argc, argv, &p);
    if (r) return r > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    fig_ctx c = {0};
    c.dir = a.dir;
    c.quick = a.quick;
    c.threads = (int)a.threads;
    const char *scenes = a.scenes;
    const int first_arg = p.first_arg;
    if (first_arg >= argc)
        return cli_error(FIG_CMD, "missing figure name (fig5, fig6c, fig7, fig9, table1, aliasing, dispersion, filters, "
                                  "tape-art, stress-thickness or all)"),
               CLI_EXIT_USAGE;
    if (first_arg + 1 < argc) return cli_error(FIG_CMD, "unexpected argument '%s'", argv[first_arg + 1]), CLI_EXIT_USAGE;
    const char *name = argv[first_arg];
    char default_scenes[4096];
    if (!scenes) scenes = cli_data_path("examples", default_scenes, sizeof default_scenes);
    static const char *const NAMES[] = {"fig5",       "fig6c",   "fig7",     "fig9",
                                        "table1",     "aliasing", "dispersion", "filters",
                                        "tape-art",   "stress-thickness"};
    enum { NFIG = 10 };
    int sel[NFIG] = {0}, any = 0;
    for (int i = 0; i < NFIG; i++) any |= sel[i] = !strcmp(name, NAMES[i]) || !strcmp(name, "all");
    if (!any)
        return cli_error(FIG_CMD,
                         "unknown figure '%s' (expected fig5, fig6c, fig7, fig9, table1, aliasing, dispersion, "
                         "filters, tape-art, stress-thickness or all)",
                         name),
               CLI_EXIT_USAGE;
    if (!c.dir) return cli_error(FIG_CMD, "missing -o DIR"), CLI_EXIT_USAGE;
    /* Everything the figures read is checked before the first one is computed. */
    if ((sel[3] || sel[4]) && check_scenes(scenes, sel[3], sel[4])) return CLI_EXIT_USAGE;
    if (sel[7] && fig_filters_check(scenes)) return CLI_EXIT_USAGE;
    /* In an MPI job rank 0 alone writes, on its own file system. */
    const int root = cli_mpi_rank() == 0;
    if (root && (r = check_files(c.dir, scenes, sel, NFIG))) return r;
    if (root && prepare_dir(c.dir)) return CLI_EXIT_FAIL;
    if (c.threads > 0) omp_set_num_threads(c.threads);

    biref_spectral_config cfg;
    biref_spectral_config_default(&cfg);
    char why[BIREF_MSG_SIZE];
    if (biref_spectral_create(&cfg, &c.sp, why, sizeof why) != BIREF_OK)
        return cli_error(FIG_CMD, "spectral context: %s", why), CLI_EXIT_FAIL;
    if (biref_numeric_plan_create(c.sp, BIREF_GROUND_TRUTH_SAMPLES, &c.gt, why, sizeof why) != BIREF_OK)
        return biref_spectral_destroy(c.sp), cli_error(FIG_CMD, "numeric plan: %s", why), CLI_EXIT_FAIL;
    /* In an MPI job: every process is ready, or all stop with the first failure's line. */
    int rc = cli_mpi_agree(CLI_EXIT_OK);
    for (int i = 0; i < NFIG && rc == CLI_EXIT_OK; i++) {
        if (!sel[i]) continue;
        /* The other processes of an MPI job share fig9's renders; rank 0 makes everything else. */
        if (!root) {
            if (i == 3 && (rc = fig9(&c, scenes))) rc = cli_mpi_abort(rc);
            continue;
        }
        fprintf(stderr, "biref figure: %s%s ...\n", NAMES[i], c.quick ? " (quick)" : "");
        double t0 = biref_wall_seconds();
        switch (i) {
        case 0: rc = fig5(&c); break;
        case 1: rc = fig6c(&c); break;
        case 2: rc = fig7(&c); break;
        case 3: rc = fig9(&c, scenes); break;
        case 4: rc = table1(&c, scenes); break;
        case 5: rc = fig_aliasing(c.sp, c.dir, scenes, c.quick, c.threads); break;
        case 6: rc = fig_dispersion(&c); break;
        case 7: rc = fig_filters(&c, scenes); break;
        case 8: rc = fig_tape_art(&c); break;
        default: rc = fig_stress_thickness(&c); break;
        }
        if (rc == CLI_EXIT_OK) fprintf(stderr, "biref figure: %s done in %.1f s\n", NAMES[i], biref_wall_seconds() - t0);
        /* The other processes of an MPI job may be waiting for fig9's renders: the job ends here. */
        else
            rc = cli_mpi_abort(rc);
    }
    biref_numeric_plan_destroy(c.gt);
    biref_spectral_destroy(c.sp);
    return rc;
}
