/* Colour conversions: CIEDE2000 against Sharma, Wu & Dalal (2005), CIELAB,
 * XYZ (white E) <-> sRGB, 8-bit sRGB. Runs with the repository root as the
 * working directory (data/ciede2000_sharma2005.csv). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "biref/color.h"
#include "test_cases.h"

static const double PI = 3.14159265358979323846;

/* ---- independent references, written from the papers -------------------- */

/* CIEDE2000 following Sharma, Wu & Dalal 2005, eqs. (1)–(17), k_L=k_C=k_H=1.
 * Used to cross-check lcms2 beyond the 34 published pairs. */
static double ref_ciede2000(const double *p, const double *q)
{
    const double d2r = PI / 180.0, p25_7 = 6103515625.0; /* 25^7 */
    const double c1 = hypot(p[1], p[2]), c2 = hypot(q[1], q[2]);
    const double cb7 = pow(0.5 * (c1 + c2), 7.0);
    const double g = 0.5 * (1.0 - sqrt(cb7 / (cb7 + p25_7)));
    const double a1 = (1.0 + g) * p[1], a2 = (1.0 + g) * q[1];
    const double cp1 = hypot(a1, p[2]), cp2 = hypot(a2, q[2]);
    double h1 = (a1 == 0.0 && p[2] == 0.0) ? 0.0 : atan2(p[2], a1) / d2r;
    double h2 = (a2 == 0.0 && q[2] == 0.0) ? 0.0 : atan2(q[2], a2) / d2r;
    if (h1 < 0.0) h1 += 360.0;
    if (h2 < 0.0) h2 += 360.0;
    const double dl = q[0] - p[0], dc = cp2 - cp1;
    double dh = 0.0;
    if (cp1 * cp2 != 0.0) {
        dh = h2 - h1;
        if (dh > 180.0) dh -= 360.0;
        else if (dh < -180.0) dh += 360.0;
    }
    const double dhh = 2.0 * sqrt(cp1 * cp2) * sin(0.5 * dh * d2r);
    const double lb = 0.5 * (p[0] + q[0]), cpb = 0.5 * (cp1 + cp2);
    double hb;
    if (cp1 * cp2 == 0.0) hb = h1 + h2;
    else if (fabs(h1 - h2) <= 180.0) hb = 0.5 * (h1 + h2);
    else if (h1 + h2 < 360.0) hb = 0.5 * (h1 + h2 + 360.0);
    else hb = 0.5 * (h1 + h2 - 360.0);
    const double t = 1.0 - 0.17 * cos((hb - 30.0) * d2r) + 0.24 * cos(2.0 * hb * d2r) +
                     0.32 * cos((3.0 * hb + 6.0) * d2r) - 0.20 * cos((4.0 * hb - 63.0) * d2r);
    const double dtheta = 30.0 * exp(-pow((hb - 275.0) / 25.0, 2.0));
    const double cpb7 = pow(cpb, 7.0), rc = 2.0 * sqrt(cpb7 / (cpb7 + p25_7));
    const double l50 = (lb - 50.0) * (lb - 50.0);
    const double sl = 1.0 + 0.015 * l50 / sqrt(20.0 + l50), sc = 1.0 + 0.045 * cpb, sh = 1.0 + 0.015 * cpb * t;
    const double rt = -sin(2.0 * dtheta * d2r) * rc;
    const double x = dl / sl, y = dc / sc, z = dhh / sh;
    return sqrt(x * x + y * y + z * z + rt * y * z);
}

/* CIE 1976 L*a*b* (CIE 015:2018 §8.2.1). */
static double ref_lab_f(double t)
{
    const double eps = 216.0 / 24389.0, kappa = 24389.0 / 27.0;
    return t > eps ? cbrt(t) : (kappa * t + 16.0) / 116.0;
}
static void ref_lab(const double xyz[3], const double w[3], double lab[3])
{
    const double fx = ref_lab_f(xyz[0] / w[0]), fy = ref_lab_f(xyz[1] / w[1]), fz = ref_lab_f(xyz[2] / w[2]);
    lab[0] = 116.0 * fy - 16.0;
    lab[1] = 500.0 * (fx - fy);
    lab[2] = 200.0 * (fy - fz);
}

/* Bradford adaptation between two whites (Lam 1985), built independently of
 * the library: B⁻¹ diag(B·dst / B·src) B, with B⁻¹ by Cramer's rule. */
