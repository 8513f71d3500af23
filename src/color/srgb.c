/*
 * XYZ (relative to the equal-energy white E, E = (1,1,1)) <-> sRGB.
 *
 * White handling. biref's band-normalised tristimulus values are relative
 * to illuminant E: a flat spectrum gives X = Y = Z = 1. sRGB's white is D65.
 * We want "white in, white out", so E is chromatically adapted to D65 with
 * the Bradford transform and then the standard sRGB matrix is applied; both
 * steps are folded into one 3x3 matrix M:
 *
 *     M = M_sRGB · B⁻¹ · diag(ρ_D65 / ρ_E) · B
 *
 *  - B: Bradford cone-response matrix (K. M. Lam, "Metamerism and colour
 *    constancy", PhD thesis, Univ. of Bradford, 1985; the linearised form
 *    used in ICC.1 / ISO 15076-1 Annex E and CIECAM97s).
 *  - ρ_w = B · XYZ_w for E = (1,1,1) and D65 = (x/y, 1, (1-x-y)/y) with the
 *    sRGB reference white chromaticity (0.3127, 0.3290).
 *  - M_sRGB: XYZ(D65) -> linear sRGB, built from the ITU-R BT.709 primaries
 *    R (0.64, 0.33), G (0.30, 0.60), B (0.15, 0.06) and that white as in
 *    SMPTE RP 177-1993 (columns = primaries scaled so R+G+B = white).
 *
 * The matrices below were produced by biref_srgb_derive_matrices (which does
 * exactly that at run time) and printed with 17 significant digits;
 * tests/test_color.c re-derives them and checks agreement to 1e-15. The
 * full-precision derivation matters: the 4-digit matrix printed in
 * IEC 61966-2-1 maps D65 to (1,1,1) only to ~1e-4.
 *
 * Transfer function: IEC 61966-2-1:1999 §5.2: encode 12.92·v on the linear
 * segment, else 1.055·v^(1/2.4) - 0.055; decode v/12.92, else
 * ((v+0.055)/1.055)^2.4; extended to negative values as an odd function.
 * The standard's rounded break points (0.0031308 linear, 0.04045 encoded)
 * do not sit where the two segments meet: its encoder jumps *down* by
 * 2.9e-8 at 0.0031308, decode(encode(v)) misses by up to 2.3e-9 just above
 * it and encode(decode(e)) by up to 3.0e-8 (measured). We switch segments at their exact intersection
 * instead (computed to 40 digits by Newton's method):
 *     v0 = 0.0031306684425006340,  12.92·v0 = 0.040448236277108192,
 * which makes both functions continuous, strictly increasing and exact
 * inverses of each other; they differ from the literal standard by < 3e-8,
 * and only for linear values in [v0, 0.0031308] (encoded [0.0404482,
 * 0.04045]). tests/test_color.c checks all three claims.
 */
#include <math.h>

#include "biref/color.h"

/* rgb = M · xyz (row-major), XYZ relative to white E. */
static const double rgb_from_xyz_e[3][3] = {
    {3.1466576541357196, -1.6664637545108383, -0.48019389962488129},
    {-0.99552160578071813, 1.9557567338090689, 0.039764871971649303},
    {0.063594802938788705, -0.21456322222468058, 1.1509684192858918},
};
/* xyz = M⁻¹ · rgb. */
static const double xyz_from_rgb_e[3][3] = {
    {0.43844878421924516, 0.39217592919722744, 0.16937528658352713},
    {0.2228276920549053, 0.70869129809695919, 0.068481009848135085},
    {0.017313736192152724, 0.11044502648170912, 0.8722412373261379},
};

static void mat_vec(const double m[3][3], const double v[3], double out[3])
{
    double r[3];
    for (int i = 0; i < 3; i++) r[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
    for (int i = 0; i < 3; i++) out[i] = r[i];
}

static void mat_mul(const double a[3][3], const double b[3][3], double out[3][3])
{
    double r[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) out[i][j] = r[i][j];
}

/* Inverse by the adjugate; the matrices here are well conditioned. */
static void mat_inv(const double m[3][3], double out[3][3])
{
    double c[3][3];
    c[0][0] = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    c[0][1] = m[0][2] * m[2][1] - m[0][1] * m[2][2];
    c[0][2] = m[0][1] * m[1][2] - m[0][2] * m[1][1];
    c[1][0] = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    c[1][1] = m[0][0] * m[2][2] - m[0][2] * m[2][0];
    c[1][2] = m[0][2] * m[1][0] - m[0][0] * m[1][2];
    c[2][0] = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    c[2][1] = m[0][1] * m[2][0] - m[0][0] * m[2][1];
    c[2][2] = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    const double det = m[0][0] * c[0][0] + m[0][1] * c[1][0] + m[0][2] * c[2][0];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) out[i][j] = c[i][j] / det;
}

