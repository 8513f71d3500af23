/* The shared ΔE00 colour scale and its legend. */
#include "de_scale.h"

#include <math.h>
#include <stdio.h>

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
