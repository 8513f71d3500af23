/* biref figure dispersion: the error of ignoring dispersion. Five crystal plates seen over
 * θ = 0–70°, each integrated exactly (16384-sample ground truth) twice: with the material's n(λ)
 * at every sample, and with the indices fixed at their 550 nm values; the CSV files hold every
 * colour and ΔE00. The picture shows a wedge of each plate (0 to its thickness) both ways, side
 * by side, with the ΔE00 map between them (docs/MATERIALS.md, docs/ACCURACY.md). */
#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "de_scale.h"
#include "fig_common.h"

/* The plates: materials and thicknesses where dispersion matters in different ways (a strong
 * group birefringence in a thin plate, a weak one in a thick plate). */
static const struct {
    const char *material;
    double d_nm;
    const char *label;
} PLATES[] = {
    {"calcite", 50e3, "calcite 50 µm"},   {"quartz", 200e3, "quartz 200 µm"},
    {"rutile", 10e3, "rutile 10 µm"},     {"linbo3", 20e3, "LiNbO3 20 µm"},
    {"sapphire", 1e6, "sapphire 1 mm"},
};
enum { NPLATE = sizeof PLATES / sizeof PLATES[0] };

/* The optic axes: in the surface at 45° to the plane of incidence (a plate cut parallel to the
 * axis, where crossed s/p filters show the most colour), and tilted out of the surface. */
static const double AXES[][3] = {{0.70710678118654752, 0.0, 0.70710678118654752}, {0.5, 0.70710678118654752, 0.5}};
static const char *const AXIS_NAMES[] = {"in-plane 45", "tilted"};
enum { NAXIS = 2 };

/* The lights: incident s/p fractions and the analyzer's s/p mask. */
static const struct {
    const char *name;
    double w_in[2], mask[2];
} LIGHTS[] = {
    {"s", {1, 0}, {1, 1}},
    {"p", {0, 1}, {1, 1}},
    {"75% s + 25% p", {0.75, 0.25}, {1, 1}},
    {"crossed s/p", {1, 0}, {0, 1}},
};
enum { NLIGHT = 4, CROSSED = 3 };

typedef struct {
    double xyz[2][NLIGHT][2][3]; /* [fixed, dispersive][light][T, R] */
    double de[NLIGHT][2];
    int failed;
} cell;

/* One plate of thickness d_nm, axis and angle: both integrations, every light. */
static void compute_cell(const fig_ctx *c, int p, int a, double d_nm, double theta_deg, cell *out)
{
    const biref_material *m = biref_material_find(PLATES[p].material);
    biref_slab geo = {0, 0, {AXES[a][0], AXES[a][1], AXES[a][2]}, d_nm, 1.0};
    double n550[2];
    biref_spectrum x[2];
    biref_slab fixed;
    biref_slab_state st;
    out->failed = !m || biref_material_indices(m, 550.0, n550, NULL) != BIREF_OK ||
                  biref_material_slab_at(m, &geo, 550.0, &fixed) != BIREF_OK ||
                  biref_slab_prepare(&fixed, fig_deg2rad(theta_deg), &st) != BIREF_OK ||
                  biref_spectrum_numeric_dispersive(c->gt, m, &geo, fig_deg2rad(theta_deg), &x[1]) != BIREF_OK;
    if (out->failed) return;
    biref_spectrum_numeric(c->gt, &st, &x[0]);
    for (int k = 0; k < 2; k++)
        for (int l = 0; l < NLIGHT; l++) {
            biref_spectrum_mix(x[k].T, LIGHTS[l].w_in, LIGHTS[l].mask, out->xyz[k][l][0]);
            biref_spectrum_mix(x[k].R, LIGHTS[l].w_in, LIGHTS[l].mask, out->xyz[k][l][1]);
        }
    for (int l = 0; l < NLIGHT; l++)
        for (int s = 0; s < 2; s++) out->de[l][s] = biref_delta_e00_xyz(out->xyz[0][l][s], out->xyz[1][l][s]);
}

