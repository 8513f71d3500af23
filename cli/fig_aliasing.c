/* biref figure aliasing: for each scene made to alias (and the photoelastic disk near a load),
 * (a) one sample per pixel with point look-ups, (b) one sample per pixel prefiltered, (c) 4x4 super-sampled point look-ups, each
 * against a 32x32 super-sampled reference of the same rows, with their ΔE00 maps and costs. */
#include "fig_aliasing.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "biref/biref.h"
#include "cli_common.h"
#include "de_scale.h"
#include "fig_common.h"

static const char *const CMD = "figure";

typedef struct {
    const char *label, *file; /* file relative to the scenes directory */
    int width, height;        /* full frame */
    double y0, y1;            /* the measured rows, as fractions of the height */
    int shown;                /* in aliasing.png (a band of a few rows is only in the CSV) */
    int pe;                   /* 0: the scene file; else the photoelastic disk in this light (render_pe) */
} alias_case;

/* Crops of rows (the reference costs 1024 samples per pixel): fig. 9c as framed for the paper's
 * figure at a small size, through its rings; the 3.5 mm slab at a grazing view, below its far
 * edge (geometric edges are super-sampling's job, not the prefilter's); fig. 9c at full HD, a
 * band of rows through the rings. */
static const alias_case CASES[] = {
    {"fig. 9c, 320x180 (rows 60-119)", "fig9c.json", 320, 180, 60.0 / 180, 120.0 / 180, 1, 0},
    {"thick slab, grazing, 320x180 (rows 100-159)", "aliasing/thick_grazing.json", 320, 180, 100.0 / 180, 160.0 / 180, 1, 0},
    {"fig. 9c, 1920x1080 (rows 440-447)", "fig9c.json", 1920, 1080, 440.0 / 1080, 448.0 / 1080, 0, 0},
    {"photoelastic disk below a load, white light (128x128 of 512x512)", NULL, 128, 128, 0.0, 1.0, 1,
     1 + BIREF_PE_WHITE},
    {"photoelastic disk below a load, 589 nm (128x128 of 512x512)", NULL, 128, 128, 0.0, 1.0, 1, 1 + BIREF_PE_MONO},
};
enum { NCASES = 5, NVAR = 4, REF = 3 };

typedef struct {
    const char *name;
    biref_antialias aa;
    int K; /* 0: the reference's */
} variant;

static const variant VARIANTS[NVAR] = {{"(a) 1 spp, point look-ups", BIREF_ANTIALIAS_NONE, 1},
                                       {"(b) 1 spp, prefiltered", BIREF_ANTIALIAS_PREFILTER, 1},
                                       {"(c) 4x4 spp, point look-ups", BIREF_ANTIALIAS_NONE, 4},
                                       {"reference", BIREF_ANTIALIAS_NONE, 0}};

static double render_rows(const biref_spectral *sp, const biref_scene *sc, biref_antialias aa, int K, int threads, int y0, int y1, float *xyz,
                          const char *label)
{
    biref_render_options opt;
    biref_render_options_default(&opt);
    opt.antialias = aa;
    opt.supersample = K;
    opt.threads = threads;
    biref_renderer *r = NULL;
    char msg[256];
    if (biref_renderer_create(sp, sc, &opt, &r, msg, sizeof msg) != BIREF_OK) return cli_error(CMD, "%s", msg), -1.0;
    biref_progress_bar bar;
    char what[48];
    snprintf(what, sizeof what, "figure %s", label);
    biref_progress_bar_init(&bar, stderr, 1, what);
    double t0 = biref_wall_seconds();
    biref_status s = biref_renderer_render(r, y0, y1, 1, xyz, biref_progress_bar_update, &bar, NULL);
    double t = biref_wall_seconds() - t0;
    biref_progress_bar_finish(&bar);
    biref_renderer_destroy(r);
    if (s != BIREF_OK) return cli_error(CMD, "render failed: %s", biref_status_string(s)), -1.0;
    return t;
}

/* The disk of `biref photoelastic --preset disk` with its defaults (polycarbonate, radius 25 mm,
 * 6 mm thick, 500 N, dark-field circular polariscope) at the pixel pitch of its default 512-pixel
 * picture (pitch times div), the W x H window whose top edge runs 1 mm below the upper load point,
 * where the fringes crowd. */
