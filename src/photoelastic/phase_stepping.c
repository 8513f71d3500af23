/* Phase stepping in a circular polariscope: the settings of the four- and six-step methods, the
 * polariscope of each step, and the demodulation of an image set into the isoclinic angle and
 * the unwrapped isochromatic phase (docs/PHOTOELASTICITY.md, "Phase stepping").
 *
 * Derivation (Jones calculus in the library's convention: the slow axis gains e^{+i phase},
 * biref_pe_shade). Light reaching the specimen e = (1, i)/sqrt2 (S3 = +1). The specimen is a
 * retarder of phase delta with its slow axis along s1, a = (cos phi, sin phi), b = (-sin phi,
 * cos phi): J = e^{i delta} a a^T + b b^T. Since a.e = e^{i phi}/sqrt2 and b.e = i e^{i phi}/sqrt2,
 *   J e = e^{i phi}/sqrt2 (e^{i delta} a + i b).
 * The output side (quarter-wave plate with its fast axis at xi, then a linear analyzer at beta)
 * passes the state u = conj(Q l) with Q = f f^T + i g g^T (f the fast axis, g the slow one) and
 * l = (cos beta, sin beta); the detected intensity is |u^H J e|^2. With u's Stokes vector
 * (1, a1, a2, a3) this works out to
 *   I = 1/2 (1 + a3 cos delta + sin delta (a2 cos 2phi - a1 sin 2phi)),
 * e.g. u = (1, 0): |e^{i delta} cos phi - i sin phi|^2 / 2 = (1 - sin 2phi sin delta)/2.
 * A real polariscope adds a background Ib and scales the rest by Ia: I = Ib + Ia/2 (...).
 * Patterson & Wang's six settings (xi, beta) = (0, 45), (0, 135), (0, 0), (45, 45), (90, 90),
 * (135, 135) deg pass the six poles of the Poincare sphere: a3 = -1, +1 (dark and light
 * circular field) and a1 = +1, a2 = +1, a1 = -1, a2 = -1 (the quarter-wave plate along the
 * analyzer leaves it linear). Hence, with this input handedness,
 *   I1 = Ib + Ia/2 (1 - cos d),            I2 = Ib + Ia/2 (1 + cos d),
 *   I3 = Ib + Ia/2 (1 - sin 2phi sin d),   I4 = Ib + Ia/2 (1 + cos 2phi sin d),
 *   I5 = Ib + Ia/2 (1 + sin 2phi sin d),   I6 = Ib + Ia/2 (1 - cos 2phi sin d)
 * (Patterson & Wang's I1 and I2 are swapped: their input light has the other handedness). The
 * test compares these with biref_pe_shade through each step's polariscope. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "biref/photoelastic.h"
#include "optics/validate.h"
#include "photoelastic/pixel_heap.h"

/* Largest |fringe order| of the reference point (docs/PHOTOELASTICITY.md, "Phase stepping"). */
#define MAX_REF_ORDER 1e5

static const double SETTINGS_DEG[6][2] = {{0, 45}, {0, 135}, {0, 0}, {45, 45}, {90, 90}, {135, 135}};

/* The state the output side passes: u = conj(Q l). */
static void stepped_u(double xi, double beta, double complex u[2])
{
    const double fx = cos(xi), fy = sin(xi), gx = -sin(xi), gy = cos(xi);
    const double lx = cos(beta), ly = sin(beta);
    const double lf = fx * lx + fy * ly, lg = gx * lx + gy * ly;
    u[0] = conj(lf * fx + I * lg * gx);
    u[1] = conj(lf * fy + I * lg * gy);
}

void biref_pe_polariscope_stepped(double qwp_rad, double analyzer_rad, biref_pe_polariscope *out)
{
    double complex u[2], P[2][2];
    stepped_u(qwp_rad, analyzer_rad, u);
    for (int k = 0; k < 2; k++)
        for (int o = 0; o < 2; o++) P[k][o] = conj(u[k]) * u[o];
    const double stokes[4] = {1.0, 0.0, 0.0, 1.0};
    (void)biref_pe_polariscope_custom(stokes, P, out);
}

