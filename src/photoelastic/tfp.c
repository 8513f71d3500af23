/* Fringe orders from one white-light colour picture (RGB or three-fringe photoelasticity, TFP):
 * the calibration table of colour against fringe order, computed by the polariscope model, and
 * its inversion by colour matching with a continuity constraint grown from a seed pixel (refined
 * TFP: Ramesh & Deshmukh's windowed search, with a quality-guided order of visit).
 * docs/PHOTOELASTICITY.md, "Fringe orders from one colour picture". */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "optics/validate.h"
#include "photoelastic/pixel_heap.h"
#include "biref/color.h"
#include "biref/photoelastic.h"

/* A principal-stress state of fringe order N at lambda_ref for this plate, at 45 degrees to x
 * (off the isoclinics of a plane polariscope at 0 degrees). */
static biref_pe_principal state_of_order(const biref_pe_setup *s, double order, double lambda_ref_nm)
{
    const double ds = order * lambda_ref_nm * 1e-9 / (s->thickness * biref_pe_C_at(&s->material, lambda_ref_nm));
    biref_pe_principal p = {0.5 * ds, -0.5 * ds, 0.25 * M_PI, 0.0, 1.0};
    return p;
}

/* The camera's linear response to the light leaving the polariscope: the mono intensity at each
 * sample wavelength (illuminant E) weighted by the sensitivities, normalised so that the light
 * without polariscope losses (intensity 1 at every wavelength) gives 1 in each channel. */
static void camera_rgb(const biref_pe_setup *s, const biref_pe_camera *cam, const biref_pe_principal *p, double rgb[3])
{
    biref_pe_setup mono = *s;
    mono.light = BIREF_PE_MONO;
    double acc[3] = {0, 0, 0}, norm[3] = {0, 0, 0};
    for (size_t i = 0; i < cam->n; i++) {
        /* trapezoid weights over the (possibly uneven) samples */
        const double lo = cam->lambda_nm[i > 0 ? i - 1 : i], hi = cam->lambda_nm[i + 1 < cam->n ? i + 1 : i];
        const double w = 0.5 * (hi - lo);
        mono.lambda_nm = cam->lambda_nm[i];
        double v[3];
        biref_pe_shade(&mono, NULL, p, v);
        for (int c = 0; c < 3; c++) {
            acc[c] += w * cam->rgb[3 * i + c] * v[0];
            norm[c] += w * cam->rgb[3 * i + c];
        }
    }
    for (int c = 0; c < 3; c++) rgb[c] = norm[c] > 0 ? acc[c] / norm[c] : 0.0;
}

biref_status biref_pe_tfp_calibrate(const biref_pe_setup *s, const biref_spectral *sp, const biref_pe_camera *cam,
                                    double lambda_ref_nm, size_t n, const double *orders, double *rgb, char *msg,
                                    size_t msg_len)
{
    if (!s || !orders || !rgb || (!cam && !sp)) return biref_fail(msg, msg_len, "no setup, orders, output or spectral tables");
    if (!(lambda_ref_nm > 0 && isfinite(lambda_ref_nm))) return biref_fail(msg, msg_len, "the reference wavelength must be positive");
    if (!(s->thickness > 0 && s->material.C_per_Pa > 0)) return biref_fail(msg, msg_len, "the plate needs a thickness and a stress-optic coefficient");
    if (cam) {
        if (cam->n < 2) return biref_fail(msg, msg_len, "the camera's sensitivities need at least 2 wavelengths");
        for (size_t i = 0; i < cam->n; i++) {
            if (!(cam->lambda_nm[i] >= 200 && cam->lambda_nm[i] <= 2000) || (i && !(cam->lambda_nm[i] > cam->lambda_nm[i - 1])))
                return biref_fail(msg, msg_len, "sensitivity %zu: wavelengths must rise within 200-2000 nm", i + 1);
            for (int c = 0; c < 3; c++)
                if (!(cam->rgb[3 * i + c] >= 0 && isfinite(cam->rgb[3 * i + c])))
                    return biref_fail(msg, msg_len, "sensitivity %zu: values must be finite and non-negative", i + 1);
        }
    }
    biref_pe_setup white = *s;
    white.light = BIREF_PE_WHITE;
    for (size_t k = 0; k < n; k++) {
        if (!(orders[k] >= 0 && orders[k] <= 1000)) return biref_fail(msg, msg_len, "fringe order %g out of 0..1000", orders[k]);
        const biref_pe_principal p = state_of_order(s, orders[k], lambda_ref_nm);
        double *out = rgb + 3 * k;
        if (cam) {
            camera_rgb(s, cam, &p, out);
        } else { /* an sRGB camera: the picture's own pipeline (XYZ, white E = 1, encoded sRGB) */
            double xyz[3];
            biref_pe_shade(&white, sp, &p, xyz);
            biref_xyz_to_srgb(xyz, out);
            for (int c = 0; c < 3; c++) out[c] = fmin(1.0, fmax(0.0, out[c]));
        }
    }
    return BIREF_OK;
}

/* ------------------------------------------------------------------------ */
/* Demodulation                                                              */
/* ------------------------------------------------------------------------ */

/* The table entry in [k0, k1] nearest in colour, refined between table entries by a parabola
 * through the distances; *res the RMS colour difference there. */