static double render_pe(const biref_spectral *sp, biref_pe_light_kind light, biref_antialias aa, int K, int threads, int W, int H, int div,
                        float *xyz)
{
    biref_pe_setup s;
    memset(&s, 0, sizeof s);
    (void)biref_pe_material_preset("polycarbonate", &s.material);
    s.thickness = 6e-3;
    s.eta_i = 1.0;
    s.light = light;
    s.lambda_nm = 589.0;
    biref_pe_polariscope_make(BIREF_PE_CIRCULAR, BIREF_PE_DARK, 0.0, &s.pol);
    biref_pe_field f;
    char msg[256];
    if (biref_pe_field_disk(&f, 25e-3, s.thickness, 500.0, msg, sizeof msg) != BIREF_OK)
        return cli_error(CMD, "disk: %s", msg), -1.0;
    const double pitch = div * (f.frame[1] - f.frame[0]) / 512.0, top = 25e-3 - 1e-3;
    f.frame[0] = -0.5 * W * pitch, f.frame[1] = 0.5 * W * pitch;
    f.frame[2] = top - H * pitch, f.frame[3] = top;
    biref_pe_image_opts io = {.width = W, .height = H, .supersample = K, .threads = threads, .tint = {1, 1, 1}, .tilt = 0.0};
    fprintf(stderr, "biref figure: aliasing: photoelastic %dx%d, %dx%d samples\n", W, H, K, K);
    double t0 = biref_wall_seconds();
    biref_status st = aa == BIREF_ANTIALIAS_PREFILTER ? biref_pe_render_prefiltered(&s, sp, &f, &io, xyz, msg, sizeof msg)
                                                      : biref_pe_render(&s, sp, &f, &io, xyz, msg, sizeof msg);
    double t = biref_wall_seconds() - t0;
    if (st != BIREF_OK) return cli_error(CMD, "photoelastic picture: %s", msg), -1.0;
    return t;
}

typedef struct {
    int w, h; /* crop */
    unsigned char *rgb[NVAR], *map[NVAR];
    double mean[NVAR], p95[NVAR], max[NVAR], secs[NVAR];
} case_result;

static int run_case(const biref_spectral *sp, const alias_case *ac, const char *scenes, int quick, int threads, FILE *csv, case_result *res)
{
    char path[4096], msg[256];
    if (!ac->pe) snprintf(path, sizeof path, "%s/%s", scenes, ac->file);
    biref_scene sc;
    if (!ac->pe && biref_scene_load(path, &sc, msg, sizeof msg) != BIREF_OK)
        return cli_error(CMD, "%s: %s", path, msg), 2;
    const int div = quick ? 4 : 1, W = ac->width / div, H = ac->height / div;
    sc.camera.width = W;
    sc.camera.height = H;
    int y0 = (int)lround(ac->y0 * H), y1 = (int)lround(ac->y1 * H);
    if (y1 <= y0) y1 = y0 + 1;
    const int K_ref = quick ? 8 : 32;
    const size_t npx = (size_t)W * (y1 - y0);
    float *xyz[NVAR];
    double *sorted = malloc(npx * sizeof *sorted);
    int rc = sorted ? 0 : 1;
    for (int v = 0; v < NVAR; v++) {
        xyz[v] = calloc((size_t)W * H * 3, sizeof(float));
        res->rgb[v] = malloc(npx * 3);
        res->map[v] = malloc(npx * 3);
        if (!xyz[v] || !res->rgb[v] || !res->map[v]) rc = 1;
    }
    res->w = W, res->h = y1 - y0;
    for (int v = 0; v < NVAR && !rc; v++) {
        int K = VARIANTS[v].K ? VARIANTS[v].K : K_ref;
        fprintf(stderr, "biref figure: aliasing: %s: %s (%dx%d samples)\n", ac->label, VARIANTS[v].name, K, K);
        res->secs[v] = ac->pe ? render_pe(sp, (biref_pe_light_kind)(ac->pe - 1), VARIANTS[v].aa, K, threads, W, H, div, xyz[v])
                              : render_rows(sp, &sc, VARIANTS[v].aa, K, threads, y0, y1, xyz[v], "aliasing");
        if (res->secs[v] < 0) rc = 1;
        else biref_xyz_image_to_srgb8(xyz[v] + (size_t)3 * W * y0, npx, res->rgb[v]);
    }
    const float *ref = rc ? NULL : xyz[REF] + (size_t)3 * W * y0;
    for (int v = 0; v < NVAR && !rc; v++) {
        const float *im = xyz[v] + (size_t)3 * W * y0;
        double sum = 0.0, mx = 0.0;
        for (size_t i = 0; i < npx; i++) {
            double a[3] = {im[3 * i], im[3 * i + 1], im[3 * i + 2]}, b[3] = {ref[3 * i], ref[3 * i + 1], ref[3 * i + 2]};
            double e = biref_delta_e00_xyz(a, b);
            if (!isfinite(e)) e = 0.0;
            sorted[i] = e, sum += e, mx = fmax(mx, e);
            cli_de_color(e, res->map[v] + 3 * i);
        }
        qsort(sorted, npx, sizeof *sorted, cli_cmp_double);
        res->mean[v] = sum / (double)npx;
        res->p95[v] = sorted[(size_t)floor(0.95 * (double)(npx - 1))];
        res->max[v] = mx;
        fprintf(csv, "\"%s\",%s,%d,%d,%d,%d,%d,%.4f,%.4f,%.4f,%.4f,%.3f\n", ac->label,
                v == 0 ? "plain_1spp" : v == 1 ? "prefilter_1spp" : v == 2 ? "plain_4x4" : "reference", W, H, y0, y1,
                VARIANTS[v].K ? VARIANTS[v].K : K_ref, res->mean[v], res->p95[v], res->max[v], res->secs[v],
                res->secs[v] / res->secs[0]);
    }
    for (int v = 0; v < NVAR; v++) free(xyz[v]);
    free(sorted);
    return rc;
}

