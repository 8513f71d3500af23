/* The two figures of `biref accuracy --plot-dir`: ΔE00 against cost per shading sample, and ΔE00
 * against the angle of incidence. PLplot (pngcairo) through fig_plot.h's page set-up and palette;
 * log axes and markers are drawn here. Not thread-safe (PLplot has global state). */
#ifndef BIREF_TOOLS_ACCURACY_PLOT_H
#define BIREF_TOOLS_ACCURACY_PLOT_H

/* How a method is drawn: its own colour, or the numeric family (joined by a line in order). */
typedef enum {
    ACC_STYLE_ANALYTIC,
    ACC_STYLE_PAIRS,
    ACC_STYLE_EXPANSION,
    ACC_STYLE_NUMERIC,
    ACC_STYLE_GROUND_TRUTH
} acc_plot_style;

typedef struct {
    const char *label; /* drawn under the mean marker, or NULL */
    acc_plot_style style;
    double ns;              /* cost per shading sample */
    double mean[2], max[2]; /* ΔE00 [transmission, reflection] */
} acc_plot_cost_point;

/* Two panels (transmission, reflection): x = ns per shading sample, y = ΔE00, both logarithmic;
 * per method a circle (mean) and a triangle (max) joined by a thin line. `note` goes under the
 * title (the sample set). Returns 0, or -1 if the file cannot be written. */
int acc_plot_vs_cost(const char *path, const acc_plot_cost_point *p, int n, const char *note);

typedef struct {
    int nmat, nmeth, ntheta;
    const char *const *mat_title; /* [nmat] */
    const char *const *meth_name; /* [nmeth] */
    const int *meth_color;        /* [nmeth], palette indices of fig_plot.h */
    const double *theta_deg; /* [ntheta] */
    /* ΔE00 over the azimuths of each angle, index ((mat * nmeth + meth) * 2 + w) * ntheta + it, NaN = none */
    const double *mean, *max;
    double mark_deg; /* a vertical guide (the acceptance range ends here), <= 0: none */
} acc_plot_theta_data;

/* Rows transmission / reflection, one column per material: y = ΔE00 (log), x = θ; per method
 * the maximum over azimuths (solid) and the mean (dashed). */
int acc_plot_vs_theta(const char *path, const acc_plot_theta_data *d);

#endif
