/* biref photoelastic: the fringe-order colour key (a Michel-Levy chart for white light) and the
 * scale bar, drawn on the picture with cairo. */
#include <cairo.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "photoelastic_ext.h"

static const char *const CMD = "photoelastic";

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* The key's range: whole fringe orders up to the picture's 99th percentile (at least 1; white
 * light at most 6, where the colours have faded to higher-order white). */
static int key_orders(const pe_ext_ctx *c)
{
    const int W = c->io->width, H = c->io->height;
    float *v = malloc((size_t)W * H * sizeof *v);
    if (!v) return 4;
    int top = 1;
    if (biref_pe_render_map(c->setup, c->field, BIREF_PE_MAP_FRINGE_ORDER, c->lambda_N, W, H, c->io->threads, v, NULL, 0) ==
        BIREF_OK) {
        size_t n = 0;
        for (size_t i = 0; i < (size_t)W * H; i++)
            if (isfinite(v[i])) v[n++] = v[i];
        if (n) {
            qsort(v, n, sizeof *v, cmp_float);
            top = (int)ceil(v[(size_t)(0.99 * (double)(n - 1))]);
        }
    }
    free(v);
    const int cap = c->setup->light == BIREF_PE_WHITE ? 6 : 30;
    return top < 1 ? 1 : top > cap ? cap : top;
}

/* The colour the picture shows at fringe order N (off the isoclinics: principal direction at 45
 * degrees to the polarizer), as 8-bit sRGB. */
static void key_colour(const pe_ext_ctx *c, double N, unsigned char rgb[3])
{
    const biref_pe_setup *s = c->setup;
    /* Uniaxial stress at 45 degrees to the polarizer, the brightest direction of a plane
     * polariscope (a circular one ignores it): sigma R R^T with R = (cos a, sin a). */
    const double sig = N * c->lambda_N * 1e-9 / (biref_pe_C_at(&s->material, c->lambda_N) * s->thickness);
    const double a = c->polarizer + 0.25 * M_PI;
    biref_pe_stress r = {sig * cos(a) * cos(a), sig * sin(a) * sin(a), sig * sin(a) * cos(a)};
    biref_pe_principal p;
    biref_pe_principal_of(&r, &p);
    double xyz[3];
    biref_pe_shade(s, c->sp, &p, xyz);
    for (int k = 0; k < 3; k++) xyz[k] *= s->light == BIREF_PE_MONO ? c->io->tint[k] : c->exposure;
    biref_xyz_to_srgb8(xyz, rgb);
}

/* 1, 2 or 5 times a power of ten, the largest not above x. */
static double nice_length(double x)
{
    double p = pow(10.0, floor(log10(x))), m = x / p;
    return (m >= 5 ? 5 : m >= 2 ? 2 : 1) * p;
}

static double draw_scale_bar(cairo_t *cr, const pe_ext_ctx *c, int W, int H)
{
    const double mm_per_px = (c->field->frame[1] - c->field->frame[0]) * 1e3 / W;
    const double L = nice_length(0.25 * W * mm_per_px), px = L / mm_per_px;
    const double fs = fmax(9.0, fmin(W, H) / 28.0), pad = 0.4 * fs;
    char label[32];
    snprintf(label, sizeof label, "%g mm", L);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    cairo_set_font_size(cr, fs);
    cairo_text_extents_t te;
    cairo_text_extents(cr, label, &te);
    const double bw = fmax(px, te.width) + 2 * pad, bh = fs + 0.6 * fs + 3 * pad;
    const double x0 = pad, y0 = H - pad - bh;
    /* A dark translucent plate keeps the bar readable on any fringe colour. */
    cairo_set_source_rgba(cr, 0, 0, 0, 0.55);
    cairo_rectangle(cr, x0, y0, bw, bh);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_move_to(cr, x0 + pad + 0.5 * (bw - 2 * pad - te.width) - te.x_bearing, y0 + pad - te.y_bearing);
    cairo_show_text(cr, label);
    const double by = y0 + bh - pad - 0.6 * fs, bx = x0 + pad + 0.5 * (bw - 2 * pad - px);
    cairo_rectangle(cr, bx, by, px, 0.6 * fs);
    cairo_fill(cr);
    return L;
}

