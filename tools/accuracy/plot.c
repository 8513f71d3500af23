/* Figures of `biref accuracy` (see accuracy_plot.h). */
#include "plot.h"

#include <errno.h>
#include <math.h>
#include <plplot.h>
#include <stdio.h>
#include <string.h>

#include "cli_common.h"
#include "fig_plot.h"

/* ΔE00 below this is drawn at this value: a log axis cannot show 0, and differences this small are
 * far below anything visible (the just-noticeable difference is about 1). */
#define DE_FLOOR 1e-3

/* Character scales: axis text, and the smaller labels, notes and legends. */
#define TEXT_SCALE 0.62
#define SMALL_SCALE 0.52
#define LEGEND_SCALE 0.47 /* legend text: a row holds about six entries */

static const char *const WHICH_TITLE[2] = {"transmission", "reflection"};

/* A light grey for the grid, after fig_plot.h's palette (whose grey is for data and guides). */
enum { GRID_GREY = FIG_BROWN + 1 };

/* One page without PLplot subpages: the panels get explicit viewports. */
static int page_begin(const char *path, int width, int height)
{
    if (fig_plot_begin(path, width, height, 1, 1))
        return cli_error("accuracy", "--plot-dir: %s", fig_plot_message()), -1;
    plscmap0n(GRID_GREY + 1); /* keeps the colours already set */
    plscol0(GRID_GREY, 215, 215, 215);
    pladv(0);
    return 0;
}

static double lg(double v) { return log10(fmax(v, DE_FLOOR)); }

/* A panel in page coordinates (vx0..vx1, vy0..vy1 in [0, 1]) with logarithmic axes where
 * requested; world coordinates are then log10 of the data. Explicit viewports instead of PLplot
 * subpages leave room where it is needed: titles, axis labels and a legend column. */
static void panel(double vx0, double vx1, double vy0, double vy1, double xmin, double xmax, double ymin, double ymax,
                  int logx, const char *xlabel, const char *ylabel, const char *title, const char *note)
{
    plschr(0.0, TEXT_SCALE);
    plvpor(vx0, vx1, vy0, vy1);
    plwind(logx ? log10(xmin) : xmin, logx ? log10(xmax) : xmax, log10(ymin), log10(ymax));
    plcol0(GRID_GREY);
    plwidth(1.0);
    /* Light grid first, then the black frame and labels over it. */
    plbox("g", 0.0, 0, "g", 0.0, 0);
    plcol0(FIG_BLACK);
    plwidth(1.0);
    plbox(logx ? "bclnst" : "bcnst", 0.0, 0, "bclnstv", 0.0, 0);
    plmtex("b", 2.8, 0.5, 0.5, xlabel);
    plmtex("l", 3.6, 0.5, 0.5, ylabel);
    if (note) {
        plmtex("t", 2.6, 0.5, 0.5, title);
        plschr(0.0, SMALL_SCALE);
        plmtex("t", 1.2, 0.5, 0.5, note);
        plschr(0.0, TEXT_SCALE);
    } else {
        plmtex("t", 1.3, 0.5, 0.5, title);
    }
}

/* A horizontal guide at ΔE00 = 1; the legend names it (a label on the line collided with the ticks
 * and the data). */
static void jnd_line(double x0, double x1)
{
    double x[2] = {x0, x1}, y[2] = {0.0, 0.0};
    plcol0(FIG_GREY);
    pllsty(3);
    plline(2, x, y);
    pllsty(1);
    plcol0(FIG_BLACK);
}

/* Says what the log axis cannot show, in a line above the panel titles. */
static void floor_note(void)
{
    plvpor(0.03, 0.97, 0.965, 0.995);
    plwind(0.0, 1.0, 0.0, 1.0);
    plschr(0.0, SMALL_SCALE);
    plcol0(FIG_BLACK);
    plptex(0.0, 0.5, 1.0, 0.0, 0.0, "ΔE00 below 10#u-3#d is drawn at 10#u-3#d (the bottom axis): a log axis cannot show 0.");
    plschr(0.0, TEXT_SCALE);
}

