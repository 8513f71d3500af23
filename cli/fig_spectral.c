/* biref figure: the paper's figures 5, 6c and 7 (slab colours against thickness, angle and
 * birefringence; no rendering). What each shows: docs/REPRODUCTION.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "fig_common.h"
#include "fig_plot.h"

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

int fig5(const fig_ctx *c)
{
    const double lambda = 550.0;
    const int n = c->quick ? 2000 : 20000;
    const int nm = (int)(sizeof FIG5_MATERIALS / sizeof FIG5_MATERIALS[0]);
    double *th = malloc(sizeof(double) * (size_t)n);
    double *J = malloc(sizeof(double) * (size_t)n * 3 * (size_t)nm);
    if (!th || !J) return free(th), free(J), cli_error(FIG_CMD, "out of memory"), CLI_EXIT_FAIL;
    char path[4096];
    biref_outfile *out = fig_open_csv(c, "fig5.csv", path, sizeof path);
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
            if (biref_slab_jones(&slab, fig_deg2rad(th[i]), lambda, &T, NULL) != BIREF_OK) {
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
    if (fig_close_csv(out, path)) return free(th), free(J), CLI_EXIT_FAIL;

    fig_out_path(c, "fig5.png", path, sizeof path);
    if (fig_begin(path, 1200, 900, 2, 2)) return free(th), free(J), CLI_EXIT_FAIL;
    for (int m = 0; m < nm; m++) {
        const double *o = J + ((size_t)m * 3) * (size_t)n;
        /* Headroom above the curves (they reach 1) holds the legend, clear of the data. */
        fig_plot_panel(0, 89, 0, 1.45, "θ (degrees)", "magnitude", FIG5_MATERIALS[m].label);
        fig_plot_line(n, th, o + n, FIG_BLUE, 1.0);
        fig_plot_line(n, th, o + 2 * (size_t)n, FIG_RED, 1.0);
        fig_plot_line(n, th, o, FIG_BLACK, 1.0);
        static const char *const labels[] = {"|J|", "|J_s|", "|J_p|"};
        static const int colors[] = {FIG_BLACK, FIG_BLUE, FIG_RED};
        fig_plot_legend(3, labels, colors, NULL, FIG_LEFT);
    }
    free(th);
    free(J);
    return fig_end(path) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

/* ------------------------------------------------------------------------ */
/* Figure 6c: fig_chromaticity vs angle, analytic vs ground truth                */
/* ------------------------------------------------------------------------ */

