/*
 * Colour-matching functions (CIE 1931 2° table and the Wyman–Sloan–Shirley
 * 2013 analytic fit) and their band normalisation (paper §5.1).
 *
 * Sources:
 *  - CIE 015:2018 "Colorimetry", 4th ed., table of the CIE 1931 standard
 *    colorimetric observer (here at 1 nm, 380–780 nm, embedded from
 *    data/cie1931_2deg_xyz_1nm.csv at build time).
 *  - C. Wyman, P.-P. Sloan, P. Shirley, "Simple Analytic Approximations to
 *    the CIE XYZ Color Matching Functions", JCGT 2(2), 2013, 1–11: the
 *    "multi-lobe" fit of the 1931 2° observer (their eqs. 2–4, piecewise
 *    Gaussians with separate widths left and right of the mean).
 *
 * All functions are pure; nothing here has state.
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "biref/color.h"
#include "color/cie1931_table.h"
#include "error.h"

/* ---- CIE 1931 table ------------------------------------------------------ */

/* The table is uniformly spaced (1 nm; tests/test_cmf.c checks it), so the
 * segment holding λ is found by arithmetic, not by search. */
static double table_first(void) { return biref_cie1931_table[0][0]; }
static double table_last(void) { return biref_cie1931_table[biref_cie1931_rows - 1][0]; }
static double table_step(void)
{
    return (table_last() - table_first()) / (double)(biref_cie1931_rows - 1);
}

static void table_eval(double lambda, double xyz[3])
{
    const double first = table_first(), last = table_last();
    if (!(lambda >= first && lambda <= last)) { /* also catches NaN */
        xyz[0] = xyz[1] = xyz[2] = 0.0;
        return;
    }
    const double t = (lambda - first) / table_step();
    int i = (int)floor(t);
    if (i > biref_cie1931_rows - 2) i = biref_cie1931_rows - 2;
    if (i < 0) i = 0;
    const double w = t - (double)i;
    const double *r0 = biref_cie1931_table[i], *r1 = biref_cie1931_table[i + 1];
    for (int j = 0; j < 3; j++) xyz[j] = (1.0 - w) * r0[j + 1] + w * r1[j + 1];
}

/* Exact integral of the piecewise-linear interpolant over [a, b]: on each
 * table segment the overlap is integrated by the trapezoid rule, which is
 * exact for a linear function. */
static void table_integrals(double a, double b, double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    const double first = table_first(), last = table_last();
    if (a < first) a = first;
    if (b > last) b = last;
    if (!(a < b)) return;
    for (int i = 0; i + 1 < biref_cie1931_rows; i++) {
        const double x0 = biref_cie1931_table[i][0], x1 = biref_cie1931_table[i + 1][0];
        const double u = a > x0 ? a : x0, v = b < x1 ? b : x1;
        if (!(u < v)) continue;
        double fu[3], fv[3];
        table_eval(u, fu);
        table_eval(v, fv);
        for (int j = 0; j < 3; j++) out[j] += 0.5 * (v - u) * (fu[j] + fv[j]);
    }
}

/* ---- Wyman, Sloan & Shirley 2013, multi-lobe fit of CIE 1931 2° ---------- */

/* One lobe: weight · g(λ; μ, σ_left, σ_right), where
 * g = exp(-½ ((λ-μ)/σ)²) and σ = σ_left for λ < μ, σ_right otherwise
 * (WSS13 §2, eq. 2). Constants: WSS13 eqs. 2–4 (nm). */
typedef struct {
    double weight, mu, sigma_left, sigma_right;
} wss_lobe;

typedef struct {
    int n;
    wss_lobe lobe[3];
} wss_fn;

static const wss_fn wss13[3] = {
    /* x̄ */ {3, {{1.056, 599.8, 37.9, 31.0}, {0.362, 442.0, 16.0, 26.7}, {-0.065, 501.1, 20.4, 26.2}}},
    /* ȳ */ {2, {{0.821, 568.8, 46.9, 40.5}, {0.286, 530.9, 16.3, 31.1}, {0.0, 0.0, 1.0, 1.0}}},
    /* z̄ */ {2, {{1.217, 437.0, 11.8, 36.0}, {0.681, 459.0, 26.0, 13.8}, {0.0, 0.0, 1.0, 1.0}}},
};

static double wss_lobe_eval(const wss_lobe *l, double lambda)
{
    const double s = lambda < l->mu ? l->sigma_left : l->sigma_right;
    const double t = (lambda - l->mu) / s;
    return l->weight * exp(-0.5 * t * t);
}

/* ∫_a^b exp(-½((x-μ)/σ)²) dx = σ √(π/2) [erf((b-μ)/(σ√2)) - erf((a-μ)/(σ√2))]. */
static double gauss_integral(double mu, double sigma, double a, double b)
{
    const double k = 1.0 / (sigma * sqrt(2.0));
    return sigma * sqrt(2.0 * acos(-1.0)) * 0.5 * (erf((b - mu) * k) - erf((a - mu) * k));
}

