/* Helpers of the figures (fig_common.h). */
#include <stdio.h>

#include "cli_common.h"
#include "fig_common.h"
#include "fig_plot.h"

void fig_out_path(const fig_ctx *c, const char *name, char *buf, size_t len)
{
    snprintf(buf, len, "%s/%s", c->dir, name);
}

/* Output files through io/outfile.h: in place only once complete. */
biref_outfile *fig_open_out(const char *path)
{
    char msg[600];
    biref_outfile *o = biref_outfile_open(path, msg, sizeof msg);
    if (!o) cli_error(FIG_CMD, "%s", msg);
    return o;
}

biref_outfile *fig_open_csv(const fig_ctx *c, const char *name, char *path, size_t len)
{
    fig_out_path(c, name, path, len);
    return fig_open_out(path);
}

int fig_close_csv(biref_outfile *o, const char *path)
{
    char msg[600];
    if (biref_outfile_close(o, 1, msg, sizeof msg) != BIREF_OK) return cli_error(FIG_CMD, "%s", msg), -1;
    printf("wrote %s\n", path);
    return 0;
}

void fig_discard(biref_outfile *o) { biref_outfile_close(o, 0, NULL, 0); }

int fig_begin(const char *path, int width, int height, int nx, int ny)
{
    if (fig_plot_begin(path, width, height, nx, ny)) return cli_error(FIG_CMD, "%s", fig_plot_message()), -1;
    return 0;
}

int fig_end(const char *path)
{
    if (fig_plot_end()) return cli_error(FIG_CMD, "%s", fig_plot_message()), -1;
    printf("wrote %s\n", path);
    return 0;
}

cairo_status_t fig_write_stream(void *closure, const unsigned char *data, unsigned int length)
{
    return fwrite(data, 1, length, closure) == length ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

void fig_chromaticity(const double xyz[3], double *x, double *y)
{
    double s = xyz[0] + xyz[1] + xyz[2];
    *x = s > 0 ? xyz[0] / s : NAN;
    *y = s > 0 ? xyz[1] / s : NAN;
}

int fig_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}
