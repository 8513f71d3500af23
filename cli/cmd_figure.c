/* biref figure: regenerates the paper's figures 5, 6c, 7, 9 and table 1 as PNG plots (PLplot,
 * cairo for the image grids) with the underlying numbers as CSV next to each plot.
 * What each figure shows and how it compares with the paper: docs/REPRODUCTION.md. */
#include <cairo.h>
#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "biref/render.h"
#include "cli_common.h"
#include "cli_data.h"
#include "commands.h"
#include "fig_plot.h"
#include "io/outfile.h"

static const char *const CMD = "figure";

typedef struct {
    const char *dir;
    int quick;
    int threads; /* 0 = OpenMP default */
    biref_spectral *sp;
    biref_numeric_plan *gt; /* 16384-sample ground-truth plan */
} fig_ctx;

static void help(void)
{
    printf("usage: biref figure NAME -o DIR [--quick] [--threads T]\n\n"
           "Regenerates a figure or table of the paper as PNG plots plus CSV numbers in DIR.\n\n"
           "NAME:\n"
           "  fig5     |J|, |J_s|, |J_p| of transmission vs angle (random polarisation, 550 nm)\n"
           "  fig6c    chromaticity vs angle of the s->p transmission, analytic vs ground truth\n"
           "  fig7     CIEDE2000 of analytic vs ground truth as a function of angle and birefringence\n"
           "  fig9     renders of examples/fig9{a,b,c}.json with every method, with error maps\n"
           "  table1   time per 1920x1080 frame of each method on examples/fig9a.json\n"
           "  all      everything above\n\n"
           "Options:\n"
           "  -o, --out DIR        output directory (created if missing; its parent must exist)\n"
           "  --quick              fewer samples and smaller images (seconds instead of minutes)\n"
           "  --threads T          OpenMP threads (default: all cores)\n"
           "  --scenes DIR         where fig9a/b/c.json are (default: examples, from $BIREF_DATA_DIR\n"
           "                       or the installed copy when not in the current directory)\n"
           "  -h, --help           this help\n");
}

/* ------------------------------------------------------------------------ */
/* Small utilities                                                           */
/* ------------------------------------------------------------------------ */

static void out_path(const fig_ctx *c, const char *name, char *buf, size_t len)
{
    snprintf(buf, len, "%s/%s", c->dir, name);
}

/* Output files through io/outfile.h: in place only once complete. */
static biref_outfile *open_out(const char *path)
{
    char msg[600];
    biref_outfile *o = biref_outfile_open(path, msg, sizeof msg);
    if (!o) cli_error(CMD, "%s", msg);
    return o;
}

static biref_outfile *open_csv(const fig_ctx *c, const char *name, char *path, size_t len)
{
    out_path(c, name, path, len);
    return open_out(path);
}

static int close_csv(biref_outfile *o, const char *path)
{
    char msg[600];
    if (biref_outfile_close(o, 1, msg, sizeof msg) != BIREF_OK) return cli_error(CMD, "%s", msg), -1;
    printf("wrote %s\n", path);
    return 0;
}

static void discard(biref_outfile *o) { biref_outfile_close(o, 0, NULL, 0); }

static int plot_begin(const char *path, int width, int height, int nx, int ny)
{
    if (fig_plot_begin(path, width, height, nx, ny)) return cli_error(CMD, "%s", fig_plot_message()), -1;
    return 0;
}

static int plot_end(const char *path)
{
    if (fig_plot_end()) return cli_error(CMD, "%s", fig_plot_message()), -1;
    printf("wrote %s\n", path);
    return 0;
}