/* A quartz-like plate tens of µm thick: its retardance (~0.5 µm at normal incidence) sits in the first two orders of
 * the Michel-Lévy chart, where the s->p colour sweeps across the fig_chromaticity plane as theta
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
        fig_chromaticity(xyz, &x[i], &y[i]);
    }
    x[NL] = x[0];
    y[NL] = y[0];
    fig_plot_line(NL + 1, x, y, FIG_GREY, 1.0);
}

int fig6c(const fig_ctx *c)
{
    const int n = c->quick ? 90 : 891;
    double *buf = malloc(sizeof(double) * (size_t)n * 8);
    if (!buf) return cli_error(FIG_CMD, "out of memory"), CLI_EXIT_FAIL;
    double *th = buf, *xa = buf + n, *ya = buf + 2 * n, *xg = buf + 3 * n, *yg = buf + 4 * n, *de = buf + 5 * n,
           *Ya = buf + 6 * n, *Yg = buf + 7 * n;
    biref_slab slab = {FIG6C.eta_o, FIG6C.eta_e, {FIG6C.axis[0], FIG6C.axis[1], FIG6C.axis[2]}, FIG6C.d_nm, 1.0};
#pragma omp parallel for schedule(dynamic, 4)
    for (int i = 0; i < n; i++) {
        th[i] = 89.0 * i / (n - 1);
        biref_slab_state st;
        xa[i] = ya[i] = xg[i] = yg[i] = de[i] = Ya[i] = Yg[i] = NAN;
        if (biref_slab_prepare(&slab, fig_deg2rad(th[i]), &st) != BIREF_OK) continue;
        biref_spectrum sa, sg;
        biref_spectrum_analytic(c->sp, &st, &sa);
        biref_spectrum_numeric(c->gt, &st, &sg);
        double a[3], g[3];
        transmitted_xyz(&sa, LIGHT_S_TO_P, a);
        transmitted_xyz(&sg, LIGHT_S_TO_P, g);
        fig_chromaticity(a, &xa[i], &ya[i]);
        fig_chromaticity(g, &xg[i], &yg[i]);
        Ya[i] = a[1];
        Yg[i] = g[1];
        de[i] = biref_delta_e00_xyz(a, g);
    }
    char path[4096];
    biref_outfile *out = fig_open_csv(c, "fig6c.csv", path, sizeof path);
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
    if (fig_close_csv(out, path)) return free(buf), CLI_EXIT_FAIL;

    fig_out_path(c, "fig6c.png", path, sizeof path);
    if (fig_begin(path, 1300, 620, 2, 1)) return free(buf), CLI_EXIT_FAIL;
    double pad = 0.05 * fmax(xmax - xmin, ymax - ymin) + 0.01;
    char title[160];
    snprintf(title, sizeof title, "s-polarised in, p out (CIE 1931 xy)\n%s", FIG6C.label);
    /* Extra room below keeps the legend (bottom right) off the curve. */
    fig_plot_panel(xmin - pad, xmax + 2 * pad, ymin - 6 * pad, ymax + pad, "x", "y", title);
    draw_locus();
    fig_plot_line(n, xg, yg, FIG_BLACK, 4.0);
    fig_plot_line(n, xa, ya, FIG_ORANGE, 1.5);
    /* Angle labels along the ground-truth curve so the reader can follow theta; where the curve
     * turns slowly (50-70 degrees) labels closer than a label's width to the last one are left
     * out rather than printed over each other. */
    double last_x = INFINITY, last_y = INFINITY;
    const double min_dx = 0.09 * (xmax - xmin + 3 * pad), min_dy = 0.05 * (ymax - ymin + 6 * pad);
    for (int k = 0; k <= 8; k++) {
        int i = (int)lround((n - 1) * (k * 10.0) / 89.0);
        if (i >= n || !isfinite(xg[i])) continue;
        if (fabs(xg[i] - last_x) < min_dx && fabs(yg[i] - last_y) < min_dy) continue;
        char lab[16];
        snprintf(lab, sizeof lab, "%d°", k * 10);
        fig_plot_text(xg[i], yg[i], lab);
        last_x = xg[i], last_y = yg[i];
    }
    static const char *const labels[] = {"ground truth (16384)", "analytic (m = 1)", "spectral locus, purple line"};
    static const int colors[] = {FIG_BLACK, FIG_ORANGE, FIG_GREY};
    static const double widths[] = {4.0, 1.5, 1.0};
    fig_plot_legend(3, labels, colors, widths, FIG_BOTTOM);
    fig_plot_panel(0, 89, 0, fmax(1.0, demax * 1.05), "θ (degrees)", "ΔE00", "analytic vs ground truth");
    fig_plot_line(n, th, de, FIG_RED, 1.5);
    free(buf);
    return fig_end(path) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
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
/* Rows: the paper's analytic method (eq. 26) in three lights, then analytic-pairs (beyond the
 * paper) between crossed polarisers, where eq. 26 errs most. */
enum { FIG7_NM = 3, FIG7_ND = 6, FIG7_ROWS = 4 };