int fig_aliasing(const biref_spectral *sp, const char *dir, const char *scenes, int quick, int threads)
{
    char csv_path[4096], png_path[4096];
    snprintf(csv_path, sizeof csv_path, "%s/aliasing.csv", dir);
    snprintf(png_path, sizeof png_path, "%s/aliasing.png", dir);
    biref_outfile *csv_out = fig_open_out(csv_path);
    if (!csv_out) return 1;
    FILE *csv = biref_outfile_stream(csv_out);
    fprintf(csv, "case,variant,width,height,row_begin,row_end,samples_per_axis,dE00_mean,dE00_p95,dE00_max,"
                 "render_seconds,cost_vs_plain\n");
    case_result res[NCASES];
    memset(res, 0, sizeof res);
    int rc = 0, n = 0;
    for (int i = 0; i < NCASES && !rc; i++, n++) rc = run_case(sp, &CASES[i], scenes, quick, threads, csv, &res[i]);
    if (rc) fig_discard(csv_out);
    else if (fig_close_csv(csv_out, csv_path)) rc = 1;
    if (!rc) {
        /* One block per case: titles, the four crops, the three ΔE00 maps against the reference. */
        const double tw = 300, gap = 8, head = 34;
        double H = gap + CLI_DE_LEGEND_HEIGHT + 24;
        for (int i = 0; i < NCASES; i++)
            if (CASES[i].shown) H += 22 + head + 2 * (tw * res[i].h / res[i].w + gap);
        const int Wimg = (int)(NVAR * (tw + gap) + gap);
        cairo_surface_t *out = cairo_image_surface_create(CAIRO_FORMAT_RGB24, Wimg, (int)H);
        cairo_t *cr = cairo_create(out);
        cairo_set_source_rgb(cr, 1, 1, 1);
        cairo_paint(cr);
        cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
        double y = gap;
        for (int i = 0; i < NCASES; i++) {
            const case_result *r = &res[i];
            if (!CASES[i].shown) continue;
            double th = tw * r->h / r->w;
            cairo_set_source_rgb(cr, 0, 0, 0);
            cairo_set_font_size(cr, 14);
            cairo_move_to(cr, gap, y + 14);
            cairo_show_text(cr, CASES[i].label);
            y += 22;
            cairo_set_font_size(cr, 11);
            for (int v = 0; v < NVAR; v++) {
                double x = gap + v * (tw + gap);
                char line[128];
                cairo_set_source_rgb(cr, 0, 0, 0);
                cairo_move_to(cr, x, y + 12);
                cairo_show_text(cr, v == REF ? (quick ? "reference (8x8 spp)" : "reference (32x32 spp)") : VARIANTS[v].name);
                if (v == REF)
                    snprintf(line, sizeof line, "cost %.0fx plain", r->secs[v] / r->secs[0]);
                else
                    snprintf(line, sizeof line, "mean ΔE00 %.3f, cost %.2fx plain", r->mean[v], r->secs[v] / r->secs[0]);
                cairo_move_to(cr, x, y + 27);
                cairo_show_text(cr, line);
                fig_draw_rgb_tile(cr, r->rgb[v], r->w, r->h, x, y + head, tw / r->w);
                if (v != REF) fig_draw_rgb_tile(cr, r->map[v], r->w, r->h, x, y + head + th + gap, tw / r->w);
            }
            cairo_set_source_rgb(cr, 0, 0, 0);
            cairo_move_to(cr, gap + REF * (tw + gap), y + head + th + gap + 14);
            cairo_show_text(cr, "below: ΔE00 against the reference");
            y += head + 2 * (th + gap);
        }
        cli_de_legend(cr, gap, y + 8, 700, "ΔE00 against the reference (the scale of biref diff):");
        cairo_surface_flush(out);
        biref_outfile *png = fig_open_out(png_path);
        cairo_status_t cs = png ? cairo_surface_write_to_png_stream(out, fig_write_stream, biref_outfile_stream(png))
                                : CAIRO_STATUS_WRITE_ERROR;
        cairo_destroy(cr);
        cairo_surface_destroy(out);
        if (!png) {
            rc = 1;
        } else if (cs != CAIRO_STATUS_SUCCESS) {
            fig_discard(png);
            rc = (cli_error(CMD, "cannot write %s: %s", png_path, cairo_status_to_string(cs)), 1);
        } else if (fig_close_csv(png, png_path)) {
            rc = 1;
        }
    }
    for (int i = 0; i < NCASES; i++)
        for (int v = 0; v < NVAR; v++) free(res[i].rgb[v]), free(res[i].map[v]);
    (void)n;
    return rc;
}
