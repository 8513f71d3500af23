/* PLplot helpers for `biref figure` (see fig_plot.h). */
#include "fig_plot.h"

#include <plplot.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "outfile.h"

/* PLplot draws one page at a time (it has global state), so one output is open at a time. */
static biref_outfile *current;
static char message[600];

const char *fig_plot_message(void) { return message; }

int fig_plot_begin(const char *path, int width, int height, int nx, int ny)
{
    /* Palette chosen for white paper: index 0 is the background, the rest are distinguishable
     * on screen and in greyscale print (PLplot's default cmap0 is meant for a black background). */
    static const PLINT r[] = {255, 0, 214, 31, 44, 255, 148, 23, 127, 140};
    static const PLINT g[] = {255, 0, 39, 119, 160, 127, 103, 190, 127, 86};
    static const PLINT b[] = {255, 0, 40, 180, 44, 14, 189, 207, 127, 75};
    current = biref_outfile_open(path, message, sizeof message);
    if (!current) return -1;
    /* PLplot closes the stream it is given at plend: it gets its own descriptor on our file. */
    FILE *f = biref_outfile_dup_stream(current);
    if (!f) {
        biref_outfile_close(current, 0, NULL, 0);
        current = NULL;
        snprintf(message, sizeof message, "%s: cannot write: out of file descriptors", path);
        return -1;
    }
    plsdev("pngcairo");
    plsfile(f);
    /* 90 dpi: PLplot's character sizes are physical, so this fixes text size relative to the
     * pixel size and keeps labels readable at ~1000 px wide images. */
    plspage(90.0, 90.0, width, height, 0, 0);
    plscmap0(r, g, b, (PLINT)(sizeof r / sizeof r[0]));
    plssub(nx, ny);
    plinit();
    plfontld(1);
    return 0;
}

int fig_plot_end(void)
{
    plend();
    if (!current) return -1;
    /* pngcairo reports no write error: an empty regular file is the sign of one. */
    struct stat st;
    int ok = fstat(fileno(biref_outfile_stream(current)), &st) == 0 && (!S_ISREG(st.st_mode) || st.st_size > 0);
    biref_status s = biref_outfile_close(current, ok, message, sizeof message);
    current = NULL;
    return s == BIREF_OK ? 0 : -1;
}

void fig_plot_panel(double xmin, double xmax, double ymin, double ymax, const char *xlabel, const char *ylabel,
                    const char *title)
{
    pladv(0);
    plschr(0.0, 0.9);
    plvsta();
    plwind(xmin, xmax, ymin, ymax);
    plcol0(FIG_BLACK);
    plwidth(1.0);
    plbox("bcgnst", 0.0, 0, "bcgnstv", 0.0, 0);
    /* Titles may have two lines ("a\nb"): PLplot's pllab draws one, so place both with plmtex. */
    const char *nl = strchr(title, '\n');
    pllab(xlabel, ylabel, "");
    if (nl) {
        char first[256];
        snprintf(first, sizeof first, "%.*s", (int)(nl - title), title);
        plmtex("t", 2.6, 0.5, 0.5, first);
        plmtex("t", 1.1, 0.5, 0.5, nl + 1);
    } else {
        plmtex("t", 1.5, 0.5, 0.5, title);
    }
}

void fig_plot_line(int n, const double *x, const double *y, int color, double width)
{
    plcol0(color);
    plwidth(width);
    plline(n, x, y);
    plwidth(1.0);
    plcol0(FIG_BLACK);
}

void fig_plot_legend(int n, const char *const *labels, const int *colors, const double *widths, int corner)
{
    enum { MAXL = 16 };
    if (n > MAXL) n = MAXL;
    PLINT opt[MAXL], lcol[MAXL], lsty[MAXL], tcol[MAXL];
    PLFLT lw[MAXL];
    for (int i = 0; i < n; i++) {
        opt[i] = PL_LEGEND_LINE;
        lcol[i] = colors[i];
        tcol[i] = FIG_BLACK;
        lsty[i] = 1;
        lw[i] = widths ? widths[i] : 1.5;
    }
    PLFLT w, h;
    plschr(0.0, 0.7);
    pllegend(&w, &h, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX,
             PL_POSITION_INSIDE | ((corner & FIG_BOTTOM) ? PL_POSITION_BOTTOM : PL_POSITION_TOP) |
                 ((corner & FIG_LEFT) ? PL_POSITION_LEFT : PL_POSITION_RIGHT), 0.02, 0.02,
             0.08, 0, FIG_BLACK, 1, n, 1, n, opt, 1.0, 1.0, 1.8, 0.0, tcol, labels, NULL, NULL, NULL, NULL, lcol, lsty,
             lw, NULL, NULL, NULL, NULL);
    plschr(0.0, 0.9);
}

void fig_plot_text(double x, double y, const char *text)
{
    plschr(0.0, 0.7);
    plcol0(FIG_BLACK);
    plptex(x, y, 1.0, 0.0, -0.2, text);
    plschr(0.0, 0.9);
}
