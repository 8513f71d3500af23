/* biref — stacks of homogeneous layers (isotropic or uniaxial, each with its own optic axis)
 * between the same isotropic medium above and below: wave-plate filters, cellophane art, films on
 * glass, plates whose stress varies through the thickness. Exact Jones matrices per wavelength
 * (docs/STACKS.md), a 4x4 transfer-matrix reference and stack files.
 *
 * Frame and bases as for a slab (docs/CONVENTIONS.md): the light enters the first layer at
 * y = 0, the layers follow downwards, transmitted amplitudes refer to the bottom face of the last
 * layer. Plain data, no global state; the prepared state is immutable and may be shared. */
#ifndef BIREF_STACK_H
#define BIREF_STACK_H

#include <stddef.h>

#include "biref/common.h"
#include "biref/optics.h"
#include "biref/polarization.h"
#include "biref/spectral.h"

#ifdef __cplusplus
extern "C" {
#endif

#define BIREF_STACK_MAX_LAYERS 64

/* One layer. isotropic != 0: index eta_o (eta_e and axis ignored). Otherwise uniaxial with
 * ordinary / extraordinary indices and an optic axis in the slab frame (need not be unit). */
typedef struct {
    double eta_o, eta_e;
    double axis[3];
    double thickness_nm;
    int isotropic;
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

/* Stack files (docs/STACKS.md): {"eta_i": 1.0, "layers": [{...}, ...]}, strict JSON (unknown or
 * repeated keys are errors). A layer is {"eta": n} or {"eta_o", "eta_e", "axis": [x, y, z]} or
 * {"eta_o", "eta_e", "azimuth_deg": phi} (optic axis in the surface, at phi from x towards z),
 * with exactly one of thickness_nm, thickness_um, thickness_mm. Errors name the JSON path. */
BIREF_API biref_status biref_stack_parse(const char *text, size_t len, biref_stack *out, char *msg, size_t msg_len);
/* BIREF_ERR_IO when the file cannot be read; otherwise as biref_stack_parse. */
BIREF_API biref_status biref_stack_load(const char *path, biref_stack *out, char *msg, size_t msg_len);

/* Everything about a stack at one angle of incidence that does not depend on the wavelength.
 * Interface j separates medium j (above) from medium j + 1 (below); medium 0 and medium
 * n_layers + 1 are the surround. Plain data (about 24 KB), no allocation. */
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
} biref_stack_state;

/* Per-sample entry point: BIREF_ERR_INVALID when the stack fails biref_stack_check or the angle
 * biref_theta_check, BIREF_ERR_SINGULAR when an interface's boundary system is singular. */
BIREF_API biref_status biref_stack_prepare(const biref_stack *stack, double theta_rad, biref_stack_state *st);

/* All orders of internal reflection in every layer, summed exactly (docs/STACKS.md: the
 * transfer matrix in its scattering form). Either output may be NULL. */
BIREF_API void biref_stack_jones_at(const biref_stack_state *st, double lambda_nm, biref_jones *T, biref_jones *R);

/* prepare + evaluate; the codes of biref_stack_prepare, BIREF_ERR_INVALID for a bad wavelength. */
BIREF_API biref_status biref_stack_jones(const biref_stack *stack, double theta_rad, double lambda_nm, biref_jones *T,
                                         biref_jones *R);

/* Independent reference: the product of the layers' 4x4 Berreman transfer matrices,
 * eigen-decomposed numerically (as biref_slab_jones_tmm, whose codes it returns; the growth
 * limit applies to the whole stack). */
BIREF_API biref_status biref_stack_jones_tmm(const biref_stack *stack, double theta_rad, double lambda_nm,
                                             biref_jones *T, biref_jones *R);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_STACK_H */