static void ref_bradford(const double src[3], const double dst[3], double m[3][3])
{
    static const double b[3][3] = {{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}};
    double rs[3], rd[3], bi[3][3];
    for (int i = 0; i < 3; i++) {
        rs[i] = b[i][0] * src[0] + b[i][1] * src[1] + b[i][2] * src[2];
        rd[i] = b[i][0] * dst[0] + b[i][1] * dst[1] + b[i][2] * dst[2];
    }
    const double det = b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1]) -
                       b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0]) +
                       b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0]);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            /* cofactor of b[j][i] */
            const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            bi[i][j] = (b[r0][c0] * b[r1][c1] - b[r0][c1] * b[r1][c0]) / det;
        }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double s = 0.0;
            for (int k = 0; k < 3; k++) s += bi[i][k] * rd[k] / rs[k] * b[k][j];
            m[i][j] = s;
        }
}

/* ---- tests --------------------------------------------------------------- */

static void test_ciede2000_matches_sharma_2005_test_data(void)
{
    FILE *f = fopen("data/ciede2000_sharma2005.csv", "r");
    CHECK(f != NULL);
    if (!f) return;
    char line[256];
    CHECK(fgets(line, sizeof line, f) != NULL);
    CHECK(strncmp(line, "L1,a1,b1,L2,a2,b2,dE00", 22) == 0);
    int n = 0, detected = 0;
    double max_err = 0.0, max_ref = 0.0;
    while (fgets(line, sizeof line, f)) {
        double v[7];
        if (sscanf(line, "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6]) != 7) continue;
        n++;
        const double e = biref_ciede2000(v, v + 3), e_rev = biref_ciede2000(v + 3, v);
        CHECK_NEAR(e, v[6], 1e-4);
        CHECK_NEAR(e_rev, e, 1e-12); /* symmetry */
        CHECK_NEAR(ref_ciede2000(v, v + 3), v[6], 1e-4);
        if (fabs(e - v[6]) > max_err) max_err = fabs(e - v[6]);
        if (fabs(e - ref_ciede2000(v, v + 3)) > max_ref) max_ref = fabs(e - ref_ciede2000(v, v + 3));
        /* The check can fail: moving L1 by 0.1 shifts ΔE00 by more than the
         * 1e-4 tolerance for every pair. */
        double moved[3] = {v[0] + 0.1, v[1], v[2]};
        if (fabs(biref_ciede2000(moved, v + 3) - v[6]) > 1e-4) detected++;
    }
    fclose(f);
    CHECK(n == 34);
    CHECK(detected == n);
    printf("Sharma 2005: %d pairs, max |lcms2 - table| %.3g, max |lcms2 - reference| %.3g\n", n, max_err, max_ref);
}

static void test_ciede2000_matches_reference_on_random_pairs(void)
{
    test_rng rng = {0x9e3779b97f4a7c15ULL};
    double max_diff = 0.0;
    for (int i = 0; i < 200000; i++) {
        double p[3], q[3];
        p[0] = test_uniform(&rng, 0.0, 100.0);
        p[1] = test_uniform(&rng, -128.0, 128.0);
        p[2] = test_uniform(&rng, -128.0, 128.0);
        if (i % 2) { /* small differences, where the hue branches matter */
            q[0] = p[0] + test_uniform(&rng, -2.0, 2.0);
            q[1] = p[1] + test_uniform(&rng, -3.0, 3.0);
            q[2] = p[2] + test_uniform(&rng, -3.0, 3.0);
        } else {
            q[0] = test_uniform(&rng, 0.0, 100.0);
            q[1] = test_uniform(&rng, -128.0, 128.0);
            q[2] = test_uniform(&rng, -128.0, 128.0);
        }
        if (i % 5 == 0) /* near-neutral colours */
            for (int k = 1; k < 3; k++) {
                p[k] *= 0.02;
                q[k] *= 0.02;
            }
        const double e = biref_ciede2000(p, q);
        const double d = fabs(e - ref_ciede2000(p, q));
        if (d > max_diff) max_diff = d;
        CHECK(e >= 0.0);
        if (i % 97 == 0) CHECK_NEAR(biref_ciede2000(q, p), e, 1e-12);
    }
    CHECK(max_diff < 1e-9);
    printf("CIEDE2000 lcms2 vs reference, 200000 random pairs: max |diff| %.3g\n", max_diff);
    const double a[3] = {50.0, 10.0, -20.0};
    CHECK(biref_ciede2000(a, a) == 0.0);
}

static void test_cielab_of_white_and_grey_known_values(void)
{
    const double e[3] = {1.0, 1.0, 1.0}, d65[3] = {0.3127 / 0.3290, 1.0, (1.0 - 0.3127 - 0.3290) / 0.3290};
    double lab[3];
    biref_xyz_to_lab(e, NULL, lab);
    CHECK_NEAR(lab[0], 100.0, 1e-12);
    CHECK_NEAR(lab[1], 0.0, 1e-12);
    CHECK_NEAR(lab[2], 0.0, 1e-12);
    biref_xyz_to_lab(d65, d65, lab);
    CHECK_NEAR(lab[0], 100.0, 1e-12);
    CHECK_NEAR(lab[1], 0.0, 1e-12);
    CHECK_NEAR(lab[2], 0.0, 1e-12);
    /* Y = 0.18 grey: L* = 116·0.18^(1/3) - 16 = 49.4961... */
    const double grey[3] = {0.18, 0.18, 0.18};
    biref_xyz_to_lab(grey, NULL, lab);
    CHECK_NEAR(lab[0], 116.0 * cbrt(0.18) - 16.0, 1e-12);
    CHECK_NEAR(lab[1], 0.0, 1e-12);

    test_rng rng = {12345};
    double max_diff = 0.0;
    for (int i = 0; i < 20000; i++) {
        const double s = (i % 4 == 0) ? 0.01 : 1.2; /* cover the linear segment too */
        const double xyz[3] = {test_uniform(&rng, 0.0, s), test_uniform(&rng, 0.0, s), test_uniform(&rng, 0.0, s)};
        const double *w = (i % 2) ? d65 : e;
        double l1[3], l2[3], back[3];
        biref_xyz_to_lab(xyz, w, l1);
        ref_lab(xyz, w, l2);
        for (int k = 0; k < 3; k++) {
            CHECK_NEAR(l1[k], l2[k], 1e-9);
            if (fabs(l1[k] - l2[k]) > max_diff) max_diff = fabs(l1[k] - l2[k]);
        }
        biref_lab_to_xyz(l1, w, back);
        for (int k = 0; k < 3; k++) CHECK_NEAR(back[k], xyz[k], 1e-12);
    }
    printf("Lab lcms2 vs reference: max |diff| %.3g\n", max_diff);

    /* ΔE00 in XYZ with white E. */
    double x1[3] = {0.3, 0.4, 0.5}, x2[3] = {0.31, 0.4, 0.48}, l1[3], l2[3];
    biref_xyz_to_lab(x1, NULL, l1);
    biref_xyz_to_lab(x2, NULL, l2);
    CHECK_NEAR(biref_delta_e00_xyz(x1, x2), ref_ciede2000(l1, l2), 1e-9);
    CHECK(biref_delta_e00_xyz(x1, x1) == 0.0);
    CHECK(biref_delta_e00_xyz(x1, x2) > 0.5); /* a visible difference */
}

static void test_srgb_matrices_equal_their_derivation(void)
{
    double m[3][3], minv[3][3];
    biref_srgb_derive_matrices(m, minv);
    /* The library's stored constants equal the derivation. */
    test_rng rng = {777};
    for (int i = 0; i < 1000; i++) {
        const double x[3] = {test_uniform(&rng, -1, 2), test_uniform(&rng, -1, 2), test_uniform(&rng, -1, 2)};
        double r[3], y[3];
        biref_xyz_to_linear_srgb(x, r);
        biref_linear_srgb_to_xyz(x, y);
        for (int k = 0; k < 3; k++) {
            CHECK_NEAR(r[k], m[k][0] * x[0] + m[k][1] * x[1] + m[k][2] * x[2], 1e-14);
            CHECK_NEAR(y[k], minv[k][0] * x[0] + minv[k][1] * x[1] + minv[k][2] * x[2], 1e-14);
        }
    }
    printf("XYZ(E) -> linear sRGB matrix:\n");
    for (int i = 0; i < 3; i++) printf("  % .10f % .10f % .10f\n", m[i][0], m[i][1], m[i][2]);

    /* White E -> sRGB white. */
    const double e[3] = {1.0, 1.0, 1.0};
    double rgb[3], xyz[3];
    biref_xyz_to_linear_srgb(e, rgb);
    for (int k = 0; k < 3; k++) CHECK_NEAR(rgb[k], 1.0, 1e-6);
    for (int k = 0; k < 3; k++) CHECK_NEAR(rgb[k], 1.0, 1e-14);
    biref_xyz_to_srgb(e, rgb);
    for (int k = 0; k < 3; k++) CHECK_NEAR(rgb[k], 1.0, 1e-14);
    /* The check can fail: the white point D65 itself is not (1,1,1) here. */
    const double d65[3] = {0.3127 / 0.3290, 1.0, (1.0 - 0.3127 - 0.3290) / 0.3290};
    biref_xyz_to_linear_srgb(d65, rgb);
    CHECK(fabs(rgb[0] - 1.0) > 1e-3 || fabs(rgb[2] - 1.0) > 1e-3);

    /* sRGB primaries, adapted back to D65, are the IEC 61966-2-1 columns
     * (published to 4 decimals): R (0.4124, 0.2126, 0.0193),
     * G (0.3576, 0.7152, 0.1192), B (0.1805, 0.0722, 0.9505). */
    static const double iec[3][3] = {{0.4124, 0.2126, 0.0193}, {0.3576, 0.7152, 0.1192}, {0.1805, 0.0722, 0.9505}};
    double to_d65[3][3];
    ref_bradford(e, d65, to_d65);
    for (int p = 0; p < 3; p++) {
        const double prim[3] = {p == 0, p == 1, p == 2};
        biref_linear_srgb_to_xyz(prim, xyz);
        for (int k = 0; k < 3; k++) {
            const double xd = to_d65[k][0] * xyz[0] + to_d65[k][1] * xyz[1] + to_d65[k][2] * xyz[2];
            CHECK_NEAR(xd, iec[p][k], 1.5e-4);
        }
    }
    /* Luminance of the primaries (Y row of the E-relative matrix) sums to 1. */
    const double ones[3] = {1.0, 1.0, 1.0};
    biref_linear_srgb_to_xyz(ones, xyz);
    for (int k = 0; k < 3; k++) CHECK_NEAR(xyz[k], 1.0, 1e-14);

    /* Round trips XYZ -> sRGB -> XYZ (linear and encoded). */
    for (int i = 0; i < 10000; i++) {
        const double x[3] = {test_uniform(&rng, 0, 1.2), test_uniform(&rng, 0, 1.2), test_uniform(&rng, 0, 1.2)};
        double r[3], y[3];
        biref_xyz_to_linear_srgb(x, r);
        biref_linear_srgb_to_xyz(r, y);
        for (int k = 0; k < 3; k++) CHECK_NEAR(y[k], x[k], 1e-9);
        biref_xyz_to_srgb(x, r);
        biref_srgb_to_xyz(r, y);
        for (int k = 0; k < 3; k++) CHECK_NEAR(y[k], x[k], 1e-9);
    }
}

/* The transfer function exactly as printed in IEC 61966-2-1, rounded break
 * points included. */
static double iec_encode(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055; }
static double iec_decode(double v) { return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4); }

static void test_srgb_transfer_curve_values_and_continuity(void)
{
    CHECK(biref_srgb_encode(0.0) == 0.0);
    CHECK(biref_srgb_decode(0.0) == 0.0);
    CHECK_NEAR(biref_srgb_encode(1.0), 1.0, 1e-15);
    CHECK_NEAR(biref_srgb_decode(1.0), 1.0, 1e-15);
    CHECK_NEAR(biref_srgb_decode(0.5), pow(0.555 / 1.055, 2.4), 1e-15);
    CHECK_NEAR(biref_srgb_decode(0.5), 0.21404114, 1e-8);
    CHECK_NEAR(biref_srgb_encode(0.002), 12.92 * 0.002, 1e-16);
    CHECK_NEAR(biref_srgb_encode(0.18), 1.055 * pow(0.18, 1.0 / 2.4) - 0.055, 1e-15);
    CHECK(biref_srgb_encode(-0.18) == -biref_srgb_encode(0.18));
    CHECK(biref_srgb_decode(-0.5) == -biref_srgb_decode(0.5));

    /* The library's break point is where the two segments meet. */
    const double v0 = 0.0031306684425006340;
    CHECK_NEAR(12.92 * v0, 1.055 * pow(v0, 1.0 / 2.4) - 0.055, 1e-16);
    CHECK_NEAR(biref_srgb_encode(nextafter(v0, 1.0)), biref_srgb_encode(v0), 1e-16);
    /* ...whereas the standard's own encoder jumps down at its break point
     * (this is what the library avoids; the check shows the probe works). */
    CHECK(iec_encode(nextafter(0.0031308, 1.0)) < iec_encode(0.0031308) - 2e-8);

    /* Round trips, strict monotonicity and agreement with the literal
     * standard: over an extended range and densely around the break points. */
    double max_rt = 0.0, max_iec = 0.0, prev = -INFINITY;
    for (int i = 0; i <= 400000; i++) {
        const double x = i <= 200000 ? -0.5 + 2.0 * i / 200000.0 : 0.00313 + (i - 200000) * 5e-12;
        if (i == 200001) prev = -INFINITY;
        const double enc = biref_srgb_encode(x);
        CHECK(enc > prev);
        prev = enc;
        const double d = fabs(biref_srgb_decode(enc) - x);
        if (d > max_rt) max_rt = d;
        if (x >= 0.0) {
            const double de = fabs(enc - iec_encode(x)), dd = fabs(biref_srgb_decode(x) - iec_decode(x));
            if (de > max_iec) max_iec = de;
            if (dd > max_iec) max_iec = dd;
        }
    }
    for (int i = 0; i <= 200000; i++) {
        const double y = 0.0404 + i * 5e-10;
        const double d = fabs(biref_srgb_encode(biref_srgb_decode(y)) - y);
        if (d > max_rt) max_rt = d;
        const double dd = fabs(biref_srgb_decode(y) - iec_decode(y));
        if (dd > max_iec) max_iec = dd;
    }
    CHECK(max_rt < 1e-14);
    CHECK(max_iec < 3e-8);
    printf("sRGB transfer: round trip max |error| %.3g, max |difference| from literal IEC formula %.3g\n", max_rt,
           max_iec);
}

static void test_srgb8_values_round_trip_through_xyz(void)
{
    const unsigned char white[3] = {255, 255, 255}, black[3] = {0, 0, 0}, mid[3] = {128, 128, 128};
    double xyz[3], lin[3];
    biref_srgb8_to_xyz(white, xyz);
    for (int k = 0; k < 3; k++) CHECK_NEAR(xyz[k], 1.0, 1e-12);
    biref_srgb8_to_xyz(black, xyz);
    for (int k = 0; k < 3; k++) CHECK(xyz[k] == 0.0);
    biref_srgb8_to_linear(mid, lin);
    CHECK_NEAR(lin[0], 0.21586050011389923, 1e-12);
    biref_srgb8_to_xyz(mid, xyz);
    for (int k = 0; k < 3; k++) CHECK_NEAR(xyz[k], 0.21586050011389923, 1e-12);

    /* Every 8-bit value survives 8-bit -> XYZ -> 8-bit, alone and mixed. */
    int bad = 0;
    for (int v = 0; v < 256; v++) {
        const unsigned char in[3][3] = {{v, v, v}, {v, 0, 255 - v}, {(v * 7) & 255, v, (v * 13) & 255}};
        for (int c = 0; c < 3; c++) {
            unsigned char out[3];
            biref_srgb8_to_xyz(in[c], xyz);
            biref_xyz_to_srgb8(xyz, out);
            if (memcmp(in[c], out, 3) != 0) bad++;
        }
    }
    CHECK(bad == 0);
    /* Clamping. */
    const double hot[3] = {5.0, 5.0, 5.0}, neg[3] = {-1.0, -1.0, -1.0}, nan3[3] = {NAN, NAN, NAN};
    unsigned char out[3];
    biref_xyz_to_srgb8(hot, out);
    CHECK(out[0] == 255 && out[1] == 255 && out[2] == 255);
    biref_xyz_to_srgb8(neg, out);
    CHECK(out[0] == 0 && out[1] == 0 && out[2] == 0);
    biref_xyz_to_srgb8(nan3, out);
    CHECK(out[0] == 0 && out[1] == 0 && out[2] == 0);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"ciede2000_matches_sharma_2005_test_data", test_ciede2000_matches_sharma_2005_test_data},
        {"ciede2000_matches_reference_on_random_pairs", test_ciede2000_matches_reference_on_random_pairs},
        {"cielab_of_white_and_grey_known_values", test_cielab_of_white_and_grey_known_values},
        {"srgb_matrices_equal_their_derivation", test_srgb_matrices_equal_their_derivation},
        {"srgb_transfer_curve_values_and_continuity", test_srgb_transfer_curve_values_and_continuity},
        {"srgb8_values_round_trip_through_xyz", test_srgb8_values_round_trip_through_xyz},
    };
    return test_run_cases("test_color", cases, TEST_COUNT(cases), argc, argv);
}