int biref_pe_phase_steps(int n, biref_pe_step out[6])
{
    if (n != 4 && n != 6) return 0;
    for (int k = 0; k < n; k++) {
        double complex u[2];
        out[k].qwp_deg = SETTINGS_DEG[k][0];
        out[k].analyzer_deg = SETTINGS_DEG[k][1];
        stepped_u(SETTINGS_DEG[k][0] * M_PI / 180.0, SETTINGS_DEG[k][1] * M_PI / 180.0, u);
        /* Stokes of u in the convention of biref_stokes_to_coherency. */
        const double complex c = u[0] * conj(u[1]);
        double s[4] = {1.0, creal(u[0] * conj(u[0]) - u[1] * conj(u[1])), 2.0 * creal(c), -2.0 * cimag(c)};
        for (int i = 1; i < 4; i++) s[i] = nearbyint(s[i] * 1e12) * 1e-12; /* exact poles, not 1e-17 */
        memcpy(out[k].stokes, s, sizeof s);
    }
    return n;
}

/* ------------------------------------------------------------------------ */
/* Demodulation                                                              */
/* ------------------------------------------------------------------------ */

static double wrap_pi(double x)
{
    return x - 2.0 * M_PI * nearbyint(x / (2.0 * M_PI));
}

/* Below this |sin delta| the isoclinic of a pixel is noise: such pixels take their branch from
 * phase continuity and pass on their neighbour's isoclinic instead of their own. */
#define Q_LOW 0.05
/* Below this |sin delta| a pixel has no isoclinic at all. */
#define ISO_Q 1e-3

/* The demodulation's per-pixel working arrays. */
typedef struct {
    int W, H;
    size_t np;
    /* 2phi' and delta' in [0, pi] of the branch with sin delta >= 0, its quality |sin delta|
     * (-1: masked or non-finite), Ia, Ib. */
    float *two_phi, *dl, *qual, *ia, *ib;
    float *vec, *smooth;   /* branch-free (cos d, cos 2phi sin d, sin 2phi sin d); flood order key */
    double *unw;           /* unwrapped delta of the chosen branch */
    float *ref2phi;        /* isoclinic passed on to neighbours */
    signed char *branch;   /* +1: (2phi', delta'), -1: (2phi' + pi, -delta'); 0: not reached */
    pixel_heap h;
} demod_work;

static void demod_work_free(demod_work *w)
{
    free(w->two_phi);
    free(w->dl);
    free(w->qual);
    free(w->ia);
    free(w->ib);
    free(w->vec);
    free(w->smooth);
    free(w->unw);
    free(w->ref2phi);
    free(w->branch);
    free(w->h.a);
}

static int demod_work_alloc(demod_work *w, int W, int H)
{
    const size_t np = (size_t)W * H;
    w->W = W;
    w->H = H;
    w->np = np;
    w->two_phi = malloc(np * sizeof *w->two_phi);
    w->dl = malloc(np * sizeof *w->dl);
    w->qual = malloc(np * sizeof *w->qual);
    w->ia = malloc(np * sizeof *w->ia);
    w->ib = malloc(np * sizeof *w->ib);
    w->vec = malloc(np * 3 * sizeof *w->vec);
    w->smooth = malloc(np * sizeof *w->smooth);
    w->unw = malloc(np * sizeof *w->unw);
    w->ref2phi = malloc(np * sizeof *w->ref2phi);
    w->branch = malloc(np);
    w->h.a = malloc(np * sizeof(pixel_heap_item));
    w->h.n = 0;
    return w->two_phi && w->dl && w->qual && w->ia && w->ib && w->vec && w->smooth && w->unw && w->ref2phi &&
           w->branch && w->h.a;
}

/* The wrapped isoclinic and isochromatic of every pixel from the n step intensities (the
 * formulas in the header comment); returns the largest modulation Ia. */
