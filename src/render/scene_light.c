/* A scene's light (scene_light.h). */
#include <complex.h>
#include <math.h>

#include "error.h"
#include "render/scene_light.h"

void biref_scene_light(const scene_pol *pol, const scene_filter *f, biref_light *out)
{
    const double w[2] = {pol->type == POL_SP ? pol->s : 0.5, pol->type == POL_SP ? pol->p : 0.5};
    const double mask[2] = {f->type == FILTER_P ? 0.0 : 1.0, f->type == FILTER_S ? 0.0 : 1.0};
    biref_light_sp(w, mask, out);
    if (pol->type == POL_LINEAR) biref_light_world_polarizer(out, pol->direction);
    if (f->type == FILTER_LINEAR) biref_light_world_analyzer(out, f->direction);
}

static int unit(const double v[3])
{
    const double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return isfinite(l) && fabs(l - 1.0) < 1e-6;
}

/* A diagonal matrix of real entries. */
static int real_diagonal(const biref_complex M[2][2])
{
    return M[0][1] == 0 && M[1][0] == 0 && cimag(M[0][0]) == 0 && cimag(M[1][1]) == 0;
}

biref_status biref_scene_light_check(const biref_light *l, char *msg, size_t msg_len)
{
    if (l->world_polarizer) {
        if (!unit(l->polarizer_axis))
            return biref_fail_field(msg, msg_len, "light.polarization.direction", "must be a unit vector");
    } else {
        const double ws = creal(l->C[0][0]), wp = creal(l->C[1][1]);
        if (!(real_diagonal(l->C) && isfinite(ws) && isfinite(wp) && ws >= 0 && wp >= 0 && fabs(ws + wp - 1) < 1e-9))
            return biref_fail_field(msg, msg_len, "light.polarization",
                                    "s and p must be non-negative fractions summing to 1");
    }
    if (l->world_analyzer) {
        if (!unit(l->analyzer_axis)) return biref_fail_field(msg, msg_len, "filter.direction", "must be a unit vector");
    } else if (l->has_analyzer) {
        const double ms = creal(l->P[0][0]), mp = creal(l->P[1][1]);
        if (!(real_diagonal(l->P) && (ms == 0 || ms == 1) && (mp == 0 || mp == 1)))
            return biref_fail_field(msg, msg_len, "filter", "must pass s, p or both (or be a world-fixed linear analyzer)");
    }
    return BIREF_OK;
}