static int style_color(acc_plot_style s)
{
    switch (s) {
    case ACC_STYLE_ANALYTIC: return FIG_RED;
    case ACC_STYLE_PAIRS: return FIG_ORANGE;
    case ACC_STYLE_EXPANSION: return FIG_BLUE;
    case ACC_STYLE_GROUND_TRUTH: return FIG_BLACK;
    default: return FIG_GREY;
    }
}

/* Glyphs through the cairo driver's Unicode text: clearer than PLplot's Hershey symbols. */
static const char *const MARK_MEAN = "●", *const MARK_MAX = "▲";

/* A legend in one row in the strip at the bottom of the page, below the panels, where it hides
 * no data. Drawn by hand: pllegend's column widths come out far wider than the text with the
 * cairo driver. Entry i: a line sample (lsty > 0) and/or a glyph (sym != NULL), then its text. */
typedef struct {
    const char *text;
    int color, lsty;
    double lwid;
    const char *sym;
} legend_entry;

/* Characters, not bytes: the labels carry Δ, θ and °, two bytes each in UTF-8. */
static double text_chars(const char *t)
{
    double n = 0.0;
    for (; *t; t++) n += ((unsigned char)*t & 0xC0) != 0x80;
    return n;
}

/* One row of entries at height y (0 bottom, 1 top of the strip). Each column: the sample, a gap,
 * its text and a gap before the next sample; what the samples and gaps leave is shared in
 * proportion to the text lengths, so no text runs into the next entry's sample. */
static void legend_row(int n, const legend_entry *e, double y)
{
    double len[16], total = 0.0;
    if (n > 16) n = 16;
    for (int i = 0; i < n; i++) total += len[i] = text_chars(e[i].text);
    const double sample = 0.03, gap = 0.008, pad = 0.014, fixed = sample + gap + pad;
    const double spare = 0.98 - n * fixed;
    double x0 = 0.01;
    for (int i = 0; i < n; i++) {
        if (i) x0 += fixed + spare * len[i - 1] / total;
        double lx[2] = {x0, x0 + sample}, ly[2] = {y, y};
        plcol0(e[i].color);
        if (e[i].lsty > 0) {
            pllsty(e[i].lsty);
            plwidth(e[i].lwid);
            plline(2, lx, ly);
            pllsty(1);
            plwidth(1.0);
        }
        if (e[i].sym) {
            double sx = x0 + 0.5 * sample, sy = y;
            plssym(0.0, 1.1);
            plstring(1, &sx, &sy, e[i].sym);
        }
        plcol0(FIG_BLACK);
        plptex(x0 + sample + gap, y, 1.0, 0.0, 0.0, e[i].text);
    }
}

/* The legend in the strip at the bottom of the page; entries from `split` on go to a second row
 * (split >= n: one row). Nine entries of up to 20 characters do not fit one row at this text
 * size: they ran into each other. */
static void bottom_legend(int n, const legend_entry *e, int split)
{
    plvpor(0.03, 0.97, 0.012, 0.062);
    plwind(0.0, 1.0, 0.0, 1.0);
    plcol0(FIG_BLACK);
    plwidth(1.0);
    plbox("bc", 0.0, 0, "bc", 0.0, 0);
    plschr(0.0, LEGEND_SCALE);
    if (split >= n) {
        legend_row(n, e, 0.5);
    } else {
        legend_row(split, e, 0.72);
        legend_row(n - split, e + split, 0.28);
    }
    plschr(0.0, TEXT_SCALE);
}

