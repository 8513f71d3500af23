/* Jones matrices of a uniaxial slab in a homogeneous surround: all orders of internal
 * reflection summed in closed form (paper §4, eq. 17) and the reflection analogue. */
#include <math.h>
#include <string.h>

#include "biref/optics.h"
#include "optics/cmat2.h"
#include "optics/modes_internal.h"
#include "optics/slab_internal.h"
#include "optics/validate.h"

/* The state of a checked slab; full = 0 skips the Poynting directions and effective indices of
 * the modes (left 0), which no spectral method reads. */
static biref_status slab_prepare(const biref_slab *slab, double theta, int full, biref_slab_state *st)
{
    biref_status s;
    st->slab = *slab;
    biref_axis_unit_unchecked(slab->axis, st->slab.axis);
    st->theta = theta;
    st->K = slab->eta_i * sin(theta); /* eq. 1 */

    biref_modes ambient;
    biref_isotropic_modes(slab->eta_i, st->K, &ambient);
    if (full)
        biref_uniaxial_modes(slab->eta_o, slab->eta_e, st->slab.axis, st->K, &st->modes);
    else
        biref_uniaxial_mode_fields(slab->eta_o, slab->eta_e, st->slab.axis, st->K, &st->modes);
    s = biref_interface_from_modes(&ambient, &st->modes, &st->top);
    if (s == BIREF_OK) s = biref_interface_from_modes(&st->modes, &ambient, &st->bottom);
    if (s != BIREF_OK) return s;

    /* docs/PAPER-ERRATA.md (appendix B): each leg gains its own full phase k0 * (-q_down) d or
     * k0 * q_up d; the lateral offsets cancel against the incident wavefront (eq. 11), so no path length is
     * subtracted per round trip (appendix B's "- 2 P_o" would erase the Fabry–Pérot phase). */
    double d = slab->thickness_nm;
    st->opl_down[BIREF_O] = -st->modes.q[BIREF_MODE_O_DOWN] * d;
    st->opl_down[BIREF_E] = -st->modes.q[BIREF_MODE_E_DOWN] * d;
    st->opl_up[BIREF_O] = st->modes.q[BIREF_MODE_O_UP] * d;
    st->opl_up[BIREF_E] = st->modes.q[BIREF_MODE_E_UP] * d;
    st->total_reflection = st->modes.evanescent_o || st->modes.evanescent_e;
    return BIREF_OK;
}

biref_status biref_slab_prepare(const biref_slab *slab, double theta, biref_slab_state *st)
{
    biref_status s = biref_slab_check(slab, NULL, 0);
    if (s == BIREF_OK) s = biref_theta_check(theta, NULL, 0);
    if (s != BIREF_OK) return s;
    memset(st, 0, sizeof *st);
    return slab_prepare(slab, theta, 1, st);
}

biref_status biref_slab_prepare_trusted(const biref_slab *slab, double theta, biref_slab_state *st)
{
    return slab_prepare(slab, theta, 0, st);
}

