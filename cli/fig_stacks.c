/* Figures of stacks of layers (docs/STACKS.md): the transmission spectra of a Lyot and a folded
 * Šolc filter, a cellophane "stained-glass" picture between crossed polarizers, and a stressed
 * disk whose stress varies through its thickness in a dark-field plane polariscope. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "fig_common.h"
#include "fig_plot.h"
#include "fig_stacks.h"

/* The example stack NAME of the examples directory; -1 after one error line. */
static int load_example(const char *examples, const char *name, biref_stack *s)
{
    char path[4096], msg[BIREF_MSG_SIZE];
    snprintf(path, sizeof path, "%s/stacks/%s", examples, name);
    if (biref_stack_load(path, s, msg, sizeof msg) != BIREF_OK) return cli_error(FIG_CMD, "%s: %s", path, msg), -1;
    return 0;
}

/* |J_T[in][out]|^2 at normal incidence. */
static double power_at(const biref_stack *s, double lambda, int in, int out)
{
    biref_jones T;
    if (biref_stack_jones(s, 0.0, lambda, &T, NULL) != BIREF_OK) return NAN;
    return creal(T.m[in][out] * conj(T.m[in][out]));
}

enum { LYOT_STAGES = 4 };

int fig_filters_check(const char *examples)
{
    biref_stack s;
    return load_example(examples, "lyot_stage1.json", &s) || load_example(examples, "solc_folded.json", &s) ||
           load_example(examples, "film_on_glass.json", &s) ||
           load_example(examples, "quartz_zero_order_halfwave.json", &s) ||
           load_example(examples, "quartz_multi_order_halfwave.json", &s);
}

/* The two quartz half-wave plates (n(λ) per wavelength) between crossed polarizers at 45°, and the
 * multi-order plate again with quartz's indices at 550 nm held constant (no dispersion). */
static int waveplate_curves(const char *examples, int n, const double *lam, double *zero, double *multi,
                            double *flat)
{
    biref_stack z, m;
    if (load_example(examples, "quartz_zero_order_halfwave.json", &z) ||
        load_example(examples, "quartz_multi_order_halfwave.json", &m))
        return -1;
    biref_stack c;
    if (biref_stack_at(&m, 550.0, &c) != BIREF_OK) return cli_error(FIG_CMD, "filters: quartz at 550 nm"), -1;
    for (int i = 0; i < n; i++) {
        zero[i] = power_at(&z, lam[i], BIREF_S, BIREF_P);
        multi[i] = power_at(&m, lam[i], BIREF_S, BIREF_P);
        flat[i] = power_at(&c, lam[i], BIREF_S, BIREF_P);
    }
    return 0;
}

enum { FILM_ANGLES = 86 };

/* The film on glass: band-integrated reflectance (Y) s -> s, p -> p, s -> p and unpolarized against
 * the angle of incidence, by the path expansion (coherent in the film, incoherent in the glass). */
static int film_reflectance(const fig_ctx *c, const biref_stack *film, double theta[FILM_ANGLES],
                            double Y[4][FILM_ANGLES])
{
    for (int t = 0; t < FILM_ANGLES; t++) {
        theta[t] = t;
        biref_stack_state st;
        biref_spectrum sp;
        char msg[BIREF_MSG_SIZE];
        if (biref_stack_prepare(film, t * M_PI / 180, &st) != BIREF_OK ||
            biref_stack_spectrum(c->sp, &st, NULL, NULL, &sp, NULL, NULL, NULL, msg, sizeof msg) != BIREF_OK)
            return cli_error(FIG_CMD, "filters: film on glass at %d deg failed", t), -1;
        Y[0][t] = sp.R[0][0][1];
        Y[1][t] = sp.R[1][1][1];
        Y[2][t] = sp.R[0][1][1];
        Y[3][t] = 0.5 * (sp.R[0][0][1] + sp.R[0][1][1] + sp.R[1][0][1] + sp.R[1][1][1]);
    }
    return 0;
}