static double wrapped_phases(int n, const float *const images[], demod_work *w)
{
    double ia_max = 0;
    for (size_t p = 0; p < w->np; p++) {
        double im[6];
        int finite = 1;
        for (int k = 0; k < n; k++) {
            im[k] = images[k][p];
            finite &= isfinite(im[k]);
        }
        double c, xs, ys, mean;
        if (n == 6) {
            c = im[1] - im[0];
            ys = im[4] - im[2];
            xs = im[3] - im[5];
            mean = 0.5 * (im[0] + im[1]);
        } else {
            /* I1 + I2 = 2 Ib + Ia fixes the mean the two linear steps swing about. */
            mean = 0.5 * (im[0] + im[1]);
            c = im[1] - im[0];
            ys = 2.0 * (mean - im[2]);
            xs = 2.0 * (im[3] - mean);
        }
        const double s = hypot(xs, ys), a = sqrt(c * c + s * s);
        if (!finite) {
            w->ia[p] = w->ib[p] = NAN;
            w->qual[p] = -1;
            continue;
        }
        w->two_phi[p] = (float)atan2(ys, xs);
        w->dl[p] = (float)atan2(s, c);
        w->ia[p] = (float)a;
        w->ib[p] = (float)(mean - 0.5 * a);
        w->qual[p] = a > 0 ? (float)(s / a) : 0.0f;
        /* (cos d, cos 2phi sin d, sin 2phi sin d): free of the branch ambiguity. */
        w->vec[3 * p] = a > 0 ? (float)(c / a) : 1.0f;
        w->vec[3 * p + 1] = a > 0 ? (float)(xs / a) : 0.0f;
        w->vec[3 * p + 2] = a > 0 ? (float)(ys / a) : 0.0f;
        ia_max = fmax(ia_max, a);
    }
    return ia_max;
}

/* The flood follows the smoothest pixels first: 1 - half the largest step of the branch-free
 * vector to a neighbour. Where fringes are finer than the pixels (load points) the steps
 * are large and those pixels come last, so that they cannot pass a wrong order on. */
static void flood_order(demod_work *w)
{
    const int W = w->W, H = w->H;
    const float *qual = w->qual, *vec = w->vec;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const size_t p = (size_t)y * W + x;
            double worst = 0;
            const int nb[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
            for (int k = 0; k < 4 && qual[p] >= 0; k++) {
                if (nb[k][0] < 0 || nb[k][0] >= W || nb[k][1] < 0 || nb[k][1] >= H) continue;
                const size_t q = (size_t)nb[k][1] * W + nb[k][0];
                if (qual[q] < 0) continue;
                double d2 = 0;
                for (int i = 0; i < 3; i++) d2 += (vec[3 * q + i] - vec[3 * p + i]) * (vec[3 * q + i] - vec[3 * p + i]);
                worst = fmax(worst, d2);
            }
            /* Pixels without an isoclinic (the empty field, isotropic points) come after all
             * others: entering the part from them would have to guess the phase's sign. */
            w->smooth[p] = (float)(1.0 - 0.5 * sqrt(worst) + (qual[p] >= ISO_Q ? 1.0 : 0.0));
        }
}

/* The best pixel of the reference's region to start the unwrapping from: one where the
 * isoclinic is defined (|sin d| >= 1/2) and the field smoothest. A stack-free flood over the
 * region (branch[] marks visited pixels, cleared again). */
