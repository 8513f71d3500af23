/* Parameter checks shared by the library's entry points; each writes a one-line reason. */
#ifndef BIREF_OPTICS_VALIDATE_H
#define BIREF_OPTICS_VALIDATE_H

#include <stddef.h>

#include "biref/common.h"
#include "error.h" /* biref_fail */

biref_status biref_check_index(const char *name, double eta, char *msg, size_t msg_len);
biref_status biref_check_axis(const double axis[3], char *msg, size_t msg_len);
biref_status biref_check_lambda(double lambda_nm, char *msg, size_t msg_len);

#endif
