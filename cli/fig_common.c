/* Helpers of the figures (fig_common.h). */
#include <stdint.h>
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

void fig_draw_rgb_tile(cairo_t *cr, const unsigned char *rgb, int w, int h, double x, double y, double scale)
{
    cairo_surface_t *img = surface_from_rgb(rgb, w, h);
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_scale(cr, scale, scale);
    cairo_set_source_surface(cr, img, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
    cairo_rectangle(cr, 0, 0, w, h);
    cairo_fill(cr);
    cairo_restore(cr);
    cairo_surface_destroy(img);
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

