/* A shader's light resolved in the packet kernel's form (analytic_packet.h, biref_packet_hit_light)
 * at one hit, as one branch-free inline body: the shader's batch (shade_hits.c) and the renderer's
 * tiles (a loop across hits that the compiler vectorises) both call it. It does what biref_light_at
 * does for biref_shader_eval's two sides, in the same operations, so the packet and one-by-one
 * paths see the same coherency and analyzer to the bit:
 *   transmission: s = x (the frame's x axis), p_in = p_out = k x s with k = -d (d the view ray);
 *   reflection:   s = -x, p_in = (-mirror) x (-x) = mirror x x, p_out = (-d) x (-x) = d x x.
 * A world-fixed polarizer's axis a gives e = (a.s, a.p_in) and C = e e^T; a world-fixed analyzer's
 * axis b gives a_t = (b.s, b.p_out), P = a_t (a_t / |a_t|)^T, which is the same matrix on both sides
 * (a_t of the reflection is minus that of the transmission). */
#ifndef BIREF_SHADING_PACKET_LIGHT_H
#define BIREF_SHADING_PACKET_LIGHT_H

#include <math.h>

#include "spectral/analytic_packet.h"

/* A real light in the kernel's form: its fixed coherency (C00, C01, C11) and analyzer [in][out]
 * (P00, P01, P10, P11; the identity without analyzer), replaced per hit where a world-fixed
 * polarizer (polarizer != 0, unit axis pol) or analyzer (analyzer != 0, unit axis ana) is set. */
typedef struct {
    int polarizer, analyzer;
    double pol[3], ana[3];
    double C[3], P[4];
} biref_packet_light_source;

static inline void biref_packet_light_of(const biref_packet_light_source *L, const double x[3], const double d[3],
                                         const double mirror[3], biref_packet_hit_light *out)
{
    /* p_T = (-d) x x, p_R = mirror x x (each product as v3_cross forms it). */
    const double pT[3] = {-d[1] * x[2] - -d[2] * x[1], -d[2] * x[0] - -d[0] * x[2], -d[0] * x[1] - -d[1] * x[0]};
    const double pR[3] = {mirror[1] * x[2] - mirror[2] * x[1], mirror[2] * x[0] - mirror[0] * x[2],
                          mirror[0] * x[1] - mirror[1] * x[0]};
    const double *a = L->pol, *b = L->ana;
    const double as = a[0] * x[0] + a[1] * x[1] + a[2] * x[2];
    const double eT[2] = {as, a[0] * pT[0] + a[1] * pT[1] + a[2] * pT[2]};
    const double eR[2] = {-as, a[0] * pR[0] + a[1] * pR[1] + a[2] * pR[2]};
    const double t[2] = {b[0] * x[0] + b[1] * x[1] + b[2] * x[2], b[0] * pT[0] + b[1] * pT[1] + b[2] * pT[2]};
    const double n = sqrt(t[0] * t[0] + t[1] * t[1]);
    const double u[2] = {n > 0 ? t[0] / n : 0.0, n > 0 ? t[1] / n : 0.0};
    const int pol = L->polarizer, ana = L->analyzer;
    out->T.C[0] = pol ? eT[0] * eT[0] : L->C[0];
    out->T.C[1] = pol ? eT[0] * eT[1] : L->C[1];
    out->T.C[2] = pol ? eT[1] * eT[1] : L->C[2];
    out->R.C[0] = pol ? eR[0] * eR[0] : L->C[0];
    out->R.C[1] = pol ? eR[0] * eR[1] : L->C[1];
    out->R.C[2] = pol ? eR[1] * eR[1] : L->C[2];
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            const double p = ana ? t[i] * u[j] : L->P[2 * i + j];
            out->T.P[2 * i + j] = p;
            out->R.P[2 * i + j] = p;
        }
}

#endif
