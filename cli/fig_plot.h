/* Thin helpers around PLplot for `biref figure`: one PNG per call sequence, white background,
 * a fixed readable palette, curves with a legend. Not thread-safe (PLplot has global state). */
#ifndef BIREF_CLI_FIG_PLOT_H
#define BIREF_CLI_FIG_PLOT_H

/* Palette indices (cmap0) set by fig_plot_begin. */
enum { FIG_BLACK = 1, FIG_RED, FIG_BLUE, FIG_GREEN, FIG_ORANGE, FIG_PURPLE, FIG_CYAN, FIG_GREY, FIG_BROWN };

/* Opens a PNG (pngcairo device) of width x height pixels divided into nx x ny panels, written
 * as io/outfile.h writes files. Returns -1 (message in fig_plot_message()) if it cannot be
 * opened; then draw nothing. */
int fig_plot_begin(const char *path, int width, int height, int nx, int ny);
/* Finishes the page and puts the file in place; -1 (message in fig_plot_message()) on failure. */
int fig_plot_end(void);
const char *fig_plot_message(void);

/* Starts the next panel with axes and labels (UTF-8 text). */
void fig_plot_panel(double xmin, double xmax, double ymin, double ymax, const char *xlabel, const char *ylabel,
                    const char *title);

/* A polyline in palette colour `color` and line width `width` (1 = thin). */
void fig_plot_line(int n, const double *x, const double *y, int color, double width);

/* A legend inside the panel; corner = 0 (top right) or an OR of FIG_LEFT, FIG_BOTTOM. */
enum { FIG_LEFT = 1, FIG_BOTTOM = 2 };
void fig_plot_legend(int n, const char *const *labels, const int *colors, const double *widths, int corner);

/* A small label just right of the point (x, y) in world coordinates. */
void fig_plot_text(double x, double y, const char *text);

#endif
