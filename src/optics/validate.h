/* Parameter checks shared by the library's entry points; each writes a one-line reason. */
#ifndef BIREF_OPTICS_VALIDATE_H
#define BIREF_OPTICS_VALIDATE_H

#include <stddef.h>

#include "biref/common.h"
#include "error.h" /* biref_fail */

/* Refractive indices are in (0, BIREF_MAX_INDEX]: no material comes near 1000 (the largest are
 * some tens, in the far infrared), and far beyond it the interface equations become singular in
 * double precision (about 1e15), so a slab there could not be evaluated anywhere. */
#define BIREF_MAX_INDEX 1000.0

biref_status biref_check_index(const char *name, double eta, char *msg, size_t msg_len);
biref_status biref_check_axis(const double axis[3], char *msg, size_t msg_len);
biref_status biref_check_lambda(double lambda_nm, char *msg, size_t msg_len);

#endif
