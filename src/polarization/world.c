/* World-fixed polarizers of a biref_light and their resolution for one wave pair (polarization.h);
 * the polarizer's text form. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "biref/experimental.h" /* biref_light_at, biref_light_passthrough */
#include "biref/polarization.h"
#include "error.h"

static biref_status unit_axis(const double a[3], double o[3])
{
    const double l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (!(l > 0.0) || !isfinite(l)) return BIREF_ERR_INVALID;
    for (int k = 0; k < 3; k++) o[k] = a[k] / l;
    return BIREF_OK;
}

biref_status biref_light_world_polarizer(biref_light *l, const double axis[3])
{
    if (!l || !axis || unit_axis(axis, l->polarizer_axis)) return BIREF_ERR_INVALID;
    l->world_polarizer = 1;
    l->sp_model = 0;
    return BIREF_OK;
}

biref_status biref_light_world_analyzer(biref_light *l, const double axis[3])
{
    if (!l || !axis || unit_axis(axis, l->analyzer_axis)) return BIREF_ERR_INVALID;
    l->world_analyzer = 1;
    l->has_analyzer = 1;
    l->sp_model = 0;
    return BIREF_OK;
}

int biref_light_is_world_fixed(const biref_light *l) { return l->world_polarizer || l->world_analyzer; }

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

void biref_light_at(const biref_light *l, const double s[3], const double p_in[3], const double p_out[3],
                    biref_light *out)
{
    *out = *l;
    if (!biref_light_is_world_fixed(l)) return;
    if (l->world_polarizer) {
        /* The polarizer's axis projected onto the incident wave's transverse plane. */
        const double e[2] = {dot3(l->polarizer_axis, s), dot3(l->polarizer_axis, p_in)};
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) out->C[i][j] = e[i] * e[j];
    }
    if (l->world_analyzer) {
        /* P = a_t (a_t / |a_t|)^T in the outgoing wave's basis. */
        const double a[2] = {dot3(l->analyzer_axis, s), dot3(l->analyzer_axis, p_out)};
        const double n = sqrt(a[0] * a[0] + a[1] * a[1]);
        const double u[2] = {n > 0 ? a[0] / n : 0.0, n > 0 ? a[1] / n : 0.0};
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) out->P[i][j] = a[i] * u[j];
    }
    out->world_polarizer = out->world_analyzer = 0;
    out->sp_model = 0;
}

double biref_light_passthrough(const biref_light *l)
{
    static const double complex ID[2][2] = {{1, 0}, {0, 1}};
    const double complex(*P)[2] = l->has_analyzer ? (const double complex(*)[2])l->P : ID;
    double f = 0.0;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) f += creal(l->C[i][j] * P[i][k] * conj(P[j][k]));
    return f;
}

biref_status biref_polarizer_parse(const char *text, biref_polarizer *out, char *msg, size_t msg_len)
{
    if (!text || !out) return biref_fail(msg, msg_len, "no polarizer text");
    memset(out, 0, sizeof *out);
    if (!strncmp(text, "linear:", 7)) {
        char *end;
        const double deg = strtod(text + 7, &end);
        if (end == text + 7 || *end || !isfinite(deg))
            return biref_fail(msg, msg_len, "linear: expected an angle in degrees, got '%s'", text + 7);
        const double a = deg * M_PI / 180.0;
        out->stokes[0] = 1.0;
        out->stokes[1] = cos(2 * a);
        out->stokes[2] = sin(2 * a);
        biref_analyzer_linear(a, out->analyzer);
        return BIREF_OK;
    }
    if (!strncmp(text, "circular:", 9)) {
        const char *h = text + 9;
        const int hand = !strcmp(h, "+1") || !strcmp(h, "1") ? 1 : !strcmp(h, "-1") ? -1 : 0;
        if (!hand) return biref_fail(msg, msg_len, "circular handedness must be +1 or -1 (sign of S3), got '%s'", h);
        out->stokes[0] = 1.0;
        out->stokes[3] = hand;
        biref_analyzer_circular(hand, out->analyzer);
        return BIREF_OK;
    }
    return biref_fail(msg, msg_len, "expected linear:DEG or circular:+1|-1, got '%s'", text);
}