static double match(const float *c, size_t n, const double *orders, const double *tab, size_t k0, size_t k1, double *res)
{
    size_t best = k0;
    double bd = INFINITY, d[3];
    for (size_t k = k0; k <= k1; k++) {
        const double *t = tab + 3 * k;
        const double e = (c[0] - t[0]) * (c[0] - t[0]) + (c[1] - t[1]) * (c[1] - t[1]) + (c[2] - t[2]) * (c[2] - t[2]);
        if (e < bd) bd = e, best = k;
    }
    *res = sqrt(bd / 3.0);
    if (best == 0 || best + 1 >= n || best == k0 || best == k1) return orders[best];
    for (int j = -1; j <= 1; j++) {
        const double *t = tab + 3 * (best + (size_t)(long)j);
        d[j + 1] = (c[0] - t[0]) * (c[0] - t[0]) + (c[1] - t[1]) * (c[1] - t[1]) + (c[2] - t[2]) * (c[2] - t[2]);
    }
    const double den = d[0] - 2 * d[1] + d[2];
    const double off = den > 0 ? 0.5 * (d[0] - d[2]) / den : 0.0;
    const double step = orders[best + 1] - orders[best];
    return orders[best] + fmax(-0.5, fmin(0.5, off)) * step;
}

/* Index range of the table within [lo, hi] (orders rise). */
static void table_range(size_t n, const double *orders, double lo, double hi, size_t *k0, size_t *k1)
{
    size_t a = 0, b = n - 1;
    while (a < n - 1 && orders[a] < lo) a++;
    while (b > a && orders[b] > hi) b--;
    *k0 = a;
    *k1 = b;
}

biref_status biref_pe_tfp_demodulate(const float *rgb, int W, int H, size_t n, const double *orders, const double *tab,
                                     const biref_pe_tfp_opts *o, float *order_out, float *residual_out, char *msg,
                                     size_t msg_len)
{
    if (!rgb || !orders || !tab || !o || !order_out || W < 1 || H < 1) return biref_fail(msg, msg_len, "no image, table or output");
    if (n < 3) return biref_fail(msg, msg_len, "the calibration table needs at least 3 rows");
    for (size_t k = 1; k < n; k++)
        if (!(orders[k] > orders[k - 1])) return biref_fail(msg, msg_len, "table row %zu: fringe orders must rise", k + 1);
    if (o->seed_x < 0 || o->seed_x >= W || o->seed_y < 0 || o->seed_y >= H)
        return biref_fail(msg, msg_len, "the seed pixel (%d, %d) is outside the %d x %d picture", o->seed_x, o->seed_y, W, H);
    if (!(o->window > 0 && o->max_residual > 0)) return biref_fail(msg, msg_len, "window and residual limit must be positive");
    const size_t npx = (size_t)W * H;
    unsigned char *done = calloc(npx, 1);
    pixel_heap h = {malloc(npx * 4 * sizeof *h.a + sizeof *h.a), 0};
    if (!done || !h.a) {
        free(done);
        free(h.a);
        return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    }
    for (size_t i = 0; i < npx; i++) {
        order_out[i] = NAN;
        if (residual_out) residual_out[i] = NAN;
    }
    /* The seed: the given order, searched within the window around it, or the best match overall. */
    const size_t s0 = (size_t)o->seed_y * W + o->seed_x;
    size_t k0 = 0, k1 = n - 1;
    if (!isnan(o->seed_order)) table_range(n, orders, o->seed_order - o->window, o->seed_order + o->window, &k0, &k1);
    double res;
    const double N0 = match(rgb + 3 * s0, n, orders, tab, k0, k1, &res);
    if (res > o->max_residual) {
        free(done);
        free(h.a);
        return biref_fail(msg, msg_len, "the seed pixel (%d, %d) matches no colour of the table%s within the residual "
                          "limit (best %.3g at N = %.3g, limit %g): another polariscope, camera or order?",
                          o->seed_x, o->seed_y, isnan(o->seed_order) ? "" : " near its order", res, N0, o->max_residual);
    }
    order_out[s0] = (float)N0;
    if (residual_out) residual_out[s0] = (float)res;
    done[s0] = 1;
    pixel_heap_push(&h, -(float)res, (int)s0); /* lowest residual first */
    /* Grow: each pixel's neighbours are matched within the window around its order; the best-matched
     * pixel is expanded first, so that noisy or ambiguous pixels never hand their order on before
     * the reliable ones around them have. */
    static const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
    size_t grown = 0;
    while (h.n) {
        grown++;
        const pixel_heap_item it = pixel_heap_pop(&h);
        const int x = it.px % W, y = it.px / W;
        const double N = order_out[it.px];
        for (int d = 0; d < 4; d++) {
            const int nx = x + dx[d], ny = y + dy[d];
            if (nx < 0 || nx >= W || ny < 0 || ny >= H) continue;
            const size_t q = (size_t)ny * W + nx;
            if (done[q]) continue;
            done[q] = 1;
            table_range(n, orders, N - o->window, N + o->window, &k0, &k1);
            const double Nq = match(rgb + 3 * q, n, orders, tab, k0, k1, &res);
            if (residual_out) residual_out[q] = (float)res;
            if (res > o->max_residual) continue; /* not this material's colours: left NaN, not passed on */
            order_out[q] = (float)Nq;
            pixel_heap_push(&h, -(float)res, (int)q);
        }
    }
    free(done);
    free(h.a);
    if (grown < 2 && npx > 1)
        return biref_fail(msg, msg_len, "no neighbour of the seed pixel (%d, %d) matches within +-%g of its order %.3g: a "
                          "wrong seed order, or a seed on an edge?", o->seed_x, o->seed_y, o->window, N0);
    return BIREF_OK;
}
