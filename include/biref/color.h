/*
 * biref — colour science: colour-matching functions, band normalisation,
 * XYZ <-> sRGB, CIELAB and CIEDE2000.
 *
 * Every function here is pure (no global mutable state) and thread-safe.
 * Design notes, sources and measured accuracy: docs/COLOR.md.
 *
 * Units and conventions
 *  - Wavelengths are vacuum wavelengths in nm.
 *  - "Band-normalised" values (paper §5.1) are S(f, Λ_j) = ∫ Λ_j f dλ with
 *    Λ_j = cmf_j / ∫_{λmin}^{λmax} cmf_j dλ restricted to [λmin, λmax]. They are
 *    CIE XYZ tristimulus values relative to the equal-energy illuminant E,
 *    scaled so that the flat spectrum f(λ) = 1 gives (1, 1, 1). Every XYZ in
 *    this header (unless stated otherwise) is on that scale: white E = (1,1,1).
 *  - sRGB: linear values are in [0, 1] for in-gamut colours; (1,1,1) is the
 *    white of the display, to which white E is mapped (Bradford adaptation
 *    E -> D65 folded into the matrix, see biref_xyz_to_linear_srgb).
 */
#ifndef BIREF_COLOR_H
#define BIREF_COLOR_H

#include "biref/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------ */
/* Colour-matching functions                                                 */
/* ------------------------------------------------------------------------ */

typedef enum {
    /* CIE 1931 2° standard observer, the 1 nm table 380–780 nm compiled into
     * the library, linearly interpolated; 0 outside [380, 780] nm. */
    BIREF_CMF_CIE1931 = 0,
    /* Wyman, Sloan & Shirley 2013 (JCGT 2(2)), multi-lobe piecewise-Gaussian
     * fit of CIE 1931 2°; analytic, defined for every λ (not cut to 380–780). */
    BIREF_CMF_WYMAN2013 = 1
} biref_cmf_kind;

/* Default band for normalisation, as in the paper's evaluation (§6). */
#define BIREF_CMF_DEFAULT_LMIN_NM 380.0
#define BIREF_CMF_DEFAULT_LMAX_NM 700.0

/* Un-normalised x̄, ȳ, z̄ at lambda_nm. An unknown kind or a non-finite
 * wavelength gives (0, 0, 0). */
BIREF_API void biref_cmf_eval(biref_cmf_kind kind, double lambda_nm, double xyz[3]);

/* "cie1931" or "wyman2013" (exact, case-sensitive). BIREF_ERR_INVALID for
 * anything else or NULL arguments; *out is untouched on error. */
BIREF_API biref_status biref_cmf_kind_from_name(const char *name, biref_cmf_kind *out);

/* The inverse: "cie1931", "wyman2013", or NULL for an unknown kind. */
BIREF_API const char *biref_cmf_kind_name(biref_cmf_kind kind);

/* integral[j] = ∫_{lmin}^{lmax} cmf_j(λ) dλ (nm). Exact to rounding: the
 * table's interpolant is integrated piecewise-linearly, the Wyman fit with
 * erf(). BIREF_ERR_INVALID for an unknown kind, non-finite bounds or
 * lmin >= lmax. Integrals may be 0 (a range outside the table). */
BIREF_API biref_status biref_cmf_band_integrals(biref_cmf_kind kind, double lmin, double lmax, double integral[3],
                                                char *msg, size_t msg_len);

/* The wavelengths the colour-matching data covers: the CIE 1931 table 380-780 nm; the Wyman fit
 * 360-830 nm (the CIE's full range; the fit is a fit of data on it). A spectral context
 * (biref_spectral_create) integrates only within this domain. BIREF_ERR_INVALID for an unknown
 * kind or NULL pointers. */
BIREF_API biref_status biref_cmf_domain(biref_cmf_kind kind, double *lmin_nm, double *lmax_nm);

/* Band-normalised sensitivity functions Λ_j (paper §5.1): a small value type,
 * fill it with biref_cmf_band_init and share it freely between threads. */
typedef struct {
    biref_cmf_kind kind;
    double lmin_nm, lmax_nm;
    double integral[3];     /* ∫ cmf_j over [lmin, lmax], nm */
    double inv_integral[3]; /* 1 / integral[j] */
} biref_cmf_band;