int fig7(const fig_ctx *c)
{
    const int nth = c->quick ? 12 : 45;   /* theta = 0 .. 88 degrees */
    const int nphi = c->quick ? 2 : 12;   /* azimuths of the optic axis about the normal */
    const size_t ncell = (size_t)FIG7_NM * FIG7_ND * (size_t)nth;
    /* [row][cell]: row 0 unpolarised at phi = 0, row 1 unpolarised azimuth-averaged,
     * row 2 crossed (s in, p out) azimuth-averaged, row 3 the same by analytic-pairs. */
    double *de = calloc(ncell * FIG7_ROWS, sizeof(double));
    double *th = malloc(sizeof(double) * (size_t)nth);
    if (!de || !th) return free(de), free(th), cli_error(FIG_CMD, "out of memory"), CLI_EXIT_FAIL;
    for (int t = 0; t < nth; t++) th[t] = 88.0 * t / (nth - 1);
    long failed = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : failed)
    for (long k = 0; k < (long)ncell; k++) {
        int m = (int)(k / ((long)FIG7_ND * nth)), d = (int)(k / nth % FIG7_ND), t = (int)(k % nth);
        const material *mt = &FIG7_MATERIALS[m];
        double eps_e = mt->eta_o * mt->eta_o + FIG7_DEPS[d];
        double acc[FIG7_ROWS] = {0, 0, 0, 0};
        for (int p = 0; p < nphi; p++) {
            /* Rotating the axis about the slab normal (y) by phi is the same as turning the slab
             * under a fixed plane of incidence. */
            double phi = 2.0 * M_PI * p / nphi, cp = cos(phi), sp = sin(phi);
            biref_slab slab = {mt->eta_o, sqrt(eps_e),
                               {mt->axis[0] * cp + mt->axis[2] * sp, mt->axis[1], -mt->axis[0] * sp + mt->axis[2] * cp},
                               mt->d_nm, 1.0};
            biref_slab_state st;
            if (biref_slab_prepare(&slab, fig_deg2rad(th[t]), &st) != BIREF_OK) {
                failed++;
                continue;
            }
            biref_spectrum sa, sg, sq;
            biref_spectrum_analytic(c->sp, &st, &sa);
            biref_spectrum_analytic_pairs(c->sp, &st, &sq);
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
            transmitted_xyz(&sq, LIGHT_S_TO_P, a);
            acc[3] += biref_delta_e00_xyz(a, g) / nphi;
        }
        for (int r = 0; r < FIG7_ROWS; r++) de[r * ncell + (size_t)k] = acc[r];
    }
    if (failed) return free(de), free(th), cli_error(FIG_CMD, "fig7: %ld slab evaluations failed", failed), CLI_EXIT_FAIL;

    char path[4096];
    biref_outfile *out = fig_open_csv(c, "fig7.csv", path, sizeof path);
    if (!out) return free(de), free(th), CLI_EXIT_FAIL;
    FILE *f = biref_outfile_stream(out);
    fprintf(f, "material,eta_o,eta_e,delta_eps,thickness_nm,theta_deg,dE00_unpolarized_phi0,"
               "dE00_unpolarized_phi_avg,dE00_crossed_s_to_p_phi_avg,dE00_crossed_s_to_p_phi_avg_analytic_pairs,"
               "azimuths\n");
    double rmax[FIG7_ROWS] = {0, 0, 0, 0};
    for (size_t k = 0; k < ncell; k++) {
        int m = (int)(k / ((size_t)FIG7_ND * nth)), d = (int)(k / nth % FIG7_ND), t = (int)(k % nth);
        const material *mt = &FIG7_MATERIALS[m];
        fprintf(f, "%s,%g,%.6f,%g,%g,%g,%.5f,%.5f,%.5f,%.5f,%d\n", mt->tag, mt->eta_o,
                sqrt(mt->eta_o * mt->eta_o + FIG7_DEPS[d]), FIG7_DEPS[d], mt->d_nm, th[t], de[k], de[ncell + k],
                de[2 * ncell + k], de[3 * ncell + k], nphi);
        for (int r = 0; r < FIG7_ROWS; r++) rmax[r] = fmax(rmax[r], de[r * ncell + k]);
    }
    if (fig_close_csv(out, path)) return free(de), free(th), CLI_EXIT_FAIL;

    fig_out_path(c, "fig7.png", path, sizeof path);
    if (fig_begin(path, 1500, 1600, FIG7_NM, FIG7_ROWS)) return free(de), free(th), CLI_EXIT_FAIL;
    static const int colors[FIG7_ND] = {FIG_BLUE, FIG_CYAN, FIG_GREEN, FIG_ORANGE, FIG_RED, FIG_PURPLE};
    static const char *const labels[FIG7_ND] = {"Δε = -0.3", "Δε = -0.1", "Δε = -0.03",
                                                "Δε = +0.03", "Δε = +0.1", "Δε = +0.3"};
    static const char *const rowname[FIG7_ROWS] = {"unpolarised, φ = 0", "unpolarised, φ-averaged",
                                                   "s in, p out, φ-averaged",
                                                   "s in, p out, φ-averaged: analytic-pairs"};
    /* PLplot fills panels row by row, so loop rows outside. */
    for (int r = 0; r < FIG7_ROWS; r++)
        for (int m = 0; m < FIG7_NM; m++) {
            char title[200];
            snprintf(title, sizeof title, "%s\n%s", FIG7_MATERIALS[m].label, rowname[r]);
            /* One y scale per row, so materials can be compared across a row; the two crossed rows
             * share theirs, so that eq. 26 and analytic-pairs compare at a glance. */
            const double ytop = r >= 2 ? fmax(rmax[2], rmax[3]) : rmax[r];
            fig_plot_panel(0, 88, 0, fmax(1.0, ytop * 1.05), "θ (degrees)", "ΔE00", title);
            const double one_x[2] = {0, 88}, one_y[2] = {1, 1};
            fig_plot_line(2, one_x, one_y, FIG_GREY, 1.0);
            for (int d = 0; d < FIG7_ND; d++)
                fig_plot_line(nth, th, de + r * ncell + ((size_t)m * FIG7_ND + d) * nth, colors[d], 1.5);
            if (r == 0 && m == 0) fig_plot_legend(FIG7_ND, labels, colors, NULL, FIG_LEFT);
        }
    int rc_plot = fig_end(path);
    free(de);
    free(th);
    return rc_plot ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

/* ------------------------------------------------------------------------ */
/* Figure 9: renders with every method and their ΔE00 maps                   */
/* ------------------------------------------------------------------------ */