static int write_cells(const fig_ctx *c, const cell *cells, int nth, const double *th)
{
    char path[4096];
    biref_outfile *out = fig_open_csv(c, "dispersion.csv", path, sizeof path);
    if (!out) return -1;
    FILE *f = biref_outfile_stream(out);
    fprintf(f, "plate,axis,theta_deg,light,side,X_fixed550,Y_fixed550,Z_fixed550,X_dispersive,Y_dispersive,"
               "Z_dispersive,dE00\n");
    for (int p = 0; p < NPLATE; p++)
        for (int a = 0; a < NAXIS; a++)
            for (int t = 0; t < nth; t++) {
                const cell *e = &cells[((size_t)p * NAXIS + a) * nth + t];
                for (int l = 0; l < NLIGHT; l++)
                    for (int s = 0; s < 2; s++)
                        fprintf(f, "%s,%s,%g,%s,%s,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.4f\n", PLATES[p].label,
                                AXIS_NAMES[a], th[t], LIGHTS[l].name, s ? "R" : "T", e->xyz[0][l][s][0],
                                e->xyz[0][l][s][1], e->xyz[0][l][s][2], e->xyz[1][l][s][0], e->xyz[1][l][s][1],
                                e->xyz[1][l][s][2], e->de[l][s]);
            }
    if (fig_close_csv(out, path)) return -1;
    /* The summary: per plate, light and side, over both axes and every angle. */
    out = fig_open_csv(c, "dispersion_summary.csv", path, sizeof path);
    if (!out) return -1;
    f = biref_outfile_stream(out);
    fprintf(f, "plate,light,side,dE00_mean,dE00_max\n");
    for (int p = 0; p < NPLATE; p++)
        for (int l = 0; l < NLIGHT; l++)
            for (int s = 0; s < 2; s++) {
                double sum = 0, mx = 0;
                for (int k = 0; k < NAXIS * nth; k++) {
                    const double v = cells[(size_t)p * NAXIS * nth + k].de[l][s];
                    sum += v;
                    mx = fmax(mx, v);
                }
                fprintf(f, "%s,%s,%s,%.3f,%.3f\n", PLATES[p].label, LIGHTS[l].name, s ? "R" : "T",
                        sum / (NAXIS * nth), mx);
            }
    return fig_close_csv(out, path);
}

/* A wedge of each plate, 0 to its thickness, at normal incidence between crossed filters, the
 * axis in the surface at 45°: strips of the fixed-index colours, the n(λ) colours and ΔE00. */
