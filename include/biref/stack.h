/* biref — stacks of homogeneous layers (isotropic or uniaxial, each with its own optic axis)
 * between the same isotropic medium above and below: wave-plate filters, cellophane art, films on
 * glass, plates whose stress varies through the thickness. Exact Jones matrices per wavelength
 * (docs/STACKS.md), a 4x4 transfer-matrix reference, stack files and the band integrals.
 *
 * Frame and bases as for a slab (docs/CONVENTIONS.md): the light enters the first layer at
 * y = 0, the layers follow downwards, transmitted amplitudes refer to the bottom face of the last
 * layer. Plain data, no global state; the prepared state is immutable and may be shared. */
#ifndef BIREF_STACK_H
#define BIREF_STACK_H

#include <stddef.h>

#include "biref/common.h"
#include "biref/material.h"
#include "biref/optics.h"
#include "biref/polarization.h"
#include "biref/spectral.h"

#ifdef __cplusplus
extern "C" {
#endif

#define BIREF_STACK_MAX_LAYERS 64

/* One layer. isotropic != 0: index eta_o (eta_e and axis ignored). Otherwise uniaxial with
 * ordinary / extraordinary indices and an optic axis in the slab frame (need not be unit).
 * material != NULL: a dispersive layer (docs/STACKS.md, "Layers of a dispersive material"): its
 * indices at each wavelength are the material's (eta_o, eta_e ignored; an isotropic material
 * makes the layer isotropic). Borrowed: the material must outlive the stack and its states (the
 * catalogue's entries are static). */
typedef struct {
    double eta_o, eta_e;
    double axis[3];
    double thickness_nm;
    int isotropic;
    const biref_material *material;
} biref_layer;

typedef struct {
    double eta_i;                             /* surrounding medium, above and below */
    int n_layers;                             /* 1 .. BIREF_STACK_MAX_LAYERS */
    biref_layer layers[BIREF_STACK_MAX_LAYERS]; /* from the face the light enters, downwards */
} biref_stack;

/* Checks a stack; one-line reason ("layers[2].eta_e must be positive ...") into msg. */
BIREF_API biref_status biref_stack_check(const biref_stack *stack, char *msg, size_t msg_len);

/* The one-layer stack of a slab. */
BIREF_API void biref_stack_from_slab(const biref_slab *slab, biref_stack *out);

/* Non-zero when a layer is of a dispersive material (biref_layer.material). */
BIREF_API int biref_stack_dispersive(const biref_stack *stack);

/* The stack at one wavelength: every material layer replaced by the constant indices of its
 * material at lambda_nm (material NULL), the other layers copied. BIREF_ERR_INVALID for a bad
 * wavelength or one where a material is unphysical (biref_material_check_band says why). */
BIREF_API biref_status biref_stack_at(const biref_stack *stack, double lambda_nm, biref_stack *out);

/* Stack files (docs/STACKS.md): {"eta_i": 1.0, "layers": [{...}, ...]}, strict JSON (unknown or
 * repeated keys are errors). A layer is {"eta": n} or {"eta_o", "eta_e", "axis": [x, y, z]} or
 * {"eta_o", "eta_e", "azimuth_deg": phi} (optic axis in the surface, at phi from x towards z),
 * or {"material": "quartz", "axis" or "azimuth_deg"} (a named material of the catalogue, whose
 * entries are static), with exactly one of thickness_nm, thickness_um, thickness_mm. Errors
 * name the JSON path. */
BIREF_API biref_status biref_stack_parse(const char *text, size_t len, biref_stack *out, char *msg, size_t msg_len);
/* BIREF_ERR_IO when the file cannot be read; otherwise as biref_stack_parse. */
BIREF_API biref_status biref_stack_load(const char *path, biref_stack *out, char *msg, size_t msg_len);

/* Everything about a stack at one angle of incidence that does not depend on the wavelength.
 * Interface j separates medium j (above) from medium j + 1 (below); medium 0 and medium
 * n_layers + 1 are the surround. Plain data (about 29 KB), no allocation. A stack with layers of
 * a dispersive material depends on the wavelength everywhere: its state holds the indices at
 * lambda_nm and a copy of the stack, and biref_stack_jones_at prepares it anew at any other
 * wavelength. */
typedef struct {
    double theta, K, eta_i;
    int n_layers;
    double thickness_nm[BIREF_STACK_MAX_LAYERS];
    biref_interface iface[BIREF_STACK_MAX_LAYERS + 1];
    /* Optical path of one crossing of layer j per mode, nm (complex for evanescent modes):
     * -q_down d down, q_up d up (as biref_slab_state). */
    biref_complex opl_down[BIREF_STACK_MAX_LAYERS][2];
    biref_complex opl_up[BIREF_STACK_MAX_LAYERS][2];
    /* Power carried across the layer by a unit amplitude of each mode (BIREF_MODE_* order),
     * relative to a unit incident wave; 0 for evanescent modes. */
    double flux[BIREF_STACK_MAX_LAYERS][4];
    int evanescent; /* number of layers with an evanescent mode */
    int dispersive;   /* layers of a dispersive material: the above are at lambda_nm */
    double lambda_nm; /* dispersive: the wavelength of the indices above (0 otherwise) */
    biref_stack stack; /* dispersive: the stack, to be prepared at other wavelengths */
} biref_stack_state;

/* The wavelength at which biref_stack_prepare takes the indices of dispersive layers (nm). */
#define BIREF_STACK_REFERENCE_NM 550.0

/* Per-sample entry point: BIREF_ERR_INVALID when the stack fails biref_stack_check or the angle
 * biref_theta_check (or a material is unphysical at the wavelength), BIREF_ERR_SINGULAR when an
 * interface's boundary system is singular. Dispersive layers take their indices at
 * BIREF_STACK_REFERENCE_NM; biref_stack_prepare_at at lambda_nm. */
BIREF_API biref_status biref_stack_prepare(const biref_stack *stack, double theta_rad, biref_stack_state *st);
BIREF_API biref_status biref_stack_prepare_at(const biref_stack *stack, double theta_rad, double lambda_nm,
                                              biref_stack_state *st);

/* All orders of internal reflection in every layer, summed exactly (docs/STACKS.md: the
 * transfer matrix in its scattering form). Either output may be NULL. A dispersive state is
 * prepared anew at lambda_nm unless it was prepared there (NaN where a material is unphysical). */
BIREF_API void biref_stack_jones_at(const biref_stack_state *st, double lambda_nm, biref_jones *T, biref_jones *R);

/* prepare + evaluate; the codes of biref_stack_prepare, BIREF_ERR_INVALID for a bad wavelength. */
BIREF_API biref_status biref_stack_jones(const biref_stack *stack, double theta_rad, double lambda_nm, biref_jones *T,
                                         biref_jones *R);

/* Independent reference: the product of the layers' 4x4 Berreman transfer matrices,
 * eigen-decomposed numerically (as biref_slab_jones_tmm, whose codes it returns; the growth
 * limit applies to the whole stack); dispersive layers at lambda_nm (biref_stack_at). */
BIREF_API biref_status biref_stack_jones_tmm(const biref_stack *stack, double theta_rad, double lambda_nm,
                                             biref_jones *T, biref_jones *R);

/* ------------------------------------------------------------------------- */
/* Band integrals (docs/STACKS.md §2)                                         */
/* ------------------------------------------------------------------------- */

typedef struct {
    biref_method method; /* BIREF_METHOD_EXPANSION (default), _NUMERIC or _GROUND_TRUTH */
    int samples;         /* numeric: wavelength samples (default 64) */
    double tolerance;    /* expansion: bound on the truncation error of every intensity (1e-3) */
    int max_groups;      /* expansion: more path groups than this leaving one face: fall back (1024;
                          * the pairs, ~n^2/2 table look-ups, then cost more than the fallback) */
} biref_stack_spectrum_opts;

BIREF_API void biref_stack_spectrum_opts_default(biref_stack_spectrum_opts *o);

/* What the integration did. */
typedef struct {
    int fallback;       /* expansion: 1 when integrated numerically instead; reason says why */
    const char *reason; /* static text, "" when the expansion was used */
    int samples;        /* numeric, ground truth or the fallback: wavelength samples used */
    int groups[2];      /* expansion: path groups leaving through the bottom [0] and the top [1] */
    int legs;           /* expansion: legs followed (the longest path kept) */
    double bound;       /* expansion: the truncation bound reached (fallback: tolerance when two
                         * runs agreed to it, NaN when the largest run was reached first) */
} biref_stack_spectrum_info;

/* Band-normalised XYZ of the four s/p pairs (out) and, when light is not NULL, its detected XYZ
 * (mixed_T, mixed_R; either may be NULL), transmission and reflection of a prepared stack.
 * numeric / ground truth: midpoint samples of the exact Jones matrices. expansion: the stack's
 * response as a sum over path groups (o/e legs per layer, internal reflections, equal optical
 * paths merged), every pair of groups integrated exactly with the S(cos), S(sin) table, paths
 * followed until those still inside bound the error of every intensity by tolerance; where a layer
 * is evanescent, the groups exceed max_groups or the bound is not met, adaptive numeric
 * integration instead (samples doubled from 256 until two runs agree to tolerance), reported in
 * info (may be NULL). Allocates: BIREF_ERR_NOMEM; BIREF_ERR_INVALID for options outside their
 * domain (the analytic method included); BIREF_ERR_ILLCOND for a non-finite result. */
BIREF_API biref_status biref_stack_spectrum(const biref_spectral *sp, const biref_stack_state *st,
                                            const biref_stack_spectrum_opts *opts, const biref_light *light,
                                            biref_spectrum *out, double mixed_T[3], double mixed_R[3],
                                            biref_stack_spectrum_info *info, char *msg, size_t msg_len);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_STACK_H */