static void xy_to_xyz(double x, double y, double out[3])
{
    out[0] = x / y;
    out[1] = 1.0;
    out[2] = (1.0 - x - y) / y;
}

void biref_srgb_derive_matrices(double rgb_from_xyz[3][3], double xyz_from_rgb[3][3])
{
    /* BT.709 / sRGB primaries and D65 as specified in IEC 61966-2-1. */
    static const double prim[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
    static const double white_d65[2] = {0.3127, 0.3290};
    /* Bradford cone-response matrix (Lam 1985). */
    static const double bradford[3][3] = {
        {0.8951, 0.2664, -0.1614},
        {-0.7502, 1.7135, 0.0367},
        {0.0389, -0.0685, 1.0296},
    };

    double d65[3], p[3][3], pinv[3][3], s[3];
    xy_to_xyz(white_d65[0], white_d65[1], d65);
    for (int k = 0; k < 3; k++) {
        double col[3];
        xy_to_xyz(prim[k][0], prim[k][1], col);
        for (int i = 0; i < 3; i++) p[i][k] = col[i];
    }
    /* Scale the primaries so that R = G = B = 1 is D65. */
    mat_inv(p, pinv);
    mat_vec(pinv, d65, s);
    double xyz_from_rgb_d65[3][3], rgb_from_xyz_d65[3][3];
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++) xyz_from_rgb_d65[i][k] = p[i][k] * s[k];
    mat_inv(xyz_from_rgb_d65, rgb_from_xyz_d65);

    /* Bradford E -> D65: B⁻¹ diag(ρ_D65/ρ_E) B. */
    const double e[3] = {1.0, 1.0, 1.0};
    double rho_e[3], rho_d65[3], binv[3][3], scaled[3][3], adapt[3][3], adapt_inv[3][3];
    mat_vec(bradford, e, rho_e);
    mat_vec(bradford, d65, rho_d65);
    mat_inv(bradford, binv);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) scaled[i][j] = rho_d65[i] / rho_e[i] * bradford[i][j];
    mat_mul(binv, scaled, adapt);
    mat_inv(adapt, adapt_inv);

    mat_mul(rgb_from_xyz_d65, adapt, rgb_from_xyz);
    mat_mul(adapt_inv, xyz_from_rgb_d65, xyz_from_rgb);
}

void biref_xyz_to_linear_srgb(const double xyz[3], double rgb[3])
{
    mat_vec(rgb_from_xyz_e, xyz, rgb);
}

void biref_linear_srgb_to_xyz(const double rgb[3], double xyz[3])
{
    mat_vec(xyz_from_rgb_e, rgb, xyz);
}

/* Where the linear and power segments of the sRGB curve meet (see top). */
#define SRGB_LINEAR_BREAK 0.0031306684425006340
#define SRGB_ENCODED_BREAK 0.040448236277108192

double biref_srgb_encode(double linear)
{
    const double a = fabs(linear);
    const double v = a <= SRGB_LINEAR_BREAK ? 12.92 * a : 1.055 * pow(a, 1.0 / 2.4) - 0.055;
    return linear < 0.0 ? -v : v;
}

double biref_srgb_decode(double encoded)
{
    const double a = fabs(encoded);
    const double v = a <= SRGB_ENCODED_BREAK ? a / 12.92 : pow((a + 0.055) / 1.055, 2.4);
    return encoded < 0.0 ? -v : v;
}

void biref_xyz_to_srgb(const double xyz[3], double srgb[3])
{
    biref_xyz_to_linear_srgb(xyz, srgb);
    for (int i = 0; i < 3; i++) srgb[i] = biref_srgb_encode(srgb[i]);
}

void biref_srgb_to_xyz(const double srgb[3], double xyz[3])
{
    double lin[3];
    for (int i = 0; i < 3; i++) lin[i] = biref_srgb_decode(srgb[i]);
    biref_linear_srgb_to_xyz(lin, xyz);
}

void biref_srgb8_to_linear(const unsigned char rgb[3], double linear[3])
{
    for (int i = 0; i < 3; i++) linear[i] = biref_srgb_decode((double)rgb[i] / 255.0);
}

void biref_srgb8_to_xyz(const unsigned char rgb[3], double xyz[3])
{
    double lin[3];
    biref_srgb8_to_linear(rgb, lin);
    biref_linear_srgb_to_xyz(lin, xyz);
}

void biref_xyz_to_srgb8(const double xyz[3], unsigned char rgb[3])
{
    double s[3];
    biref_xyz_to_srgb(xyz, s);
    for (int i = 0; i < 3; i++) {
        double v = s[i];
        if (!(v > 0.0)) v = 0.0; /* also NaN */
        if (v > 1.0) v = 1.0;
        rgb[i] = (unsigned char)lround(v * 255.0);
    }
}