int fig_filters(const fig_ctx *c, const char *examples)
{
    biref_stack lyot, solc, film;
    if (load_example(examples, "lyot_stage1.json", &lyot) || load_example(examples, "solc_folded.json", &solc) ||
        load_example(examples, "film_on_glass.json", &film))
        return CLI_EXIT_USAGE;
    double film_curves[4][FILM_ANGLES], film_theta[FILM_ANGLES];
    if (film_reflectance(c, &film, film_theta, film_curves)) return CLI_EXIT_FAIL;
    const int n = c->quick ? 400 : 3200;
    double *buf = malloc(sizeof(double) * (size_t)n * (LYOT_STAGES + 8));
    if (!buf) return cli_error(FIG_CMD, "out of memory"), CLI_EXIT_FAIL;
    double *lam = buf, *stage = buf + n, *ly = stage + (size_t)n * LYOT_STAGES, *ly0 = ly + n, *so = ly0 + n,
           *so0 = so + n, *wz = so0 + n, *wm = wz + n, *wf = wm + n;
    const biref_layer *l1 = &lyot.layers[0], *s1 = &solc.layers[0];
    const int N = solc.n_layers;
    const double rho = atan2(s1->axis[2], s1->axis[0]);
    for (int i = 0; i < n; i++) {
        lam[i] = 380.0 + 320.0 * i / (n - 1);
        ly[i] = ly0[i] = 1.0;
        /* Lyot: stages d, 2d, 4d, 8d at 45 deg, each followed by a polarizer parallel to the first
         * (ideal: the amplitudes multiply; reflections between stages are absorbed). */
        for (int k = 0; k < LYOT_STAGES; k++) {
            biref_stack st = lyot;
            st.layers[0].thickness_nm = l1->thickness_nm * (1 << k);
            const double t = power_at(&st, lam[i], BIREF_S, BIREF_S);
            stage[(size_t)k * n + i] = t;
            ly[i] *= t;
            const double G = 2 * M_PI * st.layers[0].thickness_nm * (l1->eta_e - l1->eta_o) / lam[i];
            ly0[i] *= pow(cos(G / 2), 2);
        }
        /* Folded Šolc between crossed polarizers, and its closed form (no reflections). */
        so[i] = power_at(&solc, lam[i], BIREF_S, BIREF_P);
        const double G = 2 * M_PI * s1->thickness_nm * (s1->eta_e - s1->eta_o) / lam[i];
        const double chi = acos(cos(2 * rho) * sin(G / 2));
        so0[i] = pow(tan(2 * rho) * cos(chi) * sin(N * chi) / sin(chi), 2);
    }
    if (waveplate_curves(examples, n, lam, wz, wm, wf)) return free(buf), CLI_EXIT_USAGE;
    char path[4096];
    biref_outfile *out = fig_open_csv(c, "filters.csv", path, sizeof path);
    if (!out) return free(buf), CLI_EXIT_FAIL;
    FILE *f = biref_outfile_stream(out);
    fprintf(f, "lambda_nm,lyot_stage1,lyot_stage2,lyot_stage3,lyot_stage4,lyot,lyot_ideal,solc,solc_ideal,"
               "quartz_zero_order,quartz_multi_order,quartz_multi_order_constant\n");
    for (int i = 0; i < n; i++)
        fprintf(f, "%.4f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", lam[i], stage[i], stage[n + i],
                stage[2 * n + i], stage[3 * n + i], ly[i], ly0[i], so[i], so0[i], wz[i], wm[i], wf[i]);
    if (fig_close_csv(out, path)) return free(buf), CLI_EXIT_FAIL;

    fig_out_path(c, "filters.png", path, sizeof path);
    if (fig_begin(path, 1200, 2000, 1, 4)) return free(buf), CLI_EXIT_FAIL;
    char title[160];
    snprintf(title, sizeof title, "Lyot filter: %d quartz stages at 45°, %.0f–%.0f µm, polarizers between", LYOT_STAGES,
             l1->thickness_nm / 1e3, l1->thickness_nm * (1 << (LYOT_STAGES - 1)) / 1e3);
    fig_plot_panel(380, 700, 0, 1.3, "λ (nm)", "transmission", title);
    fig_plot_line(n, lam, stage, FIG_GREY, 1.0);
    fig_plot_line(n, lam, ly0, FIG_ORANGE, 2.0);
    fig_plot_line(n, lam, ly, FIG_BLUE, 1.0);
    static const char *const ll[] = {"stack, in air (Fresnel losses)", "ideal Π cos²(2ᵏΓ/2)", "first stage alone"};
    static const int lc[] = {FIG_BLUE, FIG_ORANGE, FIG_GREY};
    static const double lw[] = {1.0, 2.0, 1.0};
    fig_plot_legend(3, ll, lc, lw, 0);
    snprintf(title, sizeof title, "folded Šolc filter: %d quartz plates of %.1f µm at ±%.1f°, crossed polarizers", N,
             s1->thickness_nm / 1e3, rho * 180 / M_PI);
    fig_plot_panel(380, 700, 0, 1.3, "λ (nm)", "transmission", title);
    fig_plot_line(n, lam, so0, FIG_ORANGE, 2.0);
    fig_plot_line(n, lam, so, FIG_BLUE, 1.0);
    static const char *const sl[] = {"stack, in air (Fresnel losses)", "ideal tan²2ρ cos²χ (sin Nχ / sin χ)²"};
    fig_plot_legend(2, sl, lc, lw, 0);
    fig_plot_panel(0, 85, 0, 1.0, "θ (degrees)", "reflectance (Y)",
                   "film on glass: 400 nm birefringent film on 1 mm glass, band-integrated (expansion)");
    static const int fc[] = {FIG_BLUE, FIG_RED, FIG_GREEN, FIG_BLACK};
    for (int k = 0; k < 4; k++) fig_plot_line(FILM_ANGLES, film_theta, film_curves[k], fc[k], 1.5);
    static const char *const fl[] = {"s → s", "p → p", "s → p (the film's birefringence)", "unpolarized"};
    static const double fw[] = {1.5, 1.5, 1.5, 1.5};
    fig_plot_legend(4, fl, fc, fw, FIG_LEFT);
    fig_plot_panel(380, 700, 0, 1.3, "λ (nm)", "transmission",
                   "quartz half-wave plates at 45°, crossed polarizers, index-matched surround, n(λ) of quartz (Ghosh 1999)");
    fig_plot_line(n, lam, wf, FIG_GREY, 1.0);
    fig_plot_line(n, lam, wm, FIG_RED, 1.5);
    fig_plot_line(n, lam, wz, FIG_BLUE, 2.0);
    static const char *const wl[] = {"zero-order: 1.000 + 1.030 mm, axes crossed", "multi-order: 630 µm (10.5 λ)",
                                     "multi-order, indices fixed at 550 nm"};
    static const int wc[] = {FIG_BLUE, FIG_RED, FIG_GREY};
    static const double ww[] = {2.0, 1.5, 1.0};
    fig_plot_legend(3, wl, wc, ww, 0);
    free(buf);
    return fig_end(path) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

/* ------------------------------------------------------------------------ */
/* Cellophane art                                                           */
/* ------------------------------------------------------------------------ */

/* One patch: `n` layers at these azimuths (degrees), each cellophane (film 0) or packing tape
 * (film 1). */
typedef struct {
    int n;
    double deg[6];
    int film[6];
} patch;

/* Cellophane-like film (27 µm) and packing tape (45 µm), birefringence 0.0095: about 260 and 430 nm
 * of retardance per layer, so a few layers run through the first orders of the Michel-Lévy chart. */
static const double FILM_O = 1.50, FILM_E = 1.5095, FILM_NM[2] = {27e3, 45e3};

static const patch PATCHES[] = {
    {0, {0}, {0}}, /* background: no film, dark between crossed polarizers */
    /* the rose window: six sectors and the centre */
    {1, {45}, {1}},
    {2, {45, 45}, {0, 0}},
    {2, {45, 45}, {0, 1}},
    {3, {45, 45, 45}, {0, 0, 0}},
    {3, {45, 45, 45}, {0, 0, 1}},
    {3, {45, 45, 45}, {0, 1, 1}},
    {4, {45, 45, 45, 45}, {1, 1, 1, 0}},
    /* the ring: the same two layers turned, then crossed */
    {2, {45, 45}, {1, 1}},
    {2, {22.5, 22.5}, {1, 1}},
    {2, {45, -45}, {1, 0}},
    {3, {45, 45, 80}, {0, 1, 0}},
    /* three mountains */
    {4, {45, 45, 45, 45}, {0, 0, 0, 1}},
    {5, {45, 45, 45, 45, 45}, {0, 1, 1, 1, 0}},
    {3, {45, 45, 45}, {1, 1, 1}},
};

/* The patch under the point (u, v) of the picture (0..1 across and down; a = width / height). */
static int patch_at(double u, double v, double a)
{
    double dx = (u - 0.27) * a, dy = v - 0.38, r = sqrt(dx * dx + dy * dy);
    if (r < 0.07) return 7;
    if (r < 0.25) return 1 + (int)((atan2(dy, dx) + M_PI) / (2 * M_PI) * 6) % 6;
    dx = (u - 0.76) * a, dy = v - 0.3, r = sqrt(dx * dx + dy * dy);
    if (r > 0.1 && r < 0.19) return 8 + (dy < 0) * 2 + (dx < 0);
    static const double m[3][3] = {{0.62, 0.58, 0.5}, {0.3, 0.66, 0.6}, {0.9, 0.62, 0.45}}; /* apex u, v; slope */
    for (int k = 0; k < 3; k++)
        if (v > m[k][1] + fabs(u - m[k][0]) * a * m[k][2]) return 12 + k;
    return 0;
}

static biref_stack film_stack(const patch *p)
{
    biref_stack s;
    memset(&s, 0, sizeof s);
    s.eta_i = 1.0;
    s.n_layers = p->n;
    for (int k = 0; k < p->n; k++) {
        const double t = p->deg[k] * M_PI / 180;
        s.layers[k] = (biref_layer){FILM_O, FILM_E, {cos(t), 0.0, sin(t)}, FILM_NM[p->film[k]], 0, NULL};
    }
    return s;
}

int fig_tape_art(const fig_ctx *c)
{
    enum { NP = sizeof PATCHES / sizeof PATCHES[0] };
    const int w = c->quick ? 320 : 960, h = c->quick ? 200 : 600;
    unsigned char rgb[NP][3] = {{0}};
    double xyz[NP][3] = {{0}};
    biref_light crossed;
    const double s_only[2] = {1, 0}, p_only[2] = {0, 1};
    biref_light_sp(s_only, p_only, &crossed); /* polarizer along x (s), analyzer along z (p) */
    char path[4096];
    biref_outfile *out = fig_open_csv(c, "tape_art.csv", path, sizeof path);
    if (!out) return CLI_EXIT_FAIL;
    FILE *f = biref_outfile_stream(out);
    fprintf(f, "patch,layers,azimuths_deg,films,X,Y,Z,R8,G8,B8,method,path_groups,fallback\n");
    for (int k = 1; k < NP; k++) {
        biref_stack s = film_stack(&PATCHES[k]);
        biref_stack_state st;
        biref_spectrum sp;
        biref_stack_spectrum_info info;
        char msg[BIREF_MSG_SIZE];
        if (biref_stack_prepare(&s, 0.0, &st) != BIREF_OK ||
            biref_stack_spectrum(c->sp, &st, NULL, &crossed, &sp, xyz[k], NULL, &info, msg, sizeof msg) != BIREF_OK)
            return fig_discard(out), cli_error(FIG_CMD, "tape-art: patch %d failed", k), CLI_EXIT_FAIL;
        double lin[3];
        biref_xyz_to_srgb(xyz[k], lin);
        for (int j = 0; j < 3; j++) rgb[k][j] = (unsigned char)lrint(255 * fmin(fmax(lin[j], 0.0), 1.0));
        fprintf(f, "%d,%d,\"", k, PATCHES[k].n);
        for (int j = 0; j < PATCHES[k].n; j++) fprintf(f, "%s%g", j ? " " : "", PATCHES[k].deg[j]);
        fprintf(f, "\",\"");
        for (int j = 0; j < PATCHES[k].n; j++) fprintf(f, "%s%s", j ? " " : "", PATCHES[k].film[j] ? "tape" : "cellophane");
        fprintf(f, "\",%.5f,%.5f,%.5f,%d,%d,%d,expansion,%d,%d\n", xyz[k][0], xyz[k][1], xyz[k][2], rgb[k][0],
                rgb[k][1], rgb[k][2], info.groups[0], info.fallback);
    }
    if (fig_close_csv(out, path)) return CLI_EXIT_FAIL;
    unsigned char *img = malloc((size_t)w * h * 3);
    if (!img) return cli_error(FIG_CMD, "out of memory"), CLI_EXIT_FAIL;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const double a = (double)w / h, u = (x + 0.5) / w, v = (y + 0.5) / h, du = 2.5 / w, dv = 2.5 / h;
            const int k = patch_at(u, v, a);
            /* Lead lines: where the patch changes within a few pixels. */
            const int lead = k != patch_at(u + du, v, a) || k != patch_at(u, v + dv, a) ||
                             k != patch_at(u + du, v + dv, a);
            for (int j = 0; j < 3; j++) img[((size_t)y * w + x) * 3 + j] = lead ? 40 : rgb[k][j];
        }
    fig_out_path(c, "tape_art.png", path, sizeof path);
    char msg[BIREF_MSG_SIZE];
    biref_status s = biref_png_write_rgb8(path, w, h, img, msg, sizeof msg);
    free(img);
    if (s != BIREF_OK) return cli_error(FIG_CMD, "%s", msg), CLI_EXIT_FAIL;
    printf("wrote %s\n", path);
    return CLI_EXIT_OK;
}
