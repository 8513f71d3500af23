/* biref — optics of uniaxial media, interfaces and slabs (paper §3, §4, appendix A). */
#ifndef BIREF_OPTICS_H
#define BIREF_OPTICS_H

#include <stddef.h>
#include <stdint.h>

#include "biref/common.h"

#ifdef __cplusplus
extern "C" {
#endif


/* Polarization indices of isotropic waves and mode indices inside a uniaxial medium. */
enum { BIREF_S = 0, BIREF_P = 1 };
enum { BIREF_O = 0, BIREF_E = 1 };

/* ------------------------------------------------------------------------- */
/* Media                                                                      */
/* ------------------------------------------------------------------------- */

/* A homogeneous, non-magnetic, lossless medium. isotropic != 0 means a single
 * index eta_o (eta_e and axis are ignored); its two modes are s and p. A
 * uniaxial medium's two modes are o and e. axis need not be normalised. */
typedef struct {
    double eta_o;
    double eta_e;
    double axis[3];
    int isotropic;
} biref_medium;

BIREF_API biref_medium biref_medium_isotropic(double eta);
BIREF_API biref_medium biref_medium_uniaxial(double eta_o, double eta_e, const double axis[3]);

/* The unit vector along an optic axis, scaled by its largest component first so that huge or tiny
 * finite axes neither overflow nor underflow. BIREF_ERR_INVALID for a non-finite axis or a zero
 * one (|axis| <= 1e-12). unit may alias axis. */
BIREF_API biref_status biref_axis_normalize(const double axis[3], double unit[3]);

/* Checks a medium; on failure writes a one-line reason into msg (may be NULL). */
BIREF_API biref_status biref_medium_check(const biref_medium *m, char *msg, size_t msg_len);

/* Mode order used in every 4-vector below. */
enum {
    BIREF_MODE_O_DOWN = 0, /* (s for isotropic) travelling towards -y */
    BIREF_MODE_E_DOWN = 1, /* (p for isotropic) */
    BIREF_MODE_O_UP = 2,
    BIREF_MODE_E_UP = 3
};

/* Normal modes of a medium for incidence parameter K (paper §3, eqs. 1–6). */
typedef struct {
    double K;
    biref_complex q[4];         /* normal components of the wave vectors (units of k0) */
    biref_complex E[4][3];      /* unit electric fields, Hermitian norm 1 */
    biref_complex H[4][3];      /* k x E (units of k0 / (mu0 c)) */
    double poynting[4][3];       /* unit time-averaged Poynting directions (eq. 4) */
    double eta_eff[4];           /* |Re k| = sqrt(q^2 + K^2) for propagating modes (eq. 5) */
    double K_max_o, K_max_e;     /* maximal incidence parameters (eq. 6, corrected) */
    int evanescent_o, evanescent_e;
} biref_modes;

/* BIREF_ERR_INVALID: the medium fails biref_medium_check (which says why) or K is negative or
 * not finite. */
BIREF_API biref_status biref_medium_modes(const biref_medium *m, double K, biref_modes *out);

/* Fresnel coefficients of a plane interface between two media (appendix A),
 * obtained by solving the boundary conditions (tangential E and H continuous).
 * All matrices are indexed [incident mode][outgoing mode], each mode index
 * 0/1 meaning s/p in an isotropic medium and o/e in a uniaxial one.
 * Amplitudes refer to the unit mode fields of biref_medium_modes. */
typedef struct {
    biref_complex r_down[2][2]; /* incident from above -> reflected up, upper medium */
    biref_complex t_down[2][2]; /* incident from above -> transmitted down, lower medium */
    biref_complex r_up[2][2];   /* incident from below -> reflected down, lower medium */
    biref_complex t_up[2][2];   /* incident from below -> transmitted up, upper medium */
} biref_interface;

/* BIREF_ERR_INVALID: a medium fails biref_medium_check or K is out of range; BIREF_ERR_SINGULAR:
 * the boundary-condition system is singular. */
BIREF_API biref_status biref_interface_solve(const biref_medium *upper, const biref_medium *lower, double K,
                                             biref_interface *out);

/* ------------------------------------------------------------------------- */
/* Slab                                                                       */
/* ------------------------------------------------------------------------- */

typedef struct {
    double eta_o, eta_e;    /* ordinary / extraordinary index */
    double axis[3];         /* optic axis in the slab frame (normalised by biref) */
    double thickness_nm;    /* d */
    double eta_i;           /* surrounding medium, both sides (1 = vacuum) */
} biref_slab;

/* Checks a slab and an angle; one-line reason into msg. theta must be in [0, pi/2). */
BIREF_API biref_status biref_slab_check(const biref_slab *slab, char *msg, size_t msg_len);
BIREF_API biref_status biref_theta_check(double theta_rad, char *msg, size_t msg_len);

/* 2x2 complex Jones matrix, indexed [input][output] with BIREF_S / BIREF_P. */
typedef struct {
    biref_complex m[2][2];
} biref_jones;

/* Everything about a slab at one incidence angle that does not depend on the
 * wavelength (dispersion ignored, paper §5.1). Plain data; no allocation. */
typedef struct {
    biref_slab slab;
    double theta;
    double K;
    biref_modes modes;          /* inside the slab */
    biref_interface top;        /* ambient (above) -> slab (below), at y = 0 */
    biref_interface bottom;     /* slab (above) -> ambient (below), at y = -d */
    /* Optical path of one vertical crossing of each leg type, in nm: the phase
     * of a leg is (2 pi / lambda) * opl. Complex for evanescent legs. */
    biref_complex opl_down[2]; /* [o, e]: -q_down * d */
    biref_complex opl_up[2];   /* [o, e]:  q_up * d */
    int total_reflection;       /* some mode inside is evanescent (K >= K_max) */
} biref_slab_state;

/* Per-sample entry point (no message buffer, see common.h): BIREF_ERR_INVALID when the slab
 * fails biref_slab_check or the angle biref_theta_check (call them for the reason),
 * BIREF_ERR_SINGULAR when an interface's boundary-condition system is singular. */
BIREF_API biref_status biref_slab_prepare(const biref_slab *slab, double theta_rad, biref_slab_state *st);

/* The same slab lit from the other face: the state in the frame rotated by 180 degrees about z
 * (x -> -x, y -> -y; axis (a, b, c) -> (-a, -b, c)), obtained by relabelling the interface
 * solves already done (each 4x4 solve gives both directions), not by solving again. Exact:
 * equals biref_slab_prepare with the rotated axis, amplitudes included (docs/PHYSICS.md §3).
 * A renderer that needs transmission (light from behind) and reflection (light from the
 * front) at one hit point prepares once and flips. out may not alias in. */
BIREF_API void biref_slab_state_flip(const biref_slab_state *in, biref_slab_state *out);

/* All orders summed in closed form (paper eq. 17, and its reflection analogue).
 * Transmission is referred to the plane y = -d, reflection to y = 0.
 * Either output may be NULL. */
BIREF_API void biref_slab_jones_at(const biref_slab_state *st, double lambda_nm, biref_jones *T, biref_jones *R);

/* One-call convenience: prepare + evaluate. The codes of biref_slab_prepare, and
 * BIREF_ERR_INVALID for a wavelength that is not a positive finite number. */
BIREF_API biref_status biref_slab_jones(const biref_slab *slab, double theta_rad, double lambda_nm, biref_jones *T,
                                        biref_jones *R);

/* Independent reference: 4x4 Berreman transfer matrix of the same slab,
 * eigen-decomposed numerically (LAPACK). Same planes and bases as above.
 * Returns BIREF_ERR_ILLCOND when evanescent growth makes it untrustworthy, BIREF_ERR_SINGULAR
 * when LAPACK finds the eigenvector matrix singular, BIREF_ERR_INVALID for arguments that fail
 * biref_slab_check, biref_theta_check or a positive finite wavelength. */
BIREF_API biref_status biref_slab_jones_tmm(const biref_slab *slab, double theta_rad, double lambda_nm, biref_jones *T,
                                            biref_jones *R);

/* Power fractions |J[in][out]|^2 (same medium on both sides, paper §4). */
BIREF_API void biref_jones_intensity(const biref_jones *J, double out[2][2]);

/* The path expansion (paper §4, eqs. 12–16). A path is a sequence of legs
 * inside the slab; order n = number of internal double reflections.
 * Transmission order n has n+1 down legs and n up legs; reflection order n
 * (n >= 1) has n down and n up legs; reflection order 0 is the direct
 * reflection off the top surface. */
typedef struct {
    biref_complex amp[2][2];  /* [input s/p][output s/p], wavelength independent */
    biref_complex opl_nm;     /* phase = 2 pi / lambda * opl_nm */
    uint32_t legs;             /* bit i set: leg i (in travel order) is extraordinary */
    uint8_t order;
    uint8_t n_down_e, n_up_e;  /* counts of extraordinary down / up legs */
    uint8_t n_legs;
} biref_path;

enum { BIREF_TRANSMISSION = 0, BIREF_REFLECTION = 1 };

/* Number of paths of orders 0..max_order (max_order <= 12). */
BIREF_API size_t biref_path_count(int which, int max_order);

/* Writes the paths of orders 0..max_order into out (capacity cap) in order of
 * increasing order; returns the number written or 0 if cap is too small. */
BIREF_API size_t biref_slab_paths(const biref_slab_state *st, int which, int max_order, biref_path *out, size_t cap);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_OPTICS_H */
