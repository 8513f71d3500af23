/* biref_light: one light description for every integration method (polarization.h). */
#include <math.h>
#include <string.h>

#include "biref/polarization.h"

biref_status biref_light_sp(const double w_in[2], const double mask[2], biref_light *out)
{
    for (int i = 0; i < 2; i++)
        if (!(w_in[i] >= 0.0 && isfinite(w_in[i]) && mask[i] >= 0.0 && mask[i] <= 1.0)) return BIREF_ERR_INVALID;
    memset(out, 0, sizeof *out);
    for (int i = 0; i < 2; i++) {
        out->w_in[i] = w_in[i];
        out->mask[i] = mask[i];
        out->C[i][i] = w_in[i];
        out->P[i][i] = sqrt(mask[i]); /* mask is a power fraction; P acts on amplitudes */
    }
    /* A mask passing both is no analyzer at all: the integrators then skip the projection. */
    out->has_analyzer = !(mask[0] == 1.0 && mask[1] == 1.0);
    out->sp_model = 1;
    return BIREF_OK;
}

void biref_light_coherency(const double complex C[2][2], biref_light *out)
{
    memset(out, 0, sizeof *out);
    memcpy(out->C, C, sizeof out->C);
    out->mask[0] = out->mask[1] = 1.0;
}

biref_status biref_light_stokes(const double stokes[4], biref_light *out)
{
    double complex C[2][2];
    biref_status s = biref_stokes_to_coherency(stokes, C);
    if (s != BIREF_OK) return s;
    biref_light_coherency(C, out);
    return BIREF_OK;
}

void biref_light_set_analyzer(biref_light *l, const double complex P[2][2])
{
    l->world_analyzer = 0;
    if (!P) {
        memset(l->P, 0, sizeof l->P);
        l->has_analyzer = 0;
        l->mask[0] = l->mask[1] = 1.0;
        return;
    }
    memcpy(l->P, P, sizeof l->P);
    l->has_analyzer = 1;
    l->sp_model = l->sp_model && P[0][1] == 0.0 && P[1][0] == 0.0 && P[0][0] == sqrt(l->mask[0]) &&
                  P[1][1] == sqrt(l->mask[1]);
}

biref_status biref_light_mix(const biref_light *l, const double X[2][2][3], double xyz[3])
{
    if (!l->sp_model) return BIREF_ERR_INVALID;
    biref_spectrum_mix(X, l->w_in, l->mask, xyz);
    return BIREF_OK;
}

void biref_spectrum_mix(const double X[2][2][3], const double w_in[2], const double out_mask[2], double xyz[3])
{
    for (int b = 0; b < 3; b++) {
        double v = 0.0;
        for (int i = 0; i < 2; i++)
            for (int o = 0; o < 2; o++) v += w_in[i] * out_mask[o] * X[i][o][b];
        xyz[b] = v;
    }
}