static double wss_lobe_integral(const wss_lobe *l, double a, double b)
{
    double sum = 0.0;
    if (a < l->mu) sum += gauss_integral(l->mu, l->sigma_left, a, b < l->mu ? b : l->mu);
    if (b > l->mu) sum += gauss_integral(l->mu, l->sigma_right, a > l->mu ? a : l->mu, b);
    return l->weight * sum;
}

static void wss_eval(double lambda, double xyz[3])
{
    if (!isfinite(lambda)) {
        xyz[0] = xyz[1] = xyz[2] = 0.0;
        return;
    }
    for (int j = 0; j < 3; j++) {
        double s = 0.0;
        for (int k = 0; k < wss13[j].n; k++) s += wss_lobe_eval(&wss13[j].lobe[k], lambda);
        xyz[j] = s;
    }
}

static void wss_integrals(double a, double b, double out[3])
{
    for (int j = 0; j < 3; j++) {
        double s = 0.0;
        for (int k = 0; k < wss13[j].n; k++) s += wss_lobe_integral(&wss13[j].lobe[k], a, b);
        out[j] = s;
    }
}

/* ---- public ------------------------------------------------------------- */

void biref_cmf_eval(biref_cmf_kind kind, double lambda_nm, double xyz[3])
{
    switch (kind) {
    case BIREF_CMF_CIE1931: table_eval(lambda_nm, xyz); return;
    case BIREF_CMF_WYMAN2013: wss_eval(lambda_nm, xyz); return;
    }
    xyz[0] = xyz[1] = xyz[2] = 0.0;
}

biref_status biref_cmf_domain(biref_cmf_kind kind, double *lmin_nm, double *lmax_nm)
{
    if (!lmin_nm || !lmax_nm) return BIREF_ERR_INVALID;
    switch (kind) {
    case BIREF_CMF_CIE1931: *lmin_nm = table_first(), *lmax_nm = table_last(); return BIREF_OK;
    case BIREF_CMF_WYMAN2013: *lmin_nm = 360.0, *lmax_nm = 830.0; return BIREF_OK;
    }
    return BIREF_ERR_INVALID;
}

biref_status biref_cmf_kind_from_name(const char *name, biref_cmf_kind *out)
{
    if (!name || !out) return BIREF_ERR_INVALID;
    if (strcmp(name, "cie1931") == 0) {
        *out = BIREF_CMF_CIE1931;
        return BIREF_OK;
    }
    if (strcmp(name, "wyman2013") == 0) {
        *out = BIREF_CMF_WYMAN2013;
        return BIREF_OK;
    }
    return BIREF_ERR_INVALID;
}

const char *biref_cmf_kind_name(biref_cmf_kind kind)
{
    switch (kind) {
    case BIREF_CMF_CIE1931: return "cie1931";
    case BIREF_CMF_WYMAN2013: return "wyman2013";
    }
    return NULL;
}

biref_status biref_cmf_band_integrals(biref_cmf_kind kind, double lmin, double lmax, double integral[3], char *msg,
                                      size_t msg_len)
{
    if (!integral) return biref_fail(msg, msg_len, "no output");
    if (!isfinite(lmin) || !isfinite(lmax) || !(lmin < lmax))
        return biref_fail(msg, msg_len, "the band %g-%g nm is empty or not finite", lmin, lmax);
    switch (kind) {
    case BIREF_CMF_CIE1931: table_integrals(lmin, lmax, integral); return BIREF_OK;
    case BIREF_CMF_WYMAN2013: wss_integrals(lmin, lmax, integral); return BIREF_OK;
    }
    return biref_fail(msg, msg_len, "unknown colour-matching functions (%d)", (int)kind);
}

biref_status biref_cmf_band_init(biref_cmf_band *band, biref_cmf_kind kind, double lmin, double lmax, char *msg,
                                 size_t msg_len)
{
    if (!band) return biref_fail(msg, msg_len, "no output");
    double integral[3];
    biref_status st = biref_cmf_band_integrals(kind, lmin, lmax, integral, msg, msg_len);
    if (st != BIREF_OK) return st;
    for (int j = 0; j < 3; j++)
        if (!(integral[j] > 0.0))
            return biref_fail(msg, msg_len, "the %s %c function is zero over %g-%g nm (nothing to normalise by)",
                              biref_cmf_kind_name(kind), "xyz"[j], lmin, lmax);
    band->kind = kind;
    band->lmin_nm = lmin;
    band->lmax_nm = lmax;
    for (int j = 0; j < 3; j++) {
        band->integral[j] = integral[j];
        band->inv_integral[j] = 1.0 / integral[j];
    }
    return BIREF_OK;
}

void biref_cmf_band_eval(const biref_cmf_band *band, double lambda_nm, double lam[3])
{
    if (!(lambda_nm >= band->lmin_nm && lambda_nm <= band->lmax_nm)) {
        lam[0] = lam[1] = lam[2] = 0.0;
        return;
    }
    biref_cmf_eval(band->kind, lambda_nm, lam);
    for (int j = 0; j < 3; j++) lam[j] *= band->inv_integral[j];
}