static int draw(const fig_ctx *c, const cell *cells, int nth)
{
    const int scale = c->quick ? 16 : 3, sh = 22, gap = 10, left = 120, head = 40;
    const int sw = nth * scale, rowh = 3 * sh + 2 * 3 + gap + 14;
    const int W = left + sw + gap, H = head + NPLATE * rowh + CLI_DE_LEGEND_HEIGHT + 2 * gap;
    unsigned char *rgb = malloc((size_t)nth * 3 * 3);
    if (!rgb) return cli_error(FIG_CMD, "out of memory"), -1;
    cairo_surface_t *surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, H);
    cairo_t *cr = cairo_create(surf);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 13);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_move_to(cr, gap, 18);
    cairo_show_text(cr, "Wedges from 0 (left) to the plate's thickness, normal incidence, crossed s/p filters,");
    cairo_move_to(cr, gap, 34);
    cairo_show_text(cr, "optic axis in the surface at 45°: indices fixed at 550 nm / n(λ) at every sample / ΔE00");
    static const char *const ROW[3] = {"n at 550 nm", "n(λ)", "ΔE00"};
    for (int p = 0; p < NPLATE; p++) {
        const double y0 = head + p * rowh;
        cairo_set_font_size(cr, 13);
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_move_to(cr, gap, y0 + 12);
        cairo_show_text(cr, PLATES[p].label);
        for (int t = 0; t < nth; t++) {
            const cell *e = &cells[(size_t)p * nth + t];
            biref_xyz_to_srgb8(e->xyz[0][CROSSED][0], rgb + 3 * t);
            biref_xyz_to_srgb8(e->xyz[1][CROSSED][0], rgb + 3 * (nth + t));
            cli_de_color(e->de[CROSSED][0], rgb + 3 * (2 * nth + t));
        }
        cairo_set_font_size(cr, 11);
        for (int r = 0; r < 3; r++) {
            const double y = y0 + 16 + r * (sh + 3);
            cairo_set_source_rgb(cr, 0, 0, 0);
            cairo_move_to(cr, gap + 8, y + 15);
            cairo_show_text(cr, ROW[r]);
            /* one row of nth pixels, stretched to the strip's height */
            cairo_save(cr);
            cairo_translate(cr, left, y);
            cairo_scale(cr, 1.0, (double)sh / scale);
            fig_draw_rgb_tile(cr, rgb + (size_t)r * nth * 3, nth, 1, 0, 0, scale);
            cairo_restore(cr);
        }
    }
    cli_de_legend(cr, gap, head + NPLATE * rowh + gap, 640, "ΔE00 between fixed and dispersive indices:");
    free(rgb);
    char path[4096];
    fig_out_path(c, "dispersion.png", path, sizeof path);
    cairo_surface_flush(surf);
    biref_outfile *png = fig_open_out(path);
    cairo_status_t cs = png ? cairo_surface_write_to_png_stream(surf, fig_write_stream, biref_outfile_stream(png))
                            : CAIRO_STATUS_WRITE_ERROR;
    cairo_destroy(cr);
    cairo_surface_destroy(surf);
    if (!png) return -1;
    if (cs != CAIRO_STATUS_SUCCESS) {
        fig_discard(png);
        return cli_error(FIG_CMD, "cannot write %s: %s", path, cairo_status_to_string(cs)), -1;
    }
    return fig_close_csv(png, path);
}

int fig_dispersion(const fig_ctx *c)
{
    const int nth = c->quick ? 15 : 71; /* θ = 0..70° */
    const size_t n = (size_t)NPLATE * NAXIS * nth;
    cell *cells = calloc(n, sizeof *cells);
    double *th = malloc(sizeof(double) * (size_t)nth);
    if (!cells || !th) return free(cells), free(th), cli_error(FIG_CMD, "out of memory"), CLI_EXIT_FAIL;
    for (int t = 0; t < nth; t++) th[t] = 70.0 * t / (nth - 1);
    long failed = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : failed)
    for (long k = 0; k < (long)n; k++) {
        const int p = (int)(k / (NAXIS * nth)), a = (int)(k / nth % NAXIS), t = (int)(k % nth);
        compute_cell(c, p, a, PLATES[p].d_nm, th[t], &cells[k]);
        failed += cells[k].failed;
    }
    /* The wedges of the picture. */
    const int nw = c->quick ? 40 : 200;
    cell *wedge = calloc((size_t)NPLATE * nw, sizeof *wedge);
    if (!wedge) return free(cells), free(th), cli_error(FIG_CMD, "out of memory"), CLI_EXIT_FAIL;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : failed)
    for (long k = 0; k < (long)NPLATE * nw; k++) {
        const int p = (int)(k / nw), i = (int)(k % nw);
        compute_cell(c, p, 0, PLATES[p].d_nm * (i + 0.5) / nw, 0.0, &wedge[k]);
        failed += wedge[k].failed;
    }
    int rc = CLI_EXIT_OK;
    if (failed) {
        cli_error(FIG_CMD, "dispersion: %ld integrations failed", failed);
        rc = CLI_EXIT_FAIL;
    } else if (write_cells(c, cells, nth, th) || draw(c, wedge, nw))
        rc = CLI_EXIT_FAIL;
    free(wedge);
    free(cells);
    free(th);
    return rc;
}
