/* The shared ΔE00 colour scale and its legend. */
#include "de_scale.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli_render.h"

static const double STOP[5] = {0.0, 1.0, 2.0, 4.0, CLI_DE_SCALE_MAX};
static const unsigned char COL[5][3] = {{0, 0, 0}, {0, 60, 255}, {0, 220, 60}, {255, 30, 0}, {255, 255, 255}};

void cli_de_color(double de, unsigned char rgb[3])
{
    if (!(de > 0)) de = 0;
    int i = 0;
    while (i < 3 && de > STOP[i + 1]) i++;
    double t = (de - STOP[i]) / (STOP[i + 1] - STOP[i]);
    if (t > 1) t = 1;
    for (int k = 0; k < 3; k++) rgb[k] = (unsigned char)lround(COL[i][k] + t * (COL[i + 1][k] - COL[i][k]));
}

void cli_de_legend(cairo_t *cr, double x, double y, double w, const char *title)
{
    cairo_save(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 11);
    cairo_text_extents_t te;
    cairo_text_extents(cr, title, &te);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_move_to(cr, x, y + 12);
    cairo_show_text(cr, title);
    /* The bar takes what the title leaves, at least 160 px. */
    double bx = x + te.x_advance + 10, bw = w - (bx - x) - 14;
    if (bw < 160) bx = x, bw = w - 14, y += 16;
    for (int i = 0; i < (int)bw; i++) {
        unsigned char c[3];
        cli_de_color(CLI_DE_SCALE_MAX * i / (bw - 1), c);
        cairo_set_source_rgb(cr, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
        cairo_rectangle(cr, bx + i, y + 2, 1, 12);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0.4, 0.4, 0.4);
    cairo_set_line_width(cr, 1);
    cairo_rectangle(cr, bx - 0.5, y + 1.5, bw + 1, 13);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    static const int ticks[] = {0, 1, 2, 4, 8};
    for (int i = 0; i < 5; i++) {
        char lab[8];
        snprintf(lab, sizeof lab, i == 4 ? "≥%d" : "%d", ticks[i]);
        cairo_text_extents(cr, lab, &te);
        double tx = bx + bw * ticks[i] / CLI_DE_SCALE_MAX - te.x_advance / 2;
        cairo_move_to(cr, tx, y + 26);
        cairo_show_text(cr, lab);
    }
    cairo_restore(cr);
}

/* The map with the scale's legend below it (the canvas at least wide enough for the legend). */
int cli_de_map_write(const char *cmd, const char *path, int w, int h, const unsigned char *map, const char *title)
{
    const int W = w > 320 ? w : 320, H = h + CLI_DE_LEGEND_HEIGHT + 8;
    cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, H);
    cairo_t *cr = cairo_create(s);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_surface_flush(s);
    unsigned char *data = cairo_image_surface_get_data(s);
    int stride = cairo_image_surface_get_stride(s);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint32_t *px = (uint32_t *)(data + (size_t)y * stride) + x;
            const unsigned char *c = map + 3 * ((size_t)y * w + x);
            *px = (uint32_t)c[0] << 16 | (uint32_t)c[1] << 8 | c[2];
        }
    cairo_surface_mark_dirty(s);
    cli_de_legend(cr, 6, h + 6, W - 6, title);
    cairo_surface_flush(s);
    /* Written through biref_png_write_rgb8 (atomic: temporary file, then rename). */
    unsigned char *rgb = malloc((size_t)W * H * 3);
    int rc = CLI_EXIT_OK;
    if (!rgb || cairo_status(cr) != CAIRO_STATUS_SUCCESS) {
        cli_error(cmd, "cannot draw the map's legend");
        rc = CLI_EXIT_FAIL;
    } else {
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                uint32_t v = ((const uint32_t *)(data + (size_t)y * stride))[x];
                unsigned char *o = rgb + 3 * ((size_t)y * W + x);
                o[0] = (unsigned char)(v >> 16), o[1] = (unsigned char)(v >> 8), o[2] = (unsigned char)v;
            }
        char msg[256];
        if (biref_png_write_rgb8(path, W, H, rgb, msg, sizeof msg) != BIREF_OK) {
            cli_error(cmd, "%s", msg);
            rc = CLI_EXIT_FAIL;
        }
    }
    free(rgb);
    cairo_destroy(cr);
    cairo_surface_destroy(s);
    return rc;
}