int acc_plot_vs_cost(const char *path, const acc_plot_cost_point *p, int n, const char *note)
{
    double xmin = INFINITY, xmax = 0.0, ymax = 1.0;
    for (int i = 0; i < n; i++) {
        xmin = fmin(xmin, p[i].ns);
        xmax = fmax(xmax, p[i].ns);
        for (int w = 0; w < 2; w++) ymax = fmax(ymax, p[i].max[w]);
    }
    /* Whole decades. */
    xmin = pow(10.0, floor(log10(xmin / 1.5)));
    xmax = pow(10.0, ceil(log10(xmax * 1.5)));
    ymax = pow(10.0, ceil(log10(ymax * 1.2)));
    plsetopt("drvopt", "graphics_anti_aliasing=0"); /* the default; acc_plot_vs_theta turns it off */
    if (page_begin(path, 1500, 680)) return -1;
    for (int w = 0; w < 2; w++) {
        char title[96];
        snprintf(title, sizeof title, "ΔE00 vs cost, %s", WHICH_TITLE[w]);
        const double vx0 = w ? 0.555 : 0.06;
        panel(vx0, vx0 + 0.425, 0.2, 0.86, xmin, xmax, DE_FLOOR, ymax, 1,
              "ns per shading sample (one core, biref_slab_prepare included)", "ΔE00 against the reference", title, note);
        jnd_line(log10(xmin), log10(xmax));
        /* The numeric family as a curve through its max (solid) and mean (dashed) markers. */
        double lx[32], lmean[32], lmax[32];
        int nl = 0;
        for (int i = 0; i < n && nl < 32; i++)
            if (p[i].style == ACC_STYLE_NUMERIC || p[i].style == ACC_STYLE_GROUND_TRUTH) {
                lx[nl] = log10(p[i].ns);
                lmean[nl] = lg(p[i].mean[w]);
                lmax[nl] = lg(p[i].max[w]);
                nl++;
            }
        plcol0(FIG_GREY);
        plwidth(1.0);
        plline(nl, lx, lmax);
        pllsty(2);
        plline(nl, lx, lmean);
        pllsty(1);
        for (int i = 0; i < n; i++) {
            double x[2] = {log10(p[i].ns), log10(p[i].ns)}, y[2] = {lg(p[i].mean[w]), lg(p[i].max[w])};
            plcol0(style_color(p[i].style));
            plline(2, x, y);
            plssym(0.0, 1.1);
            plstring(1, &x[0], &y[0], MARK_MEAN);
            plstring(1, &x[1], &y[1], MARK_MAX);
            if (p[i].label) {
                /* Under the mean marker, where the numeric labels cannot collide with each other;
                 * right-aligned near the right edge so that the label stays inside the frame. */
                const int right = x[0] > log10(xmax) - 0.8;
                plschr(0.0, SMALL_SCALE);
                plcol0(FIG_BLACK);
                plptex(x[0] + (right ? 0.1 : 0.0), y[0] - 0.28, 1.0, 0.0, right ? 1.0 : 0.5, p[i].label);
                plschr(0.0, TEXT_SCALE);
            }
        }
    }
    const legend_entry leg[] = {{"max over the samples", FIG_BLACK, 0, 0.0, MARK_MAX},
                                {"mean over the samples", FIG_BLACK, 0, 0.0, MARK_MEAN},
                                {"analytic (paper, eq. 26)", FIG_RED, 0, 0.0, MARK_MEAN},
                                {"analytic-pairs", FIG_ORANGE, 0, 0.0, MARK_MEAN},
                                {"path-group expansion", FIG_BLUE, 0, 0.0, MARK_MEAN},
                                {"numeric, N samples (label: N)", FIG_GREY, 1, 1.0, MARK_MEAN},
                                {"ΔE00 = 1", FIG_GREY, 3, 1.0, NULL}};
    bottom_legend(sizeof leg / sizeof leg[0], leg, sizeof leg / sizeof leg[0]);
    floor_note();
    if (fig_plot_end()) return cli_error("accuracy", "--plot-dir: %s", fig_plot_message()), -1;
    return 0;
}