static int draw_key(cairo_t *cr, const pe_ext_ctx *c, int W, int H, int kh)
{
    const int orders = key_orders(c);
    const double fs = fmax(10.0, kh / 6.0), margin = fmax(2 * fs, 0.06 * W);
    const double bx = margin, bw = W - 2 * margin, by = H + 0.2 * kh, bh = 0.3 * kh;
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_rectangle(cr, 0, H, W, kh);
    cairo_fill(cr);
    /* The bar: one column per pixel, the colour at that fringe order. */
    for (int i = 0; i < (int)ceil(bw); i++) {
        unsigned char rgb[3];
        key_colour(c, orders * (i + 0.5) / bw, rgb);
        cairo_set_source_rgb(cr, rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0);
        cairo_rectangle(cr, bx + i, by, 1.0, bh);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, bx - 0.5, by - 0.5, bw + 1, bh + 1);
    cairo_stroke(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, fs);
    const int step = orders > 15 ? 5 : orders > 8 ? 2 : 1;
    for (int n = 0; n <= orders; n += step) {
        const double x = bx + bw * n / orders;
        cairo_move_to(cr, x, by + bh);
        cairo_line_to(cr, x, by + bh + 0.3 * fs);
        cairo_stroke(cr);
        char t[16];
        snprintf(t, sizeof t, "%d", n);
        cairo_text_extents_t te;
        cairo_text_extents(cr, t, &te);
        cairo_move_to(cr, x - 0.5 * te.width - te.x_bearing, by + bh + 0.4 * fs - te.y_bearing);
        cairo_show_text(cr, t);
    }
    char cap[160];
    if (c->setup->light == BIREF_PE_WHITE)
        snprintf(cap, sizeof cap, "fringe order N = retardation / %.0f nm (white light)",
                 c->lambda_N);
    else
        snprintf(cap, sizeof cap, "fringe order N at %.0f nm", c->lambda_N);
    cairo_text_extents_t te;
    cairo_text_extents(cr, cap, &te);
    if (te.width > W - 2 * fs) {
        cairo_set_font_size(cr, fs * (W - 2 * fs) / te.width);
        cairo_text_extents(cr, cap, &te);
    }
    cairo_move_to(cr, 0.5 * (W - te.width) - te.x_bearing, H + kh - 0.25 * fs - (te.height + te.y_bearing));
    cairo_show_text(cr, cap);
    return orders;
}

int pe_ext_write_png(const pe_ext *e, const pe_ext_ctx *c, const unsigned char *rgb)
{
    char msg[512];
    const int W = c->io->width, H = c->io->height;
    pe_ext_json(e, c->root);
    if (!e->key && !e->scale_bar) {
        if (biref_png_write_rgb8(c->out, W, H, rgb, msg, sizeof msg) != BIREF_OK)
            return cli_error(CMD, "%s", msg), CLI_EXIT_FAIL;
        return CLI_EXIT_OK;
    }
    const int kh = e->key ? (int)fmin(160, fmax(64, W / 5.0)) : 0, TH = H + kh;
    cairo_surface_t *surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, TH);
    if (cairo_surface_status(surf) != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(surf);
        return cli_error(CMD, "cannot draw on a %d x %d picture", W, TH), CLI_EXIT_FAIL;
    }
    const int stride = cairo_image_surface_get_stride(surf);
    unsigned char *data = cairo_image_surface_get_data(surf);
    cairo_surface_flush(surf);
    for (int j = 0; j < H; j++) {
        uint32_t *row = (uint32_t *)(data + (size_t)j * stride);
        for (int i = 0; i < W; i++) {
            const unsigned char *p = rgb + 3 * ((size_t)j * W + i);
            row[i] = (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
        }
    }
    cairo_surface_mark_dirty(surf);
    cairo_t *cr = cairo_create(surf);
    const int orders = e->key ? draw_key(cr, c, W, H, kh) : 0;
    const double bar_mm = e->scale_bar ? draw_scale_bar(cr, c, W, H) : 0;
    if (c->root) {
        cJSON_AddNumberToObject(c->root, "png_height", TH);
        if (e->key) cJSON_AddNumberToObject(c->root, "key_fringe_orders", orders);
        if (e->scale_bar) cJSON_AddNumberToObject(c->root, "scale_bar_mm", bar_mm);
    }
    const int ok = cairo_status(cr) == CAIRO_STATUS_SUCCESS;
    cairo_destroy(cr);
    cairo_surface_flush(surf);
    unsigned char *out = ok ? malloc((size_t)W * TH * 3) : NULL;
    int rc = CLI_EXIT_OK;
    if (!out) {
        rc = CLI_EXIT_FAIL;
        cli_error(CMD, "cannot draw the key or scale bar");
    } else {
        for (int j = 0; j < TH; j++) {
            const uint32_t *row = (const uint32_t *)(data + (size_t)j * stride);
            for (int i = 0; i < W; i++) {
                unsigned char *p = out + 3 * ((size_t)j * W + i);
                p[0] = (unsigned char)(row[i] >> 16);
                p[1] = (unsigned char)(row[i] >> 8);
                p[2] = (unsigned char)row[i];
            }
        }
        if (biref_png_write_rgb8(c->out, W, TH, out, msg, sizeof msg) != BIREF_OK) {
            cli_error(CMD, "%s", msg);
            rc = CLI_EXIT_FAIL;
        }
    }
    free(out);
    cairo_surface_destroy(surf);
    return rc;
}