/* BIREF_ERR_INVALID as for biref_cmf_band_integrals, or if any integral is
 * not > 0 (then there is nothing to normalise by). */
BIREF_API biref_status biref_cmf_band_init(biref_cmf_band *band, biref_cmf_kind kind, double lmin, double lmax,
                                           char *msg, size_t msg_len);

/* Λ_j(λ) = cmf_j(λ) / integral[j] for λ in [lmin, lmax], 0 outside, in 1/nm.
 * ∫ Λ_j dλ = 1, so a flat spectrum integrates to (1, 1, 1). */
BIREF_API void biref_cmf_band_eval(const biref_cmf_band *band, double lambda_nm, double lam[3]);

/* ------------------------------------------------------------------------ */
/* XYZ (white E = (1,1,1)) <-> sRGB (IEC 61966-2-1)                          */
/* ------------------------------------------------------------------------ */

/* Linear sRGB from XYZ relative to white E. One 3x3 matrix
 * M = M_sRGB(D65) · Bradford(E -> D65), derived from the sRGB primaries,
 * the D65 chromaticity (0.3127, 0.3290) and the Bradford cone matrix; the
 * library stores it as a constant that tests re-derive (see
 * biref_srgb_derive_matrices). White E (1,1,1) -> (1,1,1). No clamping:
 * out-of-gamut colours give components < 0 or > 1. */
BIREF_API void biref_xyz_to_linear_srgb(const double xyz[3], double rgb[3]);
BIREF_API void biref_linear_srgb_to_xyz(const double rgb[3], double xyz[3]);

/* Re-derives both matrices above from first principles (chromaticities and
 * the Bradford matrix); rgb_from_xyz = M, xyz_from_rgb = M^-1. Row-major:
 * rgb[i] = Σ_k m[i][k] xyz[k]. For tests and documentation. */
BIREF_API void biref_srgb_derive_matrices(double rgb_from_xyz[3][3], double xyz_from_rgb[3][3]);

/* IEC 61966-2-1 transfer function, extended as an odd function
 * (f(-v) = -f(v)) so out-of-range values round-trip; no clamping. The
 * linear/power break points are the segments' exact intersection rather
 * than the standard's rounded 0.0031308 / 0.04045 (differs from the literal
 * standard by < 3e-8; makes encode and decode exact, monotone inverses). */
BIREF_API double biref_srgb_encode(double linear);
BIREF_API double biref_srgb_decode(double encoded);

/* XYZ (white E) -> encoded sRGB (non-linear, unclamped). */
BIREF_API void biref_xyz_to_srgb(const double xyz[3], double srgb[3]);
BIREF_API void biref_srgb_to_xyz(const double srgb[3], double xyz[3]);

/* 8-bit encoded sRGB <-> XYZ (white E). biref_xyz_to_srgb8 clamps each
 * encoded component to [0, 1] and rounds to nearest (NaN -> 0). */
BIREF_API void biref_srgb8_to_linear(const unsigned char rgb[3], double linear[3]);
BIREF_API void biref_srgb8_to_xyz(const unsigned char rgb[3], double xyz[3]);
BIREF_API void biref_xyz_to_srgb8(const double xyz[3], unsigned char rgb[3]);

/* ------------------------------------------------------------------------ */
/* CIELAB and CIEDE2000                                                      */
/* ------------------------------------------------------------------------ */

/* CIE 1976 L*a*b* of xyz relative to the reference white `white` (XYZ on the
 * same scale as xyz; NULL means white E = (1,1,1), the band-normalised
 * white). The white itself maps to (100, 0, 0). Uses lcms2's cmsXYZ2Lab
 * with an explicit white point. */
BIREF_API void biref_xyz_to_lab(const double xyz[3], const double white[3], double lab[3]);
BIREF_API void biref_lab_to_xyz(const double lab[3], const double white[3], double xyz[3]);

/* CIEDE2000 colour difference (k_L = k_C = k_H = 1), Sharma, Wu & Dalal 2005.
 * Symmetric. Uses lcms2's cmsCIE2000DeltaE (verified against all 34 of
 * Sharma's pairs, see docs/COLOR.md). */
BIREF_API double biref_ciede2000(const double lab1[3], const double lab2[3]);

/* ΔE00 between two XYZ colours relative to white E = (1,1,1). */
BIREF_API double biref_delta_e00_xyz(const double xyz1[3], const double xyz2[3]);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_COLOR_H */