void biref_slab_state_flip(const biref_slab_state *in, biref_slab_state *out)
{
    *out = *in;
    out->slab.axis[0] = -in->slab.axis[0];
    out->slab.axis[1] = -in->slab.axis[1];
    /* The far face becomes the near one: its "from below" coefficients (incident from the
     * ambient below / from inside going down) are the new top interface's, and vice versa.
     * The isotropic bases s = x, p = k x s both change sign under the rotation, so amplitude
     * ratios are unchanged; the o/e mode bases inside cancel along every path. */
    memcpy(out->top.r_down, in->bottom.r_up, sizeof out->top.r_down);
    memcpy(out->top.t_down, in->bottom.t_up, sizeof out->top.t_down);
    memcpy(out->top.r_up, in->bottom.r_down, sizeof out->top.r_up);
    memcpy(out->top.t_up, in->bottom.t_down, sizeof out->top.t_up);
    memcpy(out->bottom.r_down, in->top.r_up, sizeof out->bottom.r_down);
    memcpy(out->bottom.t_down, in->top.t_up, sizeof out->bottom.t_down);
    memcpy(out->bottom.r_up, in->top.r_down, sizeof out->bottom.r_up);
    memcpy(out->bottom.t_up, in->top.t_down, sizeof out->bottom.t_up);
    for (int x = 0; x < 2; x++) {
        out->opl_down[x] = in->opl_up[x];
        out->opl_up[x] = in->opl_down[x];
    }
    /* Modes: the new down-going wave is the old up-going one seen with y -> -y. */
    static const int swap[4] = {BIREF_MODE_O_UP, BIREF_MODE_E_UP, BIREF_MODE_O_DOWN, BIREF_MODE_E_DOWN};
    for (int m = 0; m < 4; m++) {
        int from = swap[m];
        out->modes.q[m] = -in->modes.q[from];
        out->modes.eta_eff[m] = in->modes.eta_eff[from];
        out->modes.E[m][0] = -in->modes.E[from][0];
        out->modes.E[m][1] = -in->modes.E[from][1];
        out->modes.E[m][2] = in->modes.E[from][2];
        out->modes.H[m][0] = -in->modes.H[from][0];
        out->modes.H[m][1] = -in->modes.H[from][1];
        out->modes.H[m][2] = in->modes.H[from][2];
        out->modes.poynting[m][0] = -in->modes.poynting[from][0];
        out->modes.poynting[m][1] = -in->modes.poynting[from][1];
        out->modes.poynting[m][2] = in->modes.poynting[from][2];
    }
}

void biref_slab_jones_at(const biref_slab_state *st, double lambda_nm, biref_jones *T, biref_jones *R)
{
    double k = 2.0 * M_PI / lambda_nm;
    double complex pd0 = cexp(I * k * st->opl_down[0]), pd1 = cexp(I * k * st->opl_down[1]);
    /* The ordinary mode's up and down legs have the same optical path (q_o+ = -q_o-): one
     * complex exponential fewer per wavelength on the numeric methods' hot path. */
    double complex pu0 = st->opl_up[0] == st->opl_down[0] ? pd0 : cexp(I * k * st->opl_up[0]);
    double complex pu1 = cexp(I * k * st->opl_up[1]);
    cmat2 t01 = cmat2_from(st->top.t_down), r10 = cmat2_from(st->top.r_up);
    cmat2 r12 = cmat2_from(st->bottom.r_down), t12 = cmat2_from(st->bottom.t_down);

    /* Row-vector convention: a leg is diag(phases) on the right of what came before.
     * down_r12 = P_down * r12 (eq. 15 D-down), round trip D = P_down r12 P_up r10. */
    cmat2 down_r12 = cmat2_scale_rows(r12, pd0, pd1);
    cmat2 up_r10 = cmat2_scale_rows(r10, pu0, pu1);
    cmat2 D = cmat2_mul(down_r12, up_r10);
    cmat2 entry = cmat2_mul(t01, cmat2_inv_one_minus(D)); /* amplitudes going down at y = 0 */
    if (T) {
        cmat2 out = cmat2_mul(entry, cmat2_scale_rows(t12, pd0, pd1)); /* eq. 17 */
        memcpy(T->m, out.m, sizeof out.m);
    }
    if (R) {
        cmat2 t10 = cmat2_from(st->top.t_up);
        cmat2 back = cmat2_mul(down_r12, cmat2_scale_rows(t10, pu0, pu1));
        cmat2 out = cmat2_add(cmat2_from(st->top.r_down), cmat2_mul(entry, back));
        memcpy(R->m, out.m, sizeof out.m);
    }
}

biref_status biref_slab_jones(const biref_slab *slab, double theta, double lambda_nm, biref_jones *T,
                              biref_jones *R)
{
    if (biref_check_lambda(lambda_nm, NULL, 0) != BIREF_OK) return BIREF_ERR_INVALID;
    biref_slab_state st;
    biref_status s = biref_slab_prepare(slab, theta, &st);
    if (s != BIREF_OK) return s;
    biref_slab_jones_at(&st, lambda_nm, T, R);
    return BIREF_OK;
}

void biref_jones_intensity(const biref_jones *J, double out[2][2])
{
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            double complex a = J->m[i][j];
            out[i][j] = creal(a) * creal(a) + cimag(a) * cimag(a);
        }
}
