/* Helpers that build cJSON values for the physics types (output only; parsing is cJSON's). */
#ifndef BIREF_CLI_JSON_OUT_H
#define BIREF_CLI_JSON_OUT_H

#include <cjson/cJSON.h>
#include <complex.h>

#include "biref/biref.h"

cJSON *json_complex(double complex z);
cJSON *json_vec3(const double v[3]);
cJSON *json_cvec3(const double complex v[3]);
/* {"s": {"s": x, "p": x}, "p": {...}} of reals. */
cJSON *json_sp_matrix(const double m[2][2]);
/* Same indexing, values as [re, im]. */
cJSON *json_sp_cmatrix(const double complex m[2][2]);
/* Same indexing, values XYZ triples: the four s/p input/output pair colours of a spectrum. */
cJSON *json_sp_xyz_pairs(const double X[2][2][3]);
/* A dispersive material used over [lo_nm, hi_nm]: {"name", "source", "range_nm" ([min, max], null
 * for none), "extrapolated_nm" (the parts of the band outside the range, [[a, b], ...])}. */
cJSON *json_dispersive_material(const biref_material *m, double lo_nm, double hi_nm);
/* The head shared by every `spectrum --json` object: {"method", "samples" (null when the method
 * has none), "cmf", "range_nm"}. */
cJSON *json_spectrum_head(biref_method method, int samples, const biref_spectral_config *cfg);
/* Prints, frees, returns 0 or 1 on allocation failure. */
int json_print_and_free(cJSON *root);

#endif
