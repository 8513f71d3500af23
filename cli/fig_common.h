/* Shared by the figures of `biref figure` (cmd_figure.c, fig_spectral.c): the run's context and
 * the helpers that write CSV files and plots. */
#ifndef BIREF_CLI_FIG_COMMON_H
#define BIREF_CLI_FIG_COMMON_H

#include <cairo.h>
#include <math.h>
#include <stddef.h>

/* The figures compare the methods one by one (numeric plans, biref_spectrum_*): unstable API. */
#ifndef BIREF_EXPERIMENTAL_API
#define BIREF_EXPERIMENTAL_API
#endif
#include "biref/biref.h"
#include "biref/experimental.h"
#include "outfile.h"

#define FIG_CMD "figure"

typedef struct {
    const char *dir;
    int quick;
    int threads; /* 0 = OpenMP default */
    biref_spectral *sp;
    biref_numeric_plan *gt; /* 16384-sample ground-truth plan */
} fig_ctx;

/* DIR/NAME. */
void fig_out_path(const fig_ctx *c, const char *name, char *buf, size_t len);
/* Output files through io/outfile.h: in place only once complete. NULL after an error line. */
biref_outfile *fig_open_out(const char *path);
biref_outfile *fig_open_csv(const fig_ctx *c, const char *name, char *path, size_t len);
/* Commits the file and says so on stdout; -1 after an error line. */
int fig_close_csv(biref_outfile *o, const char *path);
void fig_discard(biref_outfile *o);
/* A PLplot page (fig_plot.h) begun and ended with one error line on failure. */
int fig_begin(const char *path, int width, int height, int nx, int ny);
int fig_end(const char *path);
/* 8-bit RGB pixels (w x h) drawn at (x, y) enlarged by scale, nearest neighbour: enlarged pixels
 * stay pixels, so aliasing is shown, not blurred. */
void fig_draw_rgb_tile(cairo_t *cr, const unsigned char *rgb, int w, int h, double x, double y, double scale);

/* cairo's PNG stream writer into a FILE *. */
cairo_status_t fig_write_stream(void *closure, const unsigned char *data, unsigned int length);
static inline double fig_deg2rad(double d) { return d * M_PI / 180.0; }
void fig_chromaticity(const double xyz[3], double *x, double *y);

/* The figures of fig_spectral.c (slab colours, no rendering). Each returns a CLI exit code. */
int fig5(const fig_ctx *c);
int fig6c(const fig_ctx *c);
int fig7(const fig_ctx *c);
/* The error of ignoring dispersion (fig_dispersion.c). */
int fig_dispersion(const fig_ctx *c);

#endif
