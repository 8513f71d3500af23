/*
 * biref — photoelasticity: plane-stress fields in a plate, the stress-optic law, and the
 * plate seen at normal incidence in a plane or circular polariscope (docs/PHOTOELASTICITY.md).
 *
 * Units: SI throughout (metres, pascals, newtons); wavelengths in nm like the rest of biref.
 *
 * Plate frame. The plate lies in the (x, y) plane of the picture, x to the right and y up as
 * seen by an observer looking at the light source through the plate. At normal incidence this
 * is the slab frame of docs/CONVENTIONS.md with x = s and y = p (s x p = k points at the
 * observer), so an angle "from x towards y" is an angle from s towards p: counter-clockwise
 * in the picture. In the slab frame the in-plane direction at angle phi is the optic axis
 * (cos phi, 0, sin phi).
 *
 * No global mutable state; everything here is re-entrant. A biref_pe_grid is immutable after
 * loading and may be shared by threads.
 */
#ifndef BIREF_PHOTOELASTIC_H
#define BIREF_PHOTOELASTIC_H

#include <stddef.h>

#include "biref/common.h"
#include "biref/integrator.h"
#include "biref/spectral.h"
#include "biref/stack.h"

#ifdef __cplusplus
extern "C" {
#endif

/* 1 Brewster = 1e-12 m^2/N = 1e-12 / Pa. */
#define BIREF_BREWSTER 1e-12

/* ------------------------------------------------------------------------ */
/* Material and stress-optic law                                             */
/* ------------------------------------------------------------------------ */

/* n1 - n2 = C (sigma1 - sigma2) (relative stress-optic law, plane stress). Dispersion of
 * birefringence (docs/PHOTOELASTICITY.md, "Dispersion of birefringence"): C(λ) = C_per_Pa
 * (lambda_ref_nm / λ)^dispersion_alpha; alpha 0 (every preset's default) is no dispersion, C the
 * same at every wavelength, and gives the pictures of a constant C exactly. */
typedef struct {
    const char *name;        /* preset name, or "custom" */
    const char *source;      /* where the numbers come from (preset), or "user" */
    double n0;               /* index of the unstressed material */
    double C_per_Pa;         /* relative stress-optic coefficient C in 1/Pa (> 0), at lambda_ref_nm */
    double lambda_ref_nm;    /* where C_per_Pa holds; 0 means BIREF_PE_LAMBDA_REF_NM */
    double dispersion_alpha; /* exponent of C(λ); 0: none */
} biref_pe_material;

/* The wavelength of the presets' C (the mercury-green line of the fringe-value tables), nm. */
#define BIREF_PE_LAMBDA_REF_NM 546.1

/* C(λ) in 1/Pa: C_per_Pa (lambda_ref / λ)^alpha; exactly C_per_Pa when alpha is 0. */
BIREF_API double biref_pe_C_at(const biref_pe_material *m, double lambda_nm);

/* Presets: "polycarbonate", "epoxy", "pmma", "glass". BIREF_ERR_INVALID for other names. */
BIREF_API biref_status biref_pe_material_preset(const char *name, biref_pe_material *out);
/* The i-th preset (i < biref_pe_material_count()), for listings. */
BIREF_API size_t biref_pe_material_count(void);
BIREF_API const biref_pe_material *biref_pe_material_at(size_t i);
/* Checks n0 and C (finite, n0 >= 1, C > 0), lambda_ref_nm (0 or 200-2000 nm) and alpha (-1 to 3);
 * one-line reason into msg. */
BIREF_API biref_status biref_pe_material_check(const biref_pe_material *m, char *msg, size_t msg_len);
/* Material fringe constant f_sigma = lambda / C(lambda) in N/m: N = h (sigma1 - sigma2) / f_sigma. */
BIREF_API double biref_pe_fringe_constant(const biref_pe_material *m, double lambda_nm);

/* In-plane stress tensor (plane stress, sigma_zz = tau_xz = tau_yz = 0), Pa. */
typedef struct {
    double sxx, syy, txy;
} biref_pe_stress;

/* Principal stresses s1 >= s2 and the direction of s1 at angle phi (radians, from x towards
 * y, in (-pi/2, pi/2]). For an isotropic state (s1 == s2) phi = 0. */
typedef struct {
    double s1, s2;
    double phi;
    double cos2phi, sin2phi; /* of 2 phi, without trigonometry */
} biref_pe_principal;

BIREF_API void biref_pe_principal_of(const biref_pe_stress *s, biref_pe_principal *out);

/* The uniaxial slab that models the plate at one point (docs/PHOTOELASTICITY.md, "Model"):
 * optic axis in the plate plane along principal direction 1, eta_e = n1 = n0 + C (s1 - s2),
 * eta_o = n2 = n0; thickness h; surrounding index eta_i. */
BIREF_API biref_slab biref_pe_slab_at(const biref_pe_material *m, double thickness_m, double eta_i,
                                      const biref_pe_principal *p);

/* For oblique viewing: the uniaxial slab closest to the biaxial plate. The true third index
 * n3 = n0 + C2 (s1 + s2) differs from n2 by -C s2 and from n1 by -C s1 (docs, "Model"); the axis
 * goes along the principal direction whose stress is larger in magnitude, so that the two
 * indices the model makes equal are the two closest ones. At normal incidence this is the same
 * optical element as biref_pe_slab_at (up to a common index shift). */
BIREF_API biref_slab biref_pe_slab_best(const biref_pe_material *m, double thickness_m, double eta_i,
                                        const biref_pe_principal *p);

/* ------------------------------------------------------------------------ */
/* Stress through the thickness (stack.h)                                    */
/* ------------------------------------------------------------------------ */

/* A plate of thickness h whose plane stress varies through its thickness: n_layers equal layers
 * (1 .. BIREF_STACK_MAX_LAYERS), layer k (from the face the light enters) under stress[k], each the
 * slab of biref_pe_slab_at, as a stack (docs/STACKS.md §3). With fixed principal directions the
 * retardations add (integrated photoelasticity); rotating directions change the picture. */
BIREF_API biref_status biref_pe_stack(const biref_pe_material *m, double thickness_m, double eta_i, int n_layers,
                                      const biref_pe_stress *stress, biref_stack *out, char *msg, size_t msg_len);
/* The same plate at one wavelength with C(lambda_nm) (dispersion of birefringence, docs/
 * PHOTOELASTICITY.md §17): with alpha != 0 the layers' indices depend on the wavelength, so a
 * white-light picture builds the stack at every sample wavelength. biref_pe_stack is this at the
 * material's reference wavelength. */
BIREF_API biref_status biref_pe_stack_at(const biref_pe_material *m, double thickness_m, double eta_i, int n_layers,
                                         const biref_pe_stress *stress, double lambda_nm, biref_stack *out, char *msg,
                                         size_t msg_len);

/* ------------------------------------------------------------------------ */
/* Stress fields (closed forms)                                              */
/* ------------------------------------------------------------------------ */

/* Disk of radius R and thickness h under diametral compression P (N) applied at (0, +-R):
 * two Flamant point loads plus uniform tension P / (pi R h) (Frocht; Timoshenko & Goodier).
 * Meaningful for x^2 + y^2 <= R^2; infinite at the load points. */
BIREF_API void biref_pe_disk_stress(double R, double h, double P, double x, double y, biref_pe_stress *out);

/* Infinite plate with a circular hole of radius a at the origin under remote uniaxial tension
 * S (Pa) along x (Kirsch 1898). Meaningful for x^2 + y^2 >= a^2. */
BIREF_API void biref_pe_kirsch_stress(double a, double S, double x, double y, biref_pe_stress *out);

/* Beam of depth H (along y, centred on y = 0) and thickness h in pure bending by a moment M
 * (N m): sigma_xx = M y / I with I = h H^3 / 12; positive M stretches the fibres at y > 0. */
BIREF_API void biref_pe_beam_stress(double H, double h, double M, double x, double y, biref_pe_stress *out);

/* A user-supplied field on a regular grid (CSV, see biref_pe_grid_parse). */
typedef struct biref_pe_grid biref_pe_grid;

/* Parses CSV text: a header naming the five columns x_mm, y_mm, sxx_MPa, syy_MPa, txy_MPa
 * (any order, no others), then one row per grid node (any order) of a full regular grid of
 * at least 2 x 2 nodes. Blank lines and lines starting with '#' are ignored; CR LF accepted.
 * On failure: BIREF_ERR_INVALID and one line "line N: reason" (or "reason" when no line is
 * to blame) in msg. */
BIREF_API biref_status biref_pe_grid_parse(const char *text, size_t len, biref_pe_grid **out, char *msg, size_t msg_len);
/* Reads and parses a file; BIREF_ERR_IO with "cannot read: ..." if it cannot be read. */
BIREF_API biref_status biref_pe_grid_load(const char *path, biref_pe_grid **out, char *msg, size_t msg_len);
BIREF_API void biref_pe_grid_destroy(biref_pe_grid *g);
/* Grid extent in metres: xmin, xmax, ymin, ymax; and the node counts. */
BIREF_API void biref_pe_grid_bounds(const biref_pe_grid *g, double bounds[4]);
BIREF_API void biref_pe_grid_size(const biref_pe_grid *g, int *nx, int *ny);
/* Bilinear interpolation; returns 0 (and leaves out untouched) outside the grid's extent. */
BIREF_API int biref_pe_grid_stress(const biref_pe_grid *g, double x, double y, biref_pe_stress *out);

/* Scattered nodes from a finite-element export, interpolated over their Delaunay triangulation
 * (linear in each triangle); see "Nodes" below. */
typedef struct biref_pe_mesh biref_pe_mesh;

typedef enum {
    BIREF_PE_DISK = 0,
    BIREF_PE_HOLE = 1,
    BIREF_PE_BEAM = 2,
    BIREF_PE_GRID = 3,
    BIREF_PE_NODES = 4
} biref_pe_field_kind;

/* A plate: its stress field and outline. The picture shows frame[] (xmin, xmax, ymin, ymax);
 * points outside the material show the polariscope without a specimen. */
typedef struct {
    biref_pe_field_kind kind;
    double thickness;   /* plate thickness h, m */
    double radius;      /* disk: R; hole: a (m) */
    double load;        /* disk: P (N, compressive) */
    double stress;      /* hole: remote tension S (Pa) */
    double moment;      /* beam: M (N m) */
    double depth;       /* beam: H (m) */
    double width, height; /* hole: plate sides (m); beam: length (width) */
    double angle;       /* hole: direction of the remote tension from x towards y (rad) */
    const biref_pe_grid *grid; /* grid: borrowed */
    const biref_pe_mesh *mesh; /* nodes: borrowed */
    double frame[4];
} biref_pe_field;

/* Fills f for a preset with the given parameters and a frame that shows the whole part (disk:
 * 2R plus a 4 % margin; hole: the plate; beam: the length times 1.5 H). One-line reason into
 * msg for non-positive or non-finite parameters, a hole not inside its plate, etc. */
BIREF_API biref_status biref_pe_field_disk(biref_pe_field *f, double R, double h, double P, char *msg, size_t msg_len);
BIREF_API biref_status biref_pe_field_hole(biref_pe_field *f, double a, double width, double height, double h, double S,
                                           double angle, char *msg, size_t msg_len);
BIREF_API biref_status biref_pe_field_beam(biref_pe_field *f, double length, double H, double h, double M, char *msg,
                                           size_t msg_len);
BIREF_API biref_status biref_pe_field_grid(biref_pe_field *f, const biref_pe_grid *g, double h, char *msg, size_t msg_len);
/* Nodes: the frame is the bounding box of the triangulation. */
BIREF_API biref_status biref_pe_field_nodes(biref_pe_field *f, const biref_pe_mesh *m, double h, char *msg, size_t msg_len);

/* Stress at (x, y); returns 1 inside the material, 0 outside (out untouched). */
BIREF_API int biref_pe_field_stress(const biref_pe_field *f, double x, double y, biref_pe_stress *out);

/* ------------------------------------------------------------------------ */
/* Polariscope and light                                                     */
/* ------------------------------------------------------------------------ */

typedef enum { BIREF_PE_PLANE = 0, BIREF_PE_CIRCULAR = 1 } biref_pe_polariscope_kind;
typedef enum { BIREF_PE_DARK = 0, BIREF_PE_LIGHT = 1 } biref_pe_field_type;

/* Ideal achromatic polariscope: the light leaving the input side (polarizer, and quarter-wave
 * plate for a circular polariscope) as a coherency matrix C, and the output side (quarter-wave
 * plate and analyzer) as a projector P onto the unit Jones vector u (s/p basis; P = conj(u) u^T,
 * biref_analyzer_linear / biref_analyzer_circular). The input light has unit intensity. */
typedef struct {
    biref_complex C[2][2];
    biref_complex P[2][2];
    biref_complex u[2];
} biref_pe_polariscope;

/* Plane: polarizer at angle psi from x towards y; analyzer crossed (dark) or parallel (light).
 * Circular: polarizer, quarter-wave plate at 45 deg to it, specimen, quarter-wave plate,
 * analyzer. With ideal achromatic plates the light reaching the specimen is circular (here
 * S3 = +1, whatever psi) and the output side is a circular analyzer that blocks it (dark
 * field, handedness -1) or passes it (light field, +1); psi then changes nothing. */
BIREF_API void biref_pe_polariscope_make(biref_pe_polariscope_kind kind, biref_pe_field_type field, double psi_rad,
                                         biref_pe_polariscope *out);
/* Any polarized input (Stokes, S0 = 1 for unit intensity) and analyzer projector P (a rank-one
 * projector such as biref_analyzer_*). BIREF_ERR_INVALID for unphysical Stokes vectors or a
 * P that is not a unit-vector projector. */
BIREF_API biref_status biref_pe_polariscope_custom(const double stokes[4], const biref_complex P[2][2],
                                                   biref_pe_polariscope *out);
/* Detected intensity with no specimen: u^H C u. */
BIREF_API double biref_pe_polariscope_background(const biref_pe_polariscope *pol);

typedef enum { BIREF_PE_WHITE = 0, BIREF_PE_MONO = 1 } biref_pe_light_kind;

/* Everything about one picture except the stress field. */
typedef struct {
    biref_pe_material material;
    double thickness;      /* h, m */
    double eta_i;          /* surrounding index (1 = air; n0 = index-matched immersion) */
    biref_pe_polariscope pol;
    biref_pe_light_kind light;
    double lambda_nm;      /* monochromatic wavelength */
} biref_pe_setup;

/* Retardation (n1 - n2) h in nm and fringe order N = (n1 - n2) h / lambda = h C (s1 - s2) / lambda,
 * with C at the material's reference wavelength; _at: with C(lambda_nm) (the same without dispersion). */
BIREF_API double biref_pe_retardation_nm(const biref_pe_setup *s, const biref_pe_principal *p);
BIREF_API double biref_pe_retardation_at_nm(const biref_pe_setup *s, const biref_pe_principal *p, double lambda_nm);
/* The model's retardation on the oblique path at theta (the plate turned about x, as in
 * biref_pe_shade_oblique): |Re(opl_e - opl_o)| of one crossing of biref_pe_slab_best; equals
 * biref_pe_retardation_nm at theta = 0. NAN if the slab cannot be prepared. */
BIREF_API double biref_pe_retardation_oblique_nm(const biref_pe_setup *s, const biref_pe_principal *p, double theta_rad);

/* Fast path (docs/PHOTOELASTICITY.md, "Fast path"): at normal incidence with the axis in the
 * plane the o and e modes do not mix, J_T = t_e a a^T + t_o b b^T (a, b the principal
 * directions), and the detected intensity is alpha <|t_e|^2> + beta <|t_o|^2> + 2 Re(gamma
 * <t_e conj t_o>). Multiple reflections interfere within an order only (the source's coherence
 * length is far below the plate's round trip 2 n h): white light needs S(cos), S(sin) of the
 * path differences (2m + 1) delta, m = 0, 1, 2 (biref_spectral_phase_integrals); monochromatic
 * light is the closed-form geometric series. White: band-normalised XYZ (white E = (1,1,1));
 * mono: xyz[0] = xyz[1] = xyz[2] = intensity. sp may be NULL for monochromatic light. */
BIREF_API void biref_pe_shade(const biref_pe_setup *s, const biref_spectral *sp, const biref_pe_principal *p, double xyz[3]);

/* The same point by the general machinery, for verification: biref_slab_prepare on
 * biref_pe_slab_at, then white: the expansion integrator (every interference term, adaptive
 * order; the same as biref_pe_shade_integrated with a BIREF_METHOD_EXPANSION integrator); mono: |e J_T P|^2 of the closed-form Jones matrix at lambda_nm, averaged over
 * `thickness_jitter` uniform thickness samples spanning thickness_span_nm (0 or 1 sample: the
 * coherent value at the nominal thickness). */
BIREF_API biref_status biref_pe_shade_general(const biref_pe_setup *s, const biref_spectral *sp, const biref_pe_principal *p,
                                              int thickness_jitter, double thickness_span_nm, double xyz[3]);

/* Oblique viewing (the plate turned about its x axis by theta, so that the plane of incidence
 * contains the plate's y axis and normal; polarizer and analyzer stay perpendicular to the line
 * of sight, their angles measured from s = x towards p). The general path on biref_pe_slab_best:
 * monochromatic by the path expansion to order 2, paths coherent within an order and orders added
 * in intensity (docs, "Coherence"). An approximation beyond normal incidence:
 * docs/PHOTOELASTICITY.md, "How it degrades". Deprecated for white light: it builds an expansion
 * integrator per call; create one integrator and call biref_pe_shade_integrated instead. */
BIREF_API biref_status biref_pe_shade_oblique(const biref_pe_setup *s, const biref_spectral *sp, const biref_pe_principal *p,
                                              double theta_rad, double xyz[3]);

/* The polariscope as a light (integrator.h): its coherency C and analyzer P. */
BIREF_API void biref_pe_light(const biref_pe_polariscope *pol, biref_light *out);

/* The one integration interface of photoelasticity: white light through any integrator, at
 * normal incidence (theta 0: biref_pe_slab_at, the model of biref_pe_shade_general) or oblique
 * (biref_pe_slab_best, as biref_pe_shade_oblique; the pictures' tilted path). The analytic method refuses a polariscope's light (it handles the
 * paper's s/p model only). BIREF_ERR_INVALID for monochromatic light. */
BIREF_API biref_status biref_pe_shade_integrated(const biref_pe_setup *s, const biref_integrator *it,
                                                 const biref_pe_principal *p, double theta_rad, double xyz[3]);

/* ------------------------------------------------------------------------ */
/* Pictures                                                                  */
/* ------------------------------------------------------------------------ */

typedef struct {
    int width, height;  /* pixels; the frame is mapped with square pixels if the caller chose so */
    int supersample;    /* k x k samples per pixel (box filter), 1..BIREF_PE_MAX_SUPERSAMPLE */
    int threads;        /* OpenMP threads, 0 = default */
    double tint[3];     /* mono only: XYZ the intensity multiplies (white E = (1,1,1)) */
    double tilt;        /* 0: normal view (fast path); else biref_pe_shade_oblique at this angle (rad) */
    biref_progress_fn progress; /* NULL = none; called after each finished row */
    void *progress_user;
} biref_pe_image_opts;

#define BIREF_PE_MAX_SUPERSAMPLE 64
/* Largest picture side in pixels and largest tilt of the view (degrees). */
#define BIREF_PE_MAX_SIDE 8192
#define BIREF_PE_MAX_TILT_DEG 80.0

/* Renders field f seen through setup s: XYZ floats (3 per pixel, row-major, top row = frame's
 * ymax), white E = (1,1,1); the frame (plate coordinates) fills the image, so with a tilt the
 * caller foreshortens the height by cos(tilt) to keep square pixels. sp is required for white
 * light. Deterministic and independent of the thread count. BIREF_ERR_INVALID for a tilt outside
 * [0, 89 deg]. */
BIREF_API biref_status biref_pe_render(const biref_pe_setup *s, const biref_spectral *sp, const biref_pe_field *f,
                                       const biref_pe_image_opts *opt, float *xyz, char *msg, size_t msg_len);

/* The same picture with each sample's fringes averaged over its footprint in retardation (the
 * retardation's change to the next sample; docs/ANTIALIASING.md, "Photoelastic pictures"): no
 * moire where the fringes crowd, at one sample per pixel. Normal view only (a tilt renders as
 * biref_pe_render). */
BIREF_API biref_status biref_pe_render_prefiltered(const biref_pe_setup *s, const biref_spectral *sp,
                                                   const biref_pe_field *f, const biref_pe_image_opts *opt, float *xyz,
                                                   char *msg, size_t msg_len);

/* ------------------------------------------------------------------------ */
/* Nodes from a finite-element export                                        */
/* ------------------------------------------------------------------------ */

/* Column names and units of a node table (docs/PHOTOELASTICITY.md, "Stress from FEA nodes").
 * Names are matched case-insensitively; other columns are ignored. */
typedef struct {
    const char *x, *y, *sxx, *syy, *txy;
    double length_m;  /* metres per length unit of the file (1e-3 for mm) */
    double stress_pa; /* pascals per stress unit of the file (1e6 for MPa) */
} biref_pe_node_format;

/* Names x, y, sxx, syy, txy; millimetres; MPa. */
BIREF_API void biref_pe_node_format_default(biref_pe_node_format *f);

/* Parses a node table: a header line naming the columns, then one row per node. Fields are
 * separated by commas (or, if the header has none, semicolons, else tabs/spaces); '#' comments,
 * blank lines, CR LF and a UTF-8 byte-order mark are accepted. Nodes at the same position (as
 * element-wise exports repeat them) are merged with their stresses averaged. The nodes are
 * triangulated (Delaunay, qhull) and interpolated linearly in each triangle. On failure one line
 * naming the row and column, e.g. "line 7, column syy (S22): not a number: 'abc'". */
BIREF_API biref_status biref_pe_mesh_parse(const char *text, size_t len, const biref_pe_node_format *fmt, biref_pe_mesh **out,
                                 char *msg, size_t msg_len);
BIREF_API biref_status biref_pe_mesh_load(const char *path, const biref_pe_node_format *fmt, biref_pe_mesh **out, char *msg,
                                size_t msg_len);
/* Adds a boundary: one or more closed polygons, one vertex "x,y" (or "x y") per line, polygons
 * separated by blank lines, an optional header; the material is inside by the even-odd rule
 * (an outline plus the outlines of its holes). length_m as in biref_pe_node_format. */
BIREF_API biref_status biref_pe_mesh_boundary_parse(biref_pe_mesh *m, const char *text, size_t len, double length_m, char *msg,
                                          size_t msg_len);
BIREF_API biref_status biref_pe_mesh_boundary_load(biref_pe_mesh *m, const char *path, double length_m, char *msg,
                                         size_t msg_len);
BIREF_API void biref_pe_mesh_destroy(biref_pe_mesh *m);

/* Finite elements of a solver's own mesh (biref_pe_mesh_from_elements, biref_pe_frd_parse). */
typedef enum {
    BIREF_PE_TRI3 = 0,  /* linear triangle (CPS3, VTK_TRIANGLE) */
    BIREF_PE_TRI6 = 1,  /* quadratic triangle (CPS6, VTK_QUADRATIC_TRIANGLE) */
    BIREF_PE_QUAD4 = 2, /* bilinear quadrilateral (CPS4, VTK_QUAD) */
    BIREF_PE_QUAD8 = 3, /* serendipity quadrilateral (CPS8, VTK_QUADRATIC_QUAD) */
    BIREF_PE_QUAD9 = 4  /* Lagrange quadrilateral (VTK_BIQUADRATIC_QUAD) */
} biref_pe_element_type;
#define BIREF_PE_ELEMENT_TYPES 5
/* Nodes per element: 3, 6, 4, 8, 9 (0 for an unknown type). */
BIREF_API int biref_pe_element_nodes(biref_pe_element_type t);

/* A plane mesh with nodal stresses. Node order in each element as in VTK, CalculiX, Abaqus and
 * gmsh: the corners in turn (either sense), then the mid-side nodes of edges 01, 12, 20 (quads:
 * 01, 12, 23, 30), then the centre (QUAD9). Elements may have curved edges (mid-side nodes off the
 * chord): the interpolation is isoparametric. */
typedef struct {
    size_t nodes;
    const double *xy;     /* [nodes][2], m */
    const double *stress; /* [nodes][3]: sxx, syy, txy, Pa */
    size_t elements;
    const int *type;      /* [elements], biref_pe_element_type */
    const size_t *conn;   /* the node indices (from 0) of each element in turn */
} biref_pe_elements;
/* Builds a mesh interpolated inside each element with its shape functions; points in no element
 * have no material (holes and concave outlines need no boundary). The arrays are copied. One line
 * in msg for an unknown type, an index beyond the nodes, an element without area, a non-finite or
 * out-of-range value (coordinates beyond 1000 m, stresses beyond 1e12 Pa), more than 50 million
 * nodes or elements. */
BIREF_API biref_status biref_pe_mesh_from_elements(const biref_pe_elements *e, biref_pe_mesh **out, char *msg,
                                                   size_t msg_len);

/* Names of a CalculiX result file's stress components; units as in biref_pe_node_format. */
typedef struct {
    const char *sxx, *syy, *txy; /* components of the result block (default SXX, SYY, SXY) */
    double length_m, stress_pa;
} biref_pe_frd_format;
/* SXX, SYY, SXY; millimetres; MPa. */
BIREF_API void biref_pe_frd_format_default(biref_pe_frd_format *f);
/* Parses a CalculiX .frd result file (ASCII; docs/PHOTOELASTICITY.md, "CalculiX"): its nodes, its
 * plane elements (tr3, tr6, qu4, qu8) and the last result block holding the three named
 * components (the last increment's nodal stresses). Refuses 3-D solid elements and nodes out of
 * one z plane with one line saying what to export instead. */
BIREF_API biref_status biref_pe_frd_parse(const char *text, size_t len, const biref_pe_frd_format *fmt,
                                          biref_pe_mesh **out, char *msg, size_t msg_len);
BIREF_API biref_status biref_pe_frd_load(const char *path, const biref_pe_frd_format *fmt, biref_pe_mesh **out,
                                         char *msg, size_t msg_len);

typedef struct {
    size_t rows;       /* data rows read (elements: the nodes) */
    size_t nodes;      /* distinct positions */
    size_t triangles;  /* non-degenerate Delaunay triangles (node tables; 0 for elements) */
    size_t elements;   /* elements interpolated (Delaunay triangles or the solver's) */
    size_t by_type[BIREF_PE_ELEMENT_TYPES]; /* elements of each biref_pe_element_type */
    size_t loops;      /* boundary polygons (0: none) */
    size_t loop_vertices;
} biref_pe_mesh_info;
/* Nodes inside window (xmin, xmax, ymin, ymax, m; NULL: anywhere) and inside the boundary if
 * there is one: 0 means the boundary or the window misses the mesh. */
BIREF_API size_t biref_pe_mesh_nodes_inside(const biref_pe_mesh *m, const double window[4]);
BIREF_API void biref_pe_mesh_get_info(const biref_pe_mesh *m, biref_pe_mesh_info *out);
/* Bounding box of the triangulation (xmin, xmax, ymin, ymax), m. */
BIREF_API void biref_pe_mesh_bounds(const biref_pe_mesh *m, double b[4]);
/* Linear interpolation in the triangle holding (x, y); returns 0 outside the triangulation or
 * outside the boundary ("no material"), leaving out untouched. Thread-safe. */
BIREF_API int biref_pe_mesh_stress(const biref_pe_mesh *m, double x, double y, biref_pe_stress *out);

/* ------------------------------------------------------------------------ */
/* Full-field maps                                                           */
/* ------------------------------------------------------------------------ */

typedef enum {
    BIREF_PE_MAP_FRINGE_ORDER = 0, /* N = h C (s1 - s2) / lambda */
    BIREF_PE_MAP_ISOCLINIC = 1,    /* direction of s1, degrees from x towards y, (-90, 90] */
    BIREF_PE_MAP_RETARDATION = 2,  /* h C (s1 - s2), nm */
    BIREF_PE_MAP_SIGMA1 = 3,       /* MPa */
    BIREF_PE_MAP_SIGMA2 = 4        /* MPa */
} biref_pe_map_kind;
#define BIREF_PE_MAP_COUNT 5

/* "fringe-order", "isoclinic", "retardation", "sigma1", "sigma2"; and the unit ("1", "deg",
 * "nm", "MPa"). from_name: BIREF_ERR_INVALID for other names. */
BIREF_API const char *biref_pe_map_name(biref_pe_map_kind k);
BIREF_API const char *biref_pe_map_unit(biref_pe_map_kind k);
BIREF_API biref_status biref_pe_map_from_name(const char *name, biref_pe_map_kind *out);
/* One value of a map at a point with principal stresses p (fringe order at lambda_nm). */
BIREF_API double biref_pe_map_value(biref_pe_map_kind k, const biref_pe_setup *s, double lambda_nm, const biref_pe_principal *p);
/* The map on the pixel grid of biref_pe_render (one sample at each pixel centre, top row =
 * frame's ymax), NAN where there is no material. */
BIREF_API biref_status biref_pe_render_map(const biref_pe_setup *s, const biref_pe_field *f, biref_pe_map_kind k,
                                 double lambda_nm, int width, int height, int threads, float *out, char *msg,
                                 size_t msg_len);

/* ------------------------------------------------------------------------ */
/* Phase stepping                                                            */
/* ------------------------------------------------------------------------ */

/* One image of a phase-stepped circular polariscope: input polarizer and quarter-wave plate fixed
 * (circular light, S3 = +1 as biref_pe_polariscope_make), output quarter-wave plate with its fast
 * axis at qwp and analyzer at analyzer (degrees from x towards y). stokes: the state the output
 * side passes. For an ideal retarder of retardation delta = 2 pi N with s1 along phi the image is
 *   I = Ib + Ia/2 (1 + a3 cos delta + sin delta (a2 cos 2phi - a1 sin 2phi)),  a = stokes[1..3]
 * (docs/PHOTOELASTICITY.md, "Phase stepping"). */
typedef struct {
    double qwp_deg, analyzer_deg;
    double stokes[4];
} biref_pe_step;

/* The settings of the n-step method, n = 6 (Patterson & Wang's six settings) or 4 (the first four
 * of them); returns n, or 0 for any other n. */
BIREF_API int biref_pe_phase_steps(int n, biref_pe_step out[6]);
/* The polariscope of one step (ideal achromatic elements). */
BIREF_API void biref_pe_polariscope_stepped(double qwp_rad, double analyzer_rad, biref_pe_polariscope *out);

typedef struct {
    double ref_x, ref_y; /* pixel (column, row from the top) of known fringe order */
    double ref_order;    /* fringe order there (0 for a zero-order point), |ref_order| <= 1e5 */
    double min_modulation; /* pixels with Ia below this fraction of the largest Ia are masked */
} biref_pe_demod_opts;

/* Output planes (width x height floats each; any may be NULL); NAN where masked. */
typedef struct {
    float *isoclinic_deg; /* direction of s1, (-90, 90] */
    float *phase_wrapped; /* isochromatic phase 2 pi N modulo 2 pi, [0, 2 pi) */
    float *fringe_order;  /* unwrapped N */
    float *modulation;    /* Ia */
    float *background;    /* Ib */
} biref_pe_demod_maps;

/* Recovers the isoclinic angle and the isochromatic phase from an n-step image set (n = 4 or 6,
 * in the order of biref_pe_phase_steps) and unwraps the phase from the reference pixel
 * (quality-guided flood fill that keeps the isoclinic continuous, so that the pi/2 ambiguity of
 * the isoclinic and the sign of the phase are resolved together). The set leaves one global sign
 * open (s1 and s2 swapped, N mirrored about the reference); it is chosen so that the fewest
 * pixels have N < -1/4 (fringe orders are never negative). One-line reason into msg. */
BIREF_API biref_status biref_pe_demodulate(int n, const float *const images[], int width, int height,
                                 const biref_pe_demod_opts *o, const biref_pe_demod_maps *out, char *msg,
                                 size_t msg_len);


/* ------------------------------------------------------------------------ */
/* Fringe orders from one white-light colour picture (TFP)                   */
/* ------------------------------------------------------------------------ */

/* A camera's spectral sensitivities: n wavelengths (nm, rising) and their R, G, B responses. */
typedef struct {
    size_t n;
    const double *lambda_nm;
    const double *rgb; /* [n][3] */
} biref_pe_camera;

/* The colour the camera records through polariscope s (its light is white, illuminant E) at each
 * fringe order orders[k] (N at lambda_ref_nm, like the maps' white-light N): rgb[3k..3k+2]. cam
 * NULL: an sRGB camera — biref's analytic white-light integration over the CIE 1931 observer and
 * the encoded sRGB of the pictures (sp needed); else linear camera RGB, the intensity integrated
 * over the sensitivities (trapezoids) and normalised to 1 for an unattenuated beam. */
BIREF_API biref_status biref_pe_tfp_calibrate(const biref_pe_setup *s, const biref_spectral *sp,
                                              const biref_pe_camera *cam, double lambda_ref_nm, size_t n,
                                              const double *orders, double *rgb, char *msg, size_t msg_len);

typedef struct {
    int seed_x, seed_y;  /* the seed pixel (column, row from the top) */
    double seed_order;   /* its known order, NAN: the best colour match over the whole table */
    double window;       /* the largest change of order between neighbouring pixels (e.g. 0.3) */
    double max_residual; /* RMS colour difference above which a pixel is left NaN (e.g. 0.08) */
} biref_pe_tfp_opts;

/* Fringe orders of a colour picture (rgb: W x H x 3 in the table's encoding, top row first) by
 * colour matching against the calibration table (n rows, orders rising) with a continuity
 * constraint: from the seed, each neighbour's order is searched within +-window of the order of
 * the pixel it is reached from, best-matched pixels first. order_out (and residual_out if not
 * NULL): W x H, NaN where no match within max_residual connects to the seed. */
BIREF_API biref_status biref_pe_tfp_demodulate(const float *rgb, int W, int H, size_t n, const double *orders,
                                               const double *table_rgb, const biref_pe_tfp_opts *o, float *order_out,
                                               float *residual_out, char *msg, size_t msg_len);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_PHOTOELASTIC_H */
