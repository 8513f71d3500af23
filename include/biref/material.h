/* biref — dispersive materials: refractive indices that depend on the wavelength.
 *
 * A biref_material gives n_o(λ) and n_e(λ) (one index for an isotropic material) and their group
 * indices n_g = n − λ dn/dλ, from a literature formula (the named catalogue, docs/MATERIALS.md),
 * from user-defined Sellmeier or Cauchy coefficients per index, or from a table (λ, n_o, n_e)
 * interpolated by monotone cubic Hermite splines. Materials are immutable after creation and may
 * be shared between threads; the catalogue's entries are static and need no destroy.
 *
 * A formula is evaluated outside its valid range too (biref_material_extrapolated says where); a
 * material is refused where it becomes unphysical (n² <= 1, a pole of the formula, a non-finite
 * value): biref_material_check_band says why, in one line. */
#ifndef BIREF_MATERIAL_H
#define BIREF_MATERIAL_H

#include <stddef.h>

#include "biref/common.h"
#include "biref/optics.h"
#include "biref/polarization.h"
#include "biref/integrator.h"
#include "biref/spectral.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------- */
/* Dispersion formulas of one index (wavelength λ in micrometres)            */
/* ------------------------------------------------------------------------- */

typedef enum {
    /* n² = a + Σ_i b_i λ²/(λ² − c_i) + Σ_j d_j/(λ² − e_j) + f λ²   (c_i, e_j in µm²);
     * the usual Sellmeier equation n² − 1 = Σ B_i λ²/(λ² − C_i) is a = 1, b = B, c = C. */
    BIREF_FORMULA_SELLMEIER = 0,
    /* n = a + Σ_i b_i / λ^(2i), i = 1..n_terms (Cauchy: n = A + B/λ² + C/λ⁴). */
    BIREF_FORMULA_CAUCHY = 1
} biref_formula_kind;

#define BIREF_FORMULA_MAX_TERMS 4

typedef struct {
    biref_formula_kind kind;
    double a;
    int n_terms;                          /* terms b_i (and c_i), 0..BIREF_FORMULA_MAX_TERMS */
    double b[BIREF_FORMULA_MAX_TERMS];
    double c[BIREF_FORMULA_MAX_TERMS];    /* Sellmeier only */
    int n_poles;                          /* Sellmeier only: terms d_j/(λ² − e_j), 0..2 */
    double d[2], e[2];
    double f;                             /* Sellmeier only */
} biref_index_formula;

/* ------------------------------------------------------------------------- */
/* Materials                                                                  */
/* ------------------------------------------------------------------------- */

typedef struct biref_material biref_material;

typedef struct {
    const char *name;        /* "calcite"; owned by the material */
    const char *description; /* one line: what it is, temperature */
    const char *source;      /* the citation of the formula or table */
    double range_nm[2];      /* where the formula or table is valid (measured) */
    int isotropic;           /* one index: n_e = n_o */
} biref_material_info;

/* The named catalogue (docs/MATERIALS.md): calcite, quartz, sapphire, rutile, mgf2, yvo4,
 * linbo3, bbo (uniaxial) and polycarbonate, pmma (isotropic). */
BIREF_API size_t biref_material_catalogue_size(void);
/* Entry i, NULL beyond the end. */
BIREF_API const biref_material *biref_material_catalogue(size_t i);
/* By name (case-sensitive, as listed); NULL for an unknown name. */
BIREF_API const biref_material *biref_material_find(const char *name);

/* A material from one formula per index (e NULL: isotropic, n_e = n_o); range_nm NULL: valid
 * everywhere (nothing is reported as extrapolated). name may be NULL ("user"). BIREF_ERR_INVALID
 * for a formula outside its domain (term counts, non-finite coefficients). */
BIREF_API biref_status biref_material_from_formulas(const char *name, const biref_index_formula *o,
                                                    const biref_index_formula *e, const double range_nm[2],
                                                    biref_material **out, char *msg, size_t msg_len);

/* Constant indices (no dispersion): the material of today's biref_slab. */
BIREF_API biref_status biref_material_constant(double eta_o, double eta_e, biref_material **out, char *msg,
                                               size_t msg_len);

