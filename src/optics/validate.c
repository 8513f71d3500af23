/* Domain checks: every public entry point rejects input that would produce NaN or nonsense. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>

#include "biref/optics.h"
#include "optics/validate.h"

biref_status biref_check_index(const char *name, double eta, char *msg, size_t msg_len)
{
    if (!isfinite(eta)) return biref_fail(msg, msg_len, "%s must be a finite number (got %g)", name, eta);
    if (eta <= 0.0) return biref_fail(msg, msg_len, "%s must be positive (got %g)", name, eta);
    if (eta > BIREF_MAX_INDEX)
        return biref_fail(msg, msg_len, "%s must be at most %g, the largest refractive index biref takes (got %g)", name,
                          BIREF_MAX_INDEX, eta);
    return BIREF_OK;
}

/* |axis| and the axis scaled by its largest component (m = 0 for the zero vector). */
static double axis_norm(const double axis[3], double scaled[3])
{
    double a0 = fabs(axis[0]), a1 = fabs(axis[1]), a2 = fabs(axis[2]);
    double m = a0 > a1 ? a0 : a1; /* fmax without libm calls (NaN is rejected by the callers first) */
    m = m > a2 ? m : a2;
    for (int i = 0; i < 3; i++) scaled[i] = m > 0.0 ? axis[i] / m : 0.0;
    return m * sqrt(scaled[0] * scaled[0] + scaled[1] * scaled[1] + scaled[2] * scaled[2]);
}

biref_status biref_check_axis(const double axis[3], char *msg, size_t msg_len)
{
    for (int i = 0; i < 3; i++)
        if (!isfinite(axis[i])) return biref_fail(msg, msg_len, "optic axis component %d is not finite", i);
    double scaled[3];
    if (!(axis_norm(axis, scaled) > 1e-12)) return biref_fail(msg, msg_len, "optic axis must be non-zero");
    return BIREF_OK;
}

void biref_axis_unit_unchecked(const double axis[3], double unit[3])
{
    double scaled[3];
    axis_norm(axis, scaled);
    double inv = 1.0 / sqrt(scaled[0] * scaled[0] + scaled[1] * scaled[1] + scaled[2] * scaled[2]);
    for (int i = 0; i < 3; i++) unit[i] = scaled[i] * inv;
}

biref_status biref_axis_normalize(const double axis[3], double unit[3])
{
    biref_status s = biref_check_axis(axis, NULL, 0);
    if (s != BIREF_OK) return s;
    biref_axis_unit_unchecked(axis, unit);
    return BIREF_OK;
}

biref_status biref_check_lambda(double lambda_nm, char *msg, size_t msg_len)
{
    if (!isfinite(lambda_nm) || lambda_nm <= 0.0)
        return biref_fail(msg, msg_len, "wavelength must be a positive finite number of nm (got %g)", lambda_nm);
    return BIREF_OK;
}

biref_status biref_slab_check(const biref_slab *slab, char *msg, size_t msg_len)
{
    if (!slab) return biref_fail(msg, msg_len, "slab is NULL");
    biref_status s = biref_check_index("eta_o", slab->eta_o, msg, msg_len);
    if (s == BIREF_OK) s = biref_check_index("eta_e", slab->eta_e, msg, msg_len);
    if (s == BIREF_OK) s = biref_check_index("eta_i", slab->eta_i, msg, msg_len);
    if (s == BIREF_OK) s = biref_check_axis(slab->axis, msg, msg_len);
    if (s != BIREF_OK) return s;
    if (!isfinite(slab->thickness_nm) || slab->thickness_nm <= 0.0)
        return biref_fail(msg, msg_len, "thickness must be a positive finite length (got %g nm)", slab->thickness_nm);
    return BIREF_OK;
}

biref_status biref_theta_check(double theta_rad, char *msg, size_t msg_len)
{
    if (!isfinite(theta_rad) || theta_rad < 0.0 || theta_rad >= M_PI / 2)
        return biref_fail(msg, msg_len, "angle of incidence must be in [0, 90) degrees (got %g deg)",
                          theta_rad * 180.0 / M_PI);
    return BIREF_OK;
}