int acc_plot_vs_theta(const char *path, const acc_plot_theta_data *d)
{
    double ymax = 1.0;
    for (long i = 0; i < (long)d->nmat * d->nmeth * 2 * d->ntheta; i++)
        if (d->max[i] == d->max[i]) ymax = fmax(ymax, d->max[i]);
    ymax = pow(10.0, ceil(log10(ymax * 1.2)));
    const double th0 = d->theta_deg[0], th1 = d->theta_deg[d->ntheta - 1] > th0 ? d->theta_deg[d->ntheta - 1] : th0 + 1;
    /* Without anti-aliased lines: the ten jagged curves per panel otherwise make a 430 KB PNG
     * (about 110 KB without), and at this size the lines still read well. */
    plsetopt("drvopt", "graphics_anti_aliasing=1");
    if (page_begin(path, 1500, 900)) return -1;
    const double left = 0.055, right = 0.99, gap = 0.05, pw = (right - left - (d->nmat - 1) * gap) / d->nmat;
    enum { MAXT = 4096 };
    double x[MAXT], y[MAXT];
    for (int w = 0; w < 2; w++)
        for (int m = 0; m < d->nmat; m++) {
            char title[160];
            snprintf(title, sizeof title, "%s, %s", d->mat_title[m], WHICH_TITLE[w]);
            const double vx0 = left + m * (pw + gap), vy0 = w ? 0.14 : 0.6;
            panel(vx0, vx0 + pw, vy0, vy0 + 0.33, th0, th1, DE_FLOOR, ymax, 0, "θ (degrees)",
                  m == 0 ? "ΔE00 against the reference" : "", title, NULL);
            /* Named in the legend: a label inside the panel sat on the axis ticks and the data. */
            jnd_line(th0, th1);
            if (d->mark_deg > 0.0 && d->mark_deg < th1) {
                double gx[2] = {d->mark_deg, d->mark_deg}, gy[2] = {log10(DE_FLOOR), log10(ymax)};
                plcol0(FIG_GREY);
                pllsty(3);
                plline(2, gx, gy);
                pllsty(1);
            }
            for (int k = 0; k < d->nmeth; k++)
                for (int stat = 0; stat < 2; stat++) {
                    const double *v = (stat ? d->mean : d->max) + ((long)(m * d->nmeth + k) * 2 + w) * d->ntheta;
                    /* NaN (no sample) breaks the curve. */
                    int nseg = 0;
                    plcol0(d->meth_color[k]);
                    plwidth(stat ? 1.0 : 1.6);
                    pllsty(stat ? 2 : 1);
                    for (int it = 0; it <= d->ntheta; it++) {
                        if (it < d->ntheta && v[it] == v[it] && nseg < MAXT) {
                            x[nseg] = d->theta_deg[it];
                            y[nseg++] = lg(v[it]);
                            continue;
                        }
                        if (nseg > 1) plline(nseg, x, y);
                        nseg = 0;
                    }
                    pllsty(1);
                    plwidth(1.0);
                }
        }
    /* The methods by colour, then the line styles and the guide. */
    enum { MAXL = 16 };
    legend_entry leg[MAXL];
    int nl = 0;
    for (int k = 0; k < d->nmeth && nl < MAXL - 4; k++) leg[nl++] = (legend_entry){d->meth_name[k], d->meth_color[k], 1, 1.6, NULL};
    const int split = nl; /* the line styles and guides on a second row */
    leg[nl++] = (legend_entry){"max over azimuths", FIG_BLACK, 1, 1.6, NULL};
    leg[nl++] = (legend_entry){"mean over azimuths", FIG_BLACK, 2, 1.0, NULL};
    char guide[64];
    snprintf(guide, sizeof guide, "θ = %g°", d->mark_deg);
    if (d->mark_deg > 0.0 && d->mark_deg < th1) leg[nl++] = (legend_entry){guide, FIG_GREY, 3, 1.0, NULL};
    leg[nl++] = (legend_entry){"ΔE00 = 1", FIG_GREY, 3, 1.0, NULL};
    bottom_legend(nl, leg, split);
    floor_note();
    if (fig_plot_end()) return cli_error("accuracy", "--plot-dir: %s", fig_plot_message()), -1;
    return 0;
}