/* A table of n samples (n >= 2, wavelengths in nm strictly increasing, indices > 1), interpolated
 * by monotone cubic Hermite splines (Fritsch–Carlson) in λ; outside the table the end
 * segments' cubics continue (reported as extrapolated). n_e NULL: isotropic. */
BIREF_API biref_status biref_material_from_table(const char *name, size_t n, const double *lambda_nm,
                                                 const double *n_o, const double *n_e, biref_material **out,
                                                 char *msg, size_t msg_len);

/* A table from a CSV file: one row "lambda_nm,n_o,n_e" per sample (or "lambda_nm,n" for an
 * isotropic material), an optional header row, '#' comments and blank lines ignored. */
BIREF_API biref_status biref_material_load_csv(const char *path, biref_material **out, char *msg, size_t msg_len);

/* Frees a material made by a constructor above; the catalogue's entries and NULL are ignored. */
BIREF_API void biref_material_destroy(biref_material *m);

BIREF_API void biref_material_get_info(const biref_material *m, biref_material_info *out);

/* Indices n[o, e] at the vacuum wavelength lambda_nm and, unless n_group is NULL, the group
 * indices n − λ dn/dλ. Per sample (no message): BIREF_ERR_INVALID for a wavelength that is not a
 * positive finite number or where the material is unphysical (n² <= 1 or not finite);
 * biref_material_check_band says why. */
BIREF_API biref_status biref_material_indices(const biref_material *m, double lambda_nm, double n[2],
                                              double n_group[2]);

/* Checks that the material is physical over [lo_nm, hi_nm]: no pole of a formula inside, and
 * n² > 1 for both indices at every nanometre and at both ends. One line in msg on failure. */
BIREF_API biref_status biref_material_check_band(const biref_material *m, double lo_nm, double hi_nm, char *msg,
                                                 size_t msg_len);

/* The parts of [lo_nm, hi_nm] outside the material's valid range: writes up to two intervals
 * (below, then above the range) into out and returns how many. */
BIREF_API int biref_material_extrapolated(const biref_material *m, double lo_nm, double hi_nm, double out[2][2]);

/* ------------------------------------------------------------------------- */
/* Slabs of a dispersive material                                             */
/* ------------------------------------------------------------------------- */

/* The slab at one wavelength: geometry's axis, thickness and eta_i with the material's indices
 * at lambda_nm (geometry's eta_o, eta_e are ignored). The codes of biref_material_indices. */
BIREF_API biref_status biref_material_slab_at(const biref_material *m, const biref_slab *geometry, double lambda_nm,
                                              biref_slab *out);

/* ------------------------------------------------------------------------- */
/* Integration with dispersion                                                */
/* ------------------------------------------------------------------------- */

/* biref_integrate for a slab of a dispersive material: geometry's axis, thickness and eta_i (its
 * eta_o, eta_e are ignored) at theta, the indices of m. The numeric and ground-truth methods
 * prepare the slab anew at every sample wavelength (exact). The analytic method and the expansion
 * linearise each leg's phase around each band's centroid (group path and phase offset, modes and
 * Fresnel coefficients at the band's wavelength; docs/PHYSICS.md §7) and integrate exactly where
 * the phases curve too much across a band. With constant indices every method gives the numbers
 * of biref_integrate. BIREF_ERR_INVALID for a geometry failing biref_slab_check or an angle
 * failing biref_theta_check, for a wavelength where the material is unphysical
 * (biref_material_check_band over the integrator's band says why) and for no side;
 * BIREF_ERR_SINGULAR from an interface solve; BIREF_ERR_ILLCOND for a non-finite result (or the
 * expansion's). No allocation. */
BIREF_API biref_status biref_integrate_material(const biref_integrator *it, const biref_material *m,
                                                const biref_slab *geometry, double theta_rad, biref_sides sides,
                                                const biref_light *light, biref_integration *out);

/* The four s/p pair intensities of transmission and reflection (as biref_integrate_spectrum). */
BIREF_API biref_status biref_integrate_material_spectrum(const biref_integrator *it, const biref_material *m,
                                                         const biref_slab *geometry, double theta_rad,
                                                         biref_spectrum *out);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_MATERIAL_H */