static size_t region_seed(demod_work *w, size_t rp)
{
    const int W = w->W, H = w->H;
    pixel_heap *h = &w->h;
    size_t best = rp;
    pixel_heap_push(h, 0, (int)rp);
    w->branch[rp] = 2; /* visited */
    while (h->n) {
        pixel_heap_item it = pixel_heap_pop(h);
        const int x = it.px % W, y = it.px / W;
        const int okb = w->qual[best] >= 0.5f, oki = w->qual[it.px] >= 0.5f;
        if (oki > okb || (oki == okb && w->smooth[it.px] > w->smooth[best])) best = (size_t)it.px;
        const int nb[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
        for (int k = 0; k < 4; k++) {
            if (nb[k][0] < 0 || nb[k][0] >= W || nb[k][1] < 0 || nb[k][1] >= H) continue;
            const size_t q = (size_t)nb[k][1] * W + nb[k][0];
            if (w->branch[q] || w->qual[q] < 0) continue;
            w->branch[q] = 2;
            pixel_heap_push(h, 0, (int)q);
        }
    }
    for (size_t p = 0; p < w->np; p++) w->branch[p] = 0;
    return best;
}

/* Quality-guided unwrapping from the seed: each pixel reached takes the branch continuous
 * with the neighbour it was reached from, and its delta unwrapped against that neighbour's. */
static void unwrap_from(demod_work *w, size_t best)
{
    const int W = w->W, H = w->H;
    pixel_heap *h = &w->h;
    const float *two_phi = w->two_phi, *dl = w->dl, *qual = w->qual;
    float *ref2phi = w->ref2phi;
    double *unw = w->unw;
    w->branch[best] = 1;
    unw[best] = dl[best];
    ref2phi[best] = two_phi[best];
    pixel_heap_push(h, w->smooth[best], (int)best);
    while (h->n) {
        pixel_heap_item it = pixel_heap_pop(h);
        const size_t p = (size_t)it.px;
        const int x = it.px % W, y = it.px / W;
        const int nb[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
        for (int k = 0; k < 4; k++) {
            if (nb[k][0] < 0 || nb[k][0] >= W || nb[k][1] < 0 || nb[k][1] >= H) continue;
            const size_t q = (size_t)nb[k][1] * W + nb[k][0];
            if (w->branch[q] || qual[q] < 0) continue;
            int b;
            /* ref2phi is NAN where no isoclinic is known yet (the empty field, isotropic lines). */
            if (qual[q] >= Q_LOW && !isnan(ref2phi[p])) {
                /* The isoclinic is continuous: take the branch whose 2phi is nearer. */
                b = fabs(wrap_pi(two_phi[q] - ref2phi[p])) <= 0.5 * M_PI ? 1 : -1;
                ref2phi[q] = b > 0 ? two_phi[q] : (float)wrap_pi(two_phi[q] + M_PI);
            } else {
                /* Near sin delta = 0 both branches give nearly the same phase; take the one
                 * nearer the neighbour's and keep the neighbour's isoclinic. */
                const double da = fabs(wrap_pi(dl[q] - unw[p])), db = fabs(wrap_pi(-dl[q] - unw[p]));
                b = da <= db ? 1 : -1;
                const double own = b > 0 ? two_phi[q] : wrap_pi(two_phi[q] + M_PI);
                ref2phi[q] = !isnan(ref2phi[p]) ? ref2phi[p] : qual[q] >= ISO_Q ? (float)own : NAN;
            }
            const double d = b * dl[q];
            unw[q] = d + 2.0 * M_PI * nearbyint((unw[p] - d) / (2.0 * M_PI));
            w->branch[q] = (signed char)b;
            pixel_heap_push(h, w->smooth[q], (int)q);
        }
    }
}

/* The global sign (s1 and s2 swapped everywhere) and the integer offset at the reference, then
 * the requested maps (NAN outside the unwrapped region). */
static void write_maps(const demod_work *w, size_t rp, double ref_order, const biref_pe_demod_maps *out)
{
    const size_t np = w->np;
    long neg[2] = {0, 0};
    double kref[2];
    for (int s = 0; s < 2; s++) {
        const double sg = s ? -1.0 : 1.0;
        kref[s] = nearbyint(ref_order - sg * w->unw[rp] / (2.0 * M_PI));
        for (size_t p = 0; p < np; p++)
            if (w->branch[p] && sg * w->unw[p] / (2.0 * M_PI) + kref[s] < -0.25) neg[s]++;
    }
    const int s = neg[1] < neg[0];
    const double sg = s ? -1.0 : 1.0;
    for (size_t p = 0; p < np; p++) {
        const int in = w->branch[p] != 0;
        const double N = sg * w->unw[p] / (2.0 * M_PI) + kref[s];
        if (out->fringe_order) out->fringe_order[p] = in ? (float)N : NAN;
        if (out->phase_wrapped) {
            double wr = fmod(2.0 * M_PI * N, 2.0 * M_PI);
            if (wr < 0) wr += 2.0 * M_PI;
            out->phase_wrapped[p] = in ? (float)wr : NAN;
        }
        if (out->isoclinic_deg) {
            /* The chosen branch's 2phi (near sin delta = 0: the neighbours'), turned by pi if
             * the global sign flipped; phi in (-90, 90]. */
            double phi = 0.5 * wrap_pi(w->ref2phi[p] + (s ? M_PI : 0.0)) * 180.0 / M_PI;
            if (phi <= -90.0) phi += 180.0;
            out->isoclinic_deg[p] = in ? (float)phi : NAN; /* NAN stays NAN */
        }
        if (out->modulation) out->modulation[p] = w->qual[p] >= 0 ? w->ia[p] : NAN;
        if (out->background) out->background[p] = w->qual[p] >= 0 ? w->ib[p] : NAN;
    }
}

biref_status biref_pe_demodulate(int n, const float *const images[], int W, int H, const biref_pe_demod_opts *o,
                                 const biref_pe_demod_maps *out, char *msg, size_t msg_len)
{
    if (n != 4 && n != 6) return biref_fail(msg, msg_len, "expected 4 or 6 images, got %d", n);
    if (!images || !o || !out || W < 1 || H < 1) return biref_fail(msg, msg_len, "bad arguments");
    for (int k = 0; k < n; k++)
        if (!images[k]) return biref_fail(msg, msg_len, "image %d missing", k + 1);
    const int rx = (int)lround(o->ref_x), ry = (int)lround(o->ref_y);
    if (!(o->ref_x >= 0 && o->ref_x < W && o->ref_y >= 0 && o->ref_y < H) || rx >= W || ry >= H)
        return biref_fail(msg, msg_len, "the reference pixel (%g, %g) is outside the %d x %d images", o->ref_x, o->ref_y,
                          W, H);
    /* The maps are floats: beyond 1e5 fringes their steps (1/128 of a fringe there) hide the fringes. */
    if (!(fabs(o->ref_order) <= MAX_REF_ORDER))
        return biref_fail(msg, msg_len, "the reference fringe order %g is out of range (at most %g in magnitude)",
                          o->ref_order, MAX_REF_ORDER);
    const double min_mod = o->min_modulation >= 0 && isfinite(o->min_modulation) ? o->min_modulation : 0.05;
    demod_work w;
    biref_status st = BIREF_OK;
    if (!demod_work_alloc(&w, W, H)) {
        st = biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
        goto done;
    }
    const double ia_max = wrapped_phases(n, images, &w);
    if (!(ia_max > 0)) {
        st = biref_fail(msg, msg_len, "the images carry no modulation (all steps equal)");
        goto done;
    }
    for (size_t p = 0; p < w.np; p++) {
        w.branch[p] = 0;
        if (w.qual[p] >= 0 && !(w.ia[p] >= min_mod * ia_max)) w.qual[p] = -1; /* masked */
    }
    flood_order(&w);
    const size_t rp = (size_t)ry * W + rx;
    if (w.qual[rp] < 0) {
        st = biref_fail(msg, msg_len, "the reference pixel (%d, %d) has too little modulation (%.3g of the largest)", rx,
                        ry, ia_max > 0 && isfinite(w.ia[rp]) ? w.ia[rp] / ia_max : 0.0);
        goto done;
    }
    unwrap_from(&w, region_seed(&w, rp));
    write_maps(&w, rp, o->ref_order, out);
done:
    demod_work_free(&w);
    return st;
}