static cairo_status_t write_stream(void *closure, const unsigned char *data, unsigned int length)
{
    return fwrite(data, 1, length, closure) == length ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

static double deg2rad(double d) { return d * M_PI / 180.0; }

static void chromaticity(const double xyz[3], double *x, double *y)
{
    double s = xyz[0] + xyz[1] + xyz[2];
    *x = s > 0 ? xyz[0] / s : NAN;
    *y = s > 0 ? xyz[1] / s : NAN;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Colour of the transmitted light for a light model: unpolarised in, no analyzer
 * (the paper's S(|J|^2)), or s in, p out (crossed polarisers, fig. 6c). */
typedef enum { LIGHT_UNPOLARIZED, LIGHT_S_TO_P } light_model;

static void transmitted_xyz(const biref_spectrum *s, light_model m, double xyz[3])
{
    static const double UNPOL[2] = {0.5, 0.5}, ALL[2] = {1, 1}, S_IN[2] = {1, 0}, P_OUT[2] = {0, 1};
    if (m == LIGHT_UNPOLARIZED)
        biref_spectrum_mix(s->T, UNPOL, ALL, xyz);
    else
        biref_spectrum_mix(s->T, S_IN, P_OUT, xyz);
}

/* ------------------------------------------------------------------------ */
/* Figure 5: Jones magnitudes vs angle                                       */
/* ------------------------------------------------------------------------ */

typedef struct {
    const char *tag, *label;
    double eta_o, eta_e, axis[3], d_nm;
} material;

/* The fig. 9 materials plus a thin slab on which Fabry-Perot and birefringent interference are
 * slow enough in theta to be resolved by eye. */
static const material FIG5_MATERIALS[] = {
    {"fig9a", "fig. 9a: η_o 1.40, η_e 1.38, d 1.25 mm", 1.40, 1.38, {-0.54, 0.80, 0.27}, 1.25e6},
    {"fig9b", "fig. 9b: η_o 1.50, η_e 1.51, d 3.5 mm", 1.50, 1.51, {0.25, 0.97, 0.0}, 3.5e6},
    {"fig9c", "fig. 9c: η_o 1.775, η_e 1.231, d 1.15 mm", 1.775, 1.231, {0.084, 0.979, -0.187}, 1.15e6},
    {"thin", "thin: η_o 1.55, η_e 1.75, d 1.5 µm", 1.55, 1.75, {0.3, 0.5, 0.81}, 1500.0},
};

static int fig5(const fig_ctx *c)
{
    const double lambda = 550.0;
    const int n = c->quick ? 2000 : 20000;
    const int nm = (int)(sizeof FIG5_MATERIALS / sizeof FIG5_MATERIALS[0]);
    double *th = malloc(sizeof(double) * (size_t)n);
    double *J = malloc(sizeof(double) * (size_t)n * 3 * (size_t)nm);
    if (!th || !J) return free(th), free(J), cli_error(CMD, "out of memory"), CLI_EXIT_FAIL;
    char path[4096];
    biref_outfile *out = open_csv(c, "fig5.csv", path, sizeof path);
    if (!out) return free(th), free(J), CLI_EXIT_FAIL;
    FILE *f = biref_outfile_stream(out);
    fprintf(f, "material,eta_o,eta_e,axis_x,axis_y,axis_z,thickness_nm,lambda_nm,theta_deg,J,J_s,J_p\n");
    for (int m = 0; m < nm; m++) {
        const material *mt = &FIG5_MATERIALS[m];
        biref_slab slab = {mt->eta_o, mt->eta_e, {mt->axis[0], mt->axis[1], mt->axis[2]}, mt->d_nm, 1.0};
        for (int i = 0; i < n; i++) {
            th[i] = 89.0 * i / (n - 1);
            biref_jones T;
            double *o = J + ((size_t)m * 3) * (size_t)n;
            if (biref_slab_jones(&slab, deg2rad(th[i]), lambda, &T, NULL) != BIREF_OK) {
                o[i] = o[n + i] = o[2 * n + i] = NAN;
                continue;
            }
            double P[2][2];
            biref_jones_intensity(&T, P);
            /* Random (unpolarised) input: average the two input polarisations. */
            double js = 0.5 * (P[0][BIREF_S] + P[1][BIREF_S]), jp = 0.5 * (P[0][BIREF_P] + P[1][BIREF_P]);
            o[i] = sqrt(js + jp);
            o[n + i] = sqrt(js);
            o[2 * n + i] = sqrt(jp);
            fprintf(f, "%s,%g,%g,%g,%g,%g,%g,%g,%.6f,%.8f,%.8f,%.8f\n", mt->tag, mt->eta_o, mt->eta_e, mt->axis[0],
                    mt->axis[1], mt->axis[2], mt->d_nm, lambda, th[i], o[i], o[n + i], o[2 * n + i]);
        }
    }
    if (close_csv(out, path)) return free(th), free(J), CLI_EXIT_FAIL;

    out_path(c, "fig5.png", path, sizeof path);
    if (plot_begin(path, 1200, 900, 2, 2)) return free(th), free(J), CLI_EXIT_FAIL;
    for (int m = 0; m < nm; m++) {
        const double *o = J + ((size_t)m * 3) * (size_t)n;
        fig_plot_panel(0, 89, 0, 1.0, "θ (degrees)", "magnitude", FIG5_MATERIALS[m].label);
        fig_plot_line(n, th, o + n, FIG_BLUE, 1.0);
        fig_plot_line(n, th, o + 2 * (size_t)n, FIG_RED, 1.0);
        fig_plot_line(n, th, o, FIG_BLACK, 1.0);
        static const char *const labels[] = {"|J|", "|J_s|", "|J_p|"};
        static const int colors[] = {FIG_BLACK, FIG_BLUE, FIG_RED};
        fig_plot_legend(3, labels, colors, NULL, FIG_LEFT | FIG_BOTTOM);
    }
    free(th);
    free(J);
    return plot_end(path) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

/* ------------------------------------------------------------------------ */
/* Figure 6c: chromaticity vs angle, analytic vs ground truth                */
/* ------------------------------------------------------------------------ */

/* A quartz-like plate tens of µm thick: its retardance (~0.5 µm at normal incidence) sits in the first two orders of
 * the Michel-Lévy chart, where the s->p colour sweeps across the chromaticity plane as theta
 * changes the path difference. */
static const material FIG6C = {"fig6c", "η_o 1.544, η_e 1.553, A (0.6, 0.2, 0.77), d 60 µm", 1.544, 1.553,
                               {0.6, 0.2, 0.77}, 60e3};

static void draw_locus(void)
{
    /* The spectral locus (380-700 nm) and the purple line, for orientation. */
    enum { NL = 65 };
    double x[NL + 1], y[NL + 1];
    for (int i = 0; i < NL; i++) {
        double xyz[3];
        biref_cmf_eval(BIREF_CMF_CIE1931, 380.0 + 320.0 * i / (NL - 1), xyz);
        chromaticity(xyz, &x[i], &y[i]);
    }
    x[NL] = x[0];
    y[NL] = y[0];
    fig_plot_line(NL + 1, x, y, FIG_GREY, 1.0);
}

static int fig6c(const fig_ctx *c)
{
    const int n = c->quick ? 90 : 891;
    double *buf = malloc(sizeof(double) * (size_t)n * 8);
    if (!buf) return cli_error(CMD, "out of memory"), CLI_EXIT_FAIL;
    double *th = buf, *xa = buf + n, *ya = buf + 2 * n, *xg = buf + 3 * n, *yg = buf + 4 * n, *de = buf + 5 * n,
           *Ya = buf + 6 * n, *Yg = buf + 7 * n;
    biref_slab slab = {FIG6C.eta_o, FIG6C.eta_e, {FIG6C.axis[0], FIG6C.axis[1], FIG6C.axis[2]}, FIG6C.d_nm, 1.0};
#pragma omp parallel for schedule(dynamic, 4)
    for (int i = 0; i < n; i++) {
        th[i] = 89.0 * i / (n - 1);
        biref_slab_state st;
        xa[i] = ya[i] = xg[i] = yg[i] = de[i] = Ya[i] = Yg[i] = NAN;
        if (biref_slab_prepare(&slab, deg2rad(th[i]), &st) != BIREF_OK) continue;
        biref_spectrum sa, sg;
        biref_spectrum_analytic(c->sp, &st, &sa);
        biref_spectrum_numeric(c->gt, &st, &sg);
        double a[3], g[3];
        transmitted_xyz(&sa, LIGHT_S_TO_P, a);
        transmitted_xyz(&sg, LIGHT_S_TO_P, g);
        chromaticity(a, &xa[i], &ya[i]);
        chromaticity(g, &xg[i], &yg[i]);
        Ya[i] = a[1];
        Yg[i] = g[1];
        de[i] = biref_delta_e00_xyz(a, g);
    }
    char path[4096];
    biref_outfile *out = open_csv(c, "fig6c.csv", path, sizeof path);
    if (!out) return free(buf), CLI_EXIT_FAIL;
    FILE *f = biref_outfile_stream(out);
    fprintf(f, "theta_deg,x_analytic,y_analytic,Y_analytic,x_ground_truth,y_ground_truth,Y_ground_truth,dE00\n");
    double xmin = 1, xmax = 0, ymin = 1, ymax = 0, demax = 0;
    for (int i = 0; i < n; i++) {
        fprintf(f, "%.4f,%.6f,%.6f,%.6g,%.6f,%.6f,%.6g,%.4f\n", th[i], xa[i], ya[i], Ya[i], xg[i], yg[i], Yg[i],
                de[i]);
        const double px[2] = {xa[i], xg[i]}, py[2] = {ya[i], yg[i]};
        for (int k = 0; k < 2; k++) {
            if (!isfinite(px[k]) || !isfinite(py[k])) continue;
            xmin = fmin(xmin, px[k]), xmax = fmax(xmax, px[k]);
            ymin = fmin(ymin, py[k]), ymax = fmax(ymax, py[k]);
        }
        if (isfinite(de[i])) demax = fmax(demax, de[i]);
    }
    if (close_csv(out, path)) return free(buf), CLI_EXIT_FAIL;

    out_path(c, "fig6c.png", path, sizeof path);
    if (plot_begin(path, 1300, 620, 2, 1)) return free(buf), CLI_EXIT_FAIL;
    double pad = 0.05 * fmax(xmax - xmin, ymax - ymin) + 0.01;
    char title[160];
    snprintf(title, sizeof title, "s-polarised in, p out (CIE 1931 xy)\n%s", FIG6C.label);
    /* Extra room below keeps the legend (bottom right) off the curve. */
    fig_plot_panel(xmin - pad, xmax + 2 * pad, ymin - 5 * pad, ymax + pad, "x", "y", title);
    draw_locus();
    fig_plot_line(n, xg, yg, FIG_BLACK, 4.0);
    fig_plot_line(n, xa, ya, FIG_ORANGE, 1.5);
    /* Angle labels along the ground-truth curve so the reader can follow theta. */
    for (int k = 0; k <= 8; k++) {
        int i = (int)lround((n - 1) * (k * 10.0) / 89.0);
        if (i >= n || !isfinite(xg[i])) continue;
        char lab[16];
        snprintf(lab, sizeof lab, "%d°", k * 10);
        fig_plot_text(xg[i], yg[i], lab);
    }
    static const char *const labels[] = {"ground truth (16384)", "analytic (m = 1)"};
    static const int colors[] = {FIG_BLACK, FIG_ORANGE};
    static const double widths[] = {4.0, 1.5};
    fig_plot_legend(2, labels, colors, widths, FIG_BOTTOM);
    fig_plot_panel(0, 89, 0, fmax(1.0, demax * 1.05), "θ (degrees)", "ΔE00", "analytic vs ground truth");
    fig_plot_line(n, th, de, FIG_RED, 1.5);
    free(buf);
    return plot_end(path) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

/* ------------------------------------------------------------------------ */
/* Figure 7: ΔE00 of the analytic method vs angle and birefringence          */
/* ------------------------------------------------------------------------ */

/* Base materials (η_o, axis, thickness); Δε = ε_e - ε_o is swept. Thicknesses of a few to a
 * hundred µm: thick enough for coloured interference, thin enough that 16384 samples resolve it. */
static const material FIG7_MATERIALS[] = {
    {"m1", "η_o 1.40, A = fig. 9a axis, d 5 µm", 1.40, 0, {-0.54, 0.80, 0.27}, 5e3},
    {"m2", "η_o 1.50, A = fig. 9b axis, d 20 µm", 1.50, 0, {0.25, 0.97, 0.0}, 20e3},
    {"m3", "η_o 1.775, A = fig. 9c axis, d 100 µm", 1.775, 0, {0.084, 0.979, -0.187}, 100e3},
};
static const double FIG7_DEPS[] = {-0.3, -0.1, -0.03, 0.03, 0.1, 0.3};
enum { FIG7_NM = 3, FIG7_ND = 6, FIG7_ROWS = 3 };

static int fig7(const fig_ctx *c)
{
    const int nth = c->quick ? 12 : 45;   /* theta = 0 .. 88 degrees */
    const int nphi = c->quick ? 2 : 12;   /* azimuths of the optic axis about the normal */
    const size_t ncell = (size_t)FIG7_NM * FIG7_ND * (size_t)nth;
    /* [row][cell]: row 0 unpolarised at phi = 0, row 1 unpolarised azimuth-averaged,
     * row 2 crossed (s in, p out) azimuth-averaged. */
    double *de = calloc(ncell * FIG7_ROWS, sizeof(double));
    double *th = malloc(sizeof(double) * (size_t)nth);
    if (!de || !th) return free(de), free(th), cli_error(CMD, "out of memory"), CLI_EXIT_FAIL;
    for (int t = 0; t < nth; t++) th[t] = 88.0 * t / (nth - 1);
    long failed = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : failed)
    for (long k = 0; k < (long)ncell; k++) {
        int m = (int)(k / ((long)FIG7_ND * nth)), d = (int)(k / nth % FIG7_ND), t = (int)(k % nth);
        const material *mt = &FIG7_MATERIALS[m];
        double eps_e = mt->eta_o * mt->eta_o + FIG7_DEPS[d];
        double acc[FIG7_ROWS] = {0, 0, 0};
        for (int p = 0; p < nphi; p++) {
            /* Rotating the axis about the slab normal (y) by phi is the same as turning the slab
             * under a fixed plane of incidence. */
            double phi = 2.0 * M_PI * p / nphi, cp = cos(phi), sp = sin(phi);
            biref_slab slab = {mt->eta_o, sqrt(eps_e),
                               {mt->axis[0] * cp + mt->axis[2] * sp, mt->axis[1], -mt->axis[0] * sp + mt->axis[2] * cp},
                               mt->d_nm, 1.0};
            biref_slab_state st;
            if (biref_slab_prepare(&slab, deg2rad(th[t]), &st) != BIREF_OK) {
                failed++;
                continue;
            }
            biref_spectrum sa, sg;
            biref_spectrum_analytic(c->sp, &st, &sa);
            biref_spectrum_numeric(c->gt, &st, &sg);
            double a[3], g[3];
            transmitted_xyz(&sa, LIGHT_UNPOLARIZED, a);
            transmitted_xyz(&sg, LIGHT_UNPOLARIZED, g);
            double e = biref_delta_e00_xyz(a, g);
            if (p == 0) acc[0] = e;
            acc[1] += e / nphi;
            transmitted_xyz(&sa, LIGHT_S_TO_P, a);
            transmitted_xyz(&sg, LIGHT_S_TO_P, g);
            acc[2] += biref_delta_e00_xyz(a, g) / nphi;
        }
        for (int r = 0; r < FIG7_ROWS; r++) de[r * ncell + (size_t)k] = acc[r];
    }
    if (failed) return free(de), free(th), cli_error(CMD, "fig7: %ld slab evaluations failed", failed), CLI_EXIT_FAIL;

    char path[4096];
    biref_outfile *out = open_csv(c, "fig7.csv", path, sizeof path);
    if (!out) return free(de), free(th), CLI_EXIT_FAIL;
    FILE *f = biref_outfile_stream(out);
    fprintf(f, "material,eta_o,eta_e,delta_eps,thickness_nm,theta_deg,dE00_unpolarized_phi0,"
               "dE00_unpolarized_phi_avg,dE00_crossed_s_to_p_phi_avg,azimuths\n");
    double rmax[FIG7_ROWS] = {0, 0, 0};
    for (size_t k = 0; k < ncell; k++) {
        int m = (int)(k / ((size_t)FIG7_ND * nth)), d = (int)(k / nth % FIG7_ND), t = (int)(k % nth);
        const material *mt = &FIG7_MATERIALS[m];
        fprintf(f, "%s,%g,%.6f,%g,%g,%g,%.5f,%.5f,%.5f,%d\n", mt->tag, mt->eta_o,
                sqrt(mt->eta_o * mt->eta_o + FIG7_DEPS[d]), FIG7_DEPS[d], mt->d_nm, th[t], de[k], de[ncell + k],
                de[2 * ncell + k], nphi);
        for (int r = 0; r < FIG7_ROWS; r++) rmax[r] = fmax(rmax[r], de[r * ncell + k]);
    }
    if (close_csv(out, path)) return free(de), free(th), CLI_EXIT_FAIL;

    out_path(c, "fig7.png", path, sizeof path);
    if (plot_begin(path, 1500, 1200, FIG7_NM, FIG7_ROWS)) return free(de), free(th), CLI_EXIT_FAIL;
    static const int colors[FIG7_ND] = {FIG_BLUE, FIG_CYAN, FIG_GREEN, FIG_ORANGE, FIG_RED, FIG_PURPLE};
    static const char *const labels[FIG7_ND] = {"Δε = -0.3", "Δε = -0.1", "Δε = -0.03",
                                                "Δε = +0.03", "Δε = +0.1", "Δε = +0.3"};
    static const char *const rowname[FIG7_ROWS] = {"unpolarised, φ = 0", "unpolarised, φ-averaged",
                                                   "s in, p out, φ-averaged"};
    /* PLplot fills panels row by row, so loop rows outside. */
    for (int r = 0; r < FIG7_ROWS; r++)
        for (int m = 0; m < FIG7_NM; m++) {
            char title[200];
            snprintf(title, sizeof title, "%s\n%s", FIG7_MATERIALS[m].label, rowname[r]);
            /* One y scale per row, so materials can be compared across a row. */
            fig_plot_panel(0, 88, 0, fmax(1.0, rmax[r] * 1.05), "θ (degrees)", "ΔE00", title);
            const double one_x[2] = {0, 88}, one_y[2] = {1, 1};
            fig_plot_line(2, one_x, one_y, FIG_GREY, 1.0);
            for (int d = 0; d < FIG7_ND; d++)
                fig_plot_line(nth, th, de + r * ncell + ((size_t)m * FIG7_ND + d) * nth, colors[d], 1.5);
            if (r == 0 && m == 0) fig_plot_legend(FIG7_ND, labels, colors, NULL, FIG_LEFT);
        }
    int rc_plot = plot_end(path);
    free(de);
    free(th);
    return rc_plot ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

/* ------------------------------------------------------------------------ */
/* Figure 9: renders with every method and their ΔE00 maps                   */
/* ------------------------------------------------------------------------ */

typedef struct {
    const char *name;
    biref_method method;
    int samples;
} method_spec;

static const method_spec FIG9_METHODS[] = {
    {"analytic", BIREF_METHOD_ANALYTIC, 0},      {"numeric 3", BIREF_METHOD_NUMERIC, 3},
    {"numeric 8", BIREF_METHOD_NUMERIC, 8},      {"numeric 32", BIREF_METHOD_NUMERIC, 32},
    {"numeric 128", BIREF_METHOD_NUMERIC, 128},  {"ground truth", BIREF_METHOD_GROUND_TRUTH, 0},
};
enum { FIG9_NMETHODS = 6, FIG9_GT = 5 };
#define FIG9_DE_MAX 5.0

static int load_scene(const fig_ctx *c, const char *scenes, const char *name, int w, int h, biref_scene *sc)
{
    char path[4096], msg[256];
    snprintf(path, sizeof path, "%s/%s.json", scenes, name);
    if (biref_scene_load(path, sc, msg, sizeof msg) != BIREF_OK)
        return cli_error(CMD, "%s: %s", path, msg), -1;
    sc->camera.width = w;
    sc->camera.height = h;
    if (biref_scene_validate(sc, msg, sizeof msg) != BIREF_OK) return cli_error(CMD, "%s: %s", path, msg), -1;
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
    if (biref_renderer_create(sc, &opt, &r, msg, sizeof msg) != BIREF_OK)
        return cli_error(CMD, "%s: %s", ms->name, msg), -1.0;
    biref_progress_bar bar;
    biref_progress_bar_init(&bar, stderr, isatty(2), label);
    double t0 = biref_wall_seconds();
    biref_status s = biref_renderer_render(r, y0, sc->camera.height, step, xyz, biref_progress_bar_update, &bar, NULL);
    double t = biref_wall_seconds() - t0;
    biref_progress_bar_finish(&bar);
    biref_renderer_destroy(r);
    if (s != BIREF_OK) return cli_error(CMD, "%s: render failed: %s", ms->name, biref_status_string(s)), -1.0;
    return t;
}

/* ΔE00 -> colour: black below 0.5 (imperceptible), then blue, green, yellow, red at FIG9_DE_MAX. */
static void de_color(double e, double rgb[3])
{
    static const double stop[5] = {0.0, 1.0, 2.0, 3.0, FIG9_DE_MAX};
    static const double col[5][3] = {{0, 0, 0}, {0.1, 0.3, 1.0}, {0.1, 0.8, 0.2}, {1.0, 0.9, 0.1}, {0.9, 0.1, 0.1}};
    if (!(e > 0)) e = 0;
    if (e >= stop[4]) e = stop[4];
    int i = 0;
    while (i < 3 && e > stop[i + 1]) i++;
    double u = (e - stop[i]) / (stop[i + 1] - stop[i]);
    for (int k = 0; k < 3; k++) rgb[k] = col[i][k] + u * (col[i + 1][k] - col[i][k]);
}

static cairo_surface_t *surface_from_rgb(const unsigned char *rgb, int w, int h)
{
    cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    unsigned char *data = cairo_image_surface_get_data(s);
    int stride = cairo_image_surface_get_stride(s);
    cairo_surface_flush(s);
    for (int y = 0; y < h; y++) {
        uint32_t *row = (uint32_t *)(data + (size_t)y * stride);
        for (int x = 0; x < w; x++) {
            const unsigned char *p = rgb + 3 * ((size_t)y * w + x);
            row[x] = ((uint32_t)p[0] << 16) | ((uint32_t)p[1] << 8) | p[2];
        }
    }
    cairo_surface_mark_dirty(s);
    return s;
}

static void draw_tile(cairo_t *cr, cairo_surface_t *img, int w, int h, double x, double y, double scale)
{
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_scale(cr, scale, scale);
    cairo_set_source_surface(cr, img, 0, 0);
    /* Nearest neighbour: enlarged pixels stay pixels, so aliasing is shown, not blurred. */
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
    cairo_rectangle(cr, 0, 0, w, h);
    cairo_fill(cr);
    cairo_restore(cr);
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
        return free(xyz), free(rgb), free(de), free(sorted), cli_error(CMD, "out of memory"), CLI_EXIT_FAIL;
    double secs[FIG9_NMETHODS];
    for (int m = 0; m < FIG9_NMETHODS; m++) {
        char label[32];
        snprintf(label, sizeof label, "%s %s", name, FIG9_METHODS[m].name);
        fprintf(stderr, "biref figure: fig9: %s, %s (%dx%d)\n", name, FIG9_METHODS[m].name, w, h);
        secs[m] = render_rows(c, &sc, &FIG9_METHODS[m], 0, 1, xyz + (size_t)m * npx * 3, label);
        if (secs[m] < 0) return free(xyz), free(rgb), free(de), free(sorted), CLI_EXIT_FAIL;
        biref_xyz_image_to_srgb8(xyz + (size_t)m * npx * 3, npx, rgb + (size_t)m * npx * 3);
    }
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
            double col[3];
            de_color(e, col);
            for (int k = 0; k < 3; k++) map[3 * i + k] = (unsigned char)lround(255.0 * col[k]);
        }
        qsort(sorted, npx, sizeof(double), cmp_double);
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
        cairo_surface_t *img = surface_from_rgb(rgb + (size_t)m * npx * 3, w, h);
        draw_tile(cr, img, w, h, x, head, scale);
        cairo_surface_destroy(img);
        if (m == FIG9_GT) continue; /* its map against itself is empty */
        img = surface_from_rgb(rgb + (size_t)(FIG9_NMETHODS + m) * npx * 3, w, h);
        draw_tile(cr, img, w, h, x, head + thh + gap, scale);
        cairo_surface_destroy(img);
    }
    double by = head + 2 * (thh + gap) + 6;
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_move_to(cr, gap, by + 10);
    cairo_show_text(cr, "ΔE00 vs ground truth (second row):");
    double bx = gap + 250, bw = 360;
    for (int i = 0; i < (int)bw; i++) {
        double col[3];
        de_color(FIG9_DE_MAX * i / (bw - 1), col);
        cairo_set_source_rgb(cr, col[0], col[1], col[2]);
        cairo_rectangle(cr, bx + i, by, 1, 14);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    for (int v = 0; v <= (int)FIG9_DE_MAX; v++) {
        char lab[16];
        snprintf(lab, sizeof lab, v == (int)FIG9_DE_MAX ? "≥%d" : "%d", v);
        cairo_move_to(cr, bx + bw * v / FIG9_DE_MAX - 4, by + 30);
        cairo_show_text(cr, lab);
    }
    char path[4096], file[64];
    snprintf(file, sizeof file, "fig9_%s.png", name + strlen(name) - 1);
    out_path(c, file, path, sizeof path);
    cairo_surface_flush(out);
    biref_outfile *png = open_out(path);
    cairo_status_t cs = png ? cairo_surface_write_to_png_stream(out, write_stream, biref_outfile_stream(png))
                            : CAIRO_STATUS_WRITE_ERROR;
    cairo_destroy(cr);
    cairo_surface_destroy(out);
    free(xyz), free(rgb), free(de), free(sorted);
    if (!png) return CLI_EXIT_FAIL;
    if (cs != CAIRO_STATUS_SUCCESS) {
        discard(png);
        return cli_error(CMD, "cannot write %s: %s", path, cairo_status_to_string(cs)), CLI_EXIT_FAIL;
    }
    return close_csv(png, path) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

static int fig9(const fig_ctx *c, const char *scenes)
{
    char path[4096];
    biref_outfile *out = open_csv(c, "fig9.csv", path, sizeof path);
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
        if (rc) return discard(out), rc;
        done++;
    }
    if (!done) return discard(out), cli_error(CMD, "fig9: no scene found in %s (fig9a/b/c.json)", scenes), CLI_EXIT_USAGE;
    return close_csv(out, path) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

/* ------------------------------------------------------------------------ */
/* Table 1: frame times at 1920x1080                                         */
/* ------------------------------------------------------------------------ */

static int table1(const fig_ctx *c, const char *scenes)
{
    static const method_spec methods[] = {
        {"analytic", BIREF_METHOD_ANALYTIC, 0},        {"numeric 3", BIREF_METHOD_NUMERIC, 3},
        {"numeric 8", BIREF_METHOD_NUMERIC, 8},        {"numeric 32", BIREF_METHOD_NUMERIC, 32},
        {"numeric 128", BIREF_METHOD_NUMERIC, 128},    {"numeric 512", BIREF_METHOD_NUMERIC, 512},
        {"numeric 2048", BIREF_METHOD_NUMERIC, 2048},  {"ground truth", BIREF_METHOD_GROUND_TRUTH, 0},
    };
    /* The paper's frame times (table 1, mobile GeForce 1070), in seconds. */
    static const double paper[] = {1.09e-3, 1.30e-3, 1.73e-3, 3.84e-3, 12.2e-3, 45.5e-3, 0.20, 2.00};
    enum { NMETH = 8 };
    const int W = 1920, H = 1080;
    /* Seconds of measurement per method: a full frame when it fits, else every k-th row, whose
     * time scales to the frame because rows are spread evenly over the image. */
    const double budget = c->quick ? 1.0 : 20.0;
    biref_scene sc;
    if (load_scene(c, scenes, "fig9a", W, H, &sc)) return CLI_EXIT_USAGE;
    float *xyz = malloc(sizeof(float) * (size_t)W * H * 3);
    if (!xyz) return cli_error(CMD, "out of memory"), CLI_EXIT_FAIL;
    char path[4096], mdpath[4096];
    biref_outfile *out = open_csv(c, "table1.csv", path, sizeof path);
    if (!out) return free(xyz), CLI_EXIT_FAIL;
    FILE *f = biref_outfile_stream(out);
    out_path(c, "table1.md", mdpath, sizeof mdpath);
    biref_outfile *mdout = open_out(mdpath);
    if (!mdout) return discard(out), free(xyz), CLI_EXIT_FAIL;
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
        if (t < 0) return discard(out), discard(mdout), free(xyz), CLI_EXIT_FAIL;
        int rows = (H - y0 + step - 1) / step;
        double per_row = t / rows;
        if (per_row * H <= budget) {
            t = render_rows(c, &sc, &methods[m], 0, 1, xyz, label);
            if (t < 0) return discard(out), discard(mdout), free(xyz), CLI_EXIT_FAIL;
            rows = H;
        } else if ((int)(budget / per_row) > rows) {
            step = H / (int)(budget / per_row);
            y0 = step / 2;
            t = render_rows(c, &sc, &methods[m], y0, step, xyz, label);
            if (t < 0) return discard(out), discard(mdout), free(xyz), CLI_EXIT_FAIL;
            rows = (H - y0 + step - 1) / step;
        }
        double frame = t * H / rows;
        int extrap = rows < H;
        fprintf(f, "%s,%d,%d,%d,%.4f,%.4f,%d,%d,%g\n", methods[m].name,
                methods[m].method == BIREF_METHOD_GROUND_TRUTH ? BIREF_GROUND_TRUTH_SAMPLES : methods[m].samples, rows,
                H, t, frame, extrap, threads, paper[m]);
        char ours[64], theirs[32];
        snprintf(ours, sizeof ours, frame < 1 ? "%.0f ms%s" : "%.1f s%s", frame < 1 ? frame * 1e3 : frame,
                 extrap ? " (extrapolated)" : "");
        snprintf(theirs, sizeof theirs, paper[m] < 0.1 ? "%.2f ms" : "%.2f s", paper[m] < 0.1 ? paper[m] * 1e3 : paper[m]);
        fprintf(md, "| %s | %s | %d / %d | %s |\n", methods[m].name, ours, rows, H, theirs);
        fprintf(stderr, "biref figure: table1: %s: %.3f s per frame%s\n", methods[m].name, frame,
                extrap ? " (extrapolated)" : "");
    }
    free(xyz);
    if (close_csv(mdout, mdpath)) return discard(out), CLI_EXIT_FAIL;
    return close_csv(out, path) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
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
        return cli_error(CMD, "cannot create output directory %s: %s", dir, strerror(errno)), -1;
    if (stat(dir, &stt) != 0 || !S_ISDIR(stt.st_mode))
        return cli_error(CMD, "output path %s is not a directory", dir), -1;
    char probe[4096];
    snprintf(probe, sizeof probe, "%s/.biref-figure-probe", dir);
    FILE *f = fopen(probe, "w");
    if (!f) return cli_error(CMD, "output directory %s is not writable: %s", dir, strerror(errno)), -1;
    fclose(f);
    remove(probe);
    return 0;
}

/* fig9 needs at least one of its scenes, table1 needs fig9a; a scene that is present must load. */
static int check_scenes(const char *scenes, int fig9_on, int table1_on)
{
    struct stat st;
    if (stat(scenes, &st) != 0 || !S_ISDIR(st.st_mode))
        return cli_error(CMD, "--scenes: '%s' is not a directory", scenes), -1;
    static const char *const names[3] = {"fig9a", "fig9b", "fig9c"};
    int found = 0;
    for (int i = 0; i < 3; i++) {
        char path[4096], msg[256];
        snprintf(path, sizeof path, "%s/%s.json", scenes, names[i]);
        if (access(path, F_OK) != 0) {
            if (i == 0 && table1_on) return cli_error(CMD, "table1: %s not found", path), -1;
            continue;
        }
        biref_scene sc;
        if (biref_scene_load(path, &sc, msg, sizeof msg) != BIREF_OK) return cli_error(CMD, "%s: %s", path, msg), -1;
        found++;
    }
    if (fig9_on && !found) return cli_error(CMD, "fig9: no scene found in %s (fig9a/b/c.json)", scenes), -1;
    return 0;
}

enum { OPT_QUICK = 1000, OPT_THREADS, OPT_SCENES };

int cmd_figure(int argc, char **argv)
{
    static const struct option longopts[] = {{"out", required_argument, 0, 'o'},
                                             {"quick", no_argument, 0, OPT_QUICK},
                                             {"threads", required_argument, 0, OPT_THREADS},
                                             {"scenes", required_argument, 0, OPT_SCENES},
                                             {"help", no_argument, 0, 'h'},
                                             {0, 0, 0, 0}};
    fig_ctx c = {0};
    const char *scenes = NULL;
    long v;
    opterr = 0;
    optind = 1;
    int ch;
    while ((ch = getopt_long(argc, argv, ":ho:", longopts, NULL)) != -1) {
        switch (ch) {
        case 'h': help(); return CLI_EXIT_OK;
        case 'o': c.dir = optarg; break;
        case OPT_QUICK: c.quick = 1; break;
        case OPT_THREADS:
            if (cli_parse_int(CMD, "--threads", optarg, 1, 1024, &v)) return CLI_EXIT_USAGE;
            c.threads = (int)v;
            break;
        case OPT_SCENES: scenes = optarg; break;
        default: cli_getopt_error(CMD, ch, argv); return CLI_EXIT_USAGE;
        }
    }
    if (optind >= argc) return cli_error(CMD, "missing figure name (fig5, fig6c, fig7, fig9, table1 or all)"), CLI_EXIT_USAGE;
    if (optind + 1 < argc) return cli_error(CMD, "unexpected argument '%s'", argv[optind + 1]), CLI_EXIT_USAGE;
    const char *name = argv[optind];
    char default_scenes[4096];
    if (!scenes) scenes = cli_data_path("examples", default_scenes, sizeof default_scenes);
    static const char *const NAMES[] = {"fig5", "fig6c", "fig7", "fig9", "table1"};
    enum { NFIG = 5 };
    int sel[NFIG] = {0}, any = 0;
    for (int i = 0; i < NFIG; i++) any |= sel[i] = !strcmp(name, NAMES[i]) || !strcmp(name, "all");
    if (!any)
        return cli_error(CMD, "unknown figure '%s' (expected fig5, fig6c, fig7, fig9, table1 or all)", name),
               CLI_EXIT_USAGE;
    if (!c.dir) return cli_error(CMD, "missing -o DIR"), CLI_EXIT_USAGE;
    /* Everything the figures read is checked before the first one is computed. */
    if ((sel[3] || sel[4]) && check_scenes(scenes, sel[3], sel[4])) return CLI_EXIT_USAGE;
    if (prepare_dir(c.dir)) return CLI_EXIT_FAIL;
    if (c.threads > 0) omp_set_num_threads(c.threads);

    biref_spectral_config cfg;
    biref_spectral_config_default(&cfg);
    if (biref_spectral_create(&cfg, &c.sp) != BIREF_OK) return cli_error(CMD, "spectral context failed"), CLI_EXIT_FAIL;
    if (biref_numeric_plan_create(c.sp, BIREF_GROUND_TRUTH_SAMPLES, &c.gt) != BIREF_OK)
        return biref_spectral_destroy(c.sp), cli_error(CMD, "numeric plan failed"), CLI_EXIT_FAIL;
    int rc = CLI_EXIT_OK;
    for (int i = 0; i < NFIG && rc == CLI_EXIT_OK; i++) {
        if (!sel[i]) continue;
        fprintf(stderr, "biref figure: %s%s ...\n", NAMES[i], c.quick ? " (quick)" : "");
        double t0 = biref_wall_seconds();
        switch (i) {
        case 0: rc = fig5(&c); break;
        case 1: rc = fig6c(&c); break;
        case 2: rc = fig7(&c); break;
        case 3: rc = fig9(&c, scenes); break;
        default: rc = table1(&c, scenes); break;
        }
        if (rc == CLI_EXIT_OK) fprintf(stderr, "biref figure: %s done in %.1f s\n", NAMES[i], biref_wall_seconds() - t0);
    }
    biref_numeric_plan_destroy(c.gt);
    biref_spectral_destroy(c.sp);
    return rc;
}
