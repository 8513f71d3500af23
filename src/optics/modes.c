/* Normal modes of isotropic and uniaxial media for a given incidence parameter K
 * (paper §3, eqs. 2–6, with the corrections listed in docs/PHYSICS.md). */
#include <math.h>
#include <string.h>

#include "biref/optics.h"
#include "optics/modes_internal.h"

/* Root of (eps - K^2) on the branch that makes the wave carry energy, or decay, towards -y
 * for the "down" sign: propagating q_down = -sqrt(eps - K^2); evanescent Im q_down < 0. */
static void iso_normal_components(double eps, double K, double complex *q_down, double complex *q_up)
{
    double d = eps - K * K;
    if (d >= 0.0) {
        *q_down = -sqrt(d);
        *q_up = sqrt(d);
    } else {
        *q_down = -I * sqrt(-d);
        *q_up = I * sqrt(-d);
    }
}

static double herm_norm3(const double complex v[3])
{
    return sqrt(creal(v[0] * conj(v[0]) + v[1] * conj(v[1]) + v[2] * conj(v[2])));
}

static void scale3(double complex v[3], double s)
{
    v[0] *= s;
    v[1] *= s;
    v[2] *= s;
}

/* H = k x E with k = (0, q, -K) (Faraday's law for e^{i(k.r - wt)}, non-magnetic media). */
static void curl_field(double complex q, double K, const double complex E[3], double complex H[3])
{
    H[0] = q * E[2] + K * E[1];
    H[1] = -K * E[0];
    H[2] = -q * E[0];
}

/* Time-averaged Poynting direction Re(E* x H) (paper eq. 4 generalised to complex fields). */
static void poynting_dir(const double complex E[3], const double complex H[3], double out[3])
{
    double complex a[3] = {conj(E[0]), conj(E[1]), conj(E[2])};
    out[0] = creal(a[1] * H[2] - a[2] * H[1]);
    out[1] = creal(a[2] * H[0] - a[0] * H[2]);
    out[2] = creal(a[0] * H[1] - a[1] * H[0]);
    double n = sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
    if (n > 0.0)
        for (int i = 0; i < 3; i++) out[i] /= n;
}

/* Fallback pair for a degenerate direction (k parallel to the optic axis, or an isotropic
 * medium): s = x and p = k x s / |k| (docs/CONVENTIONS.md). eta is the mode's index. */
static void sp_fields(double complex q, double K, double eta, double complex Es[3], double complex Ep[3])
{
    Es[0] = 1.0;
    Es[1] = 0.0;
    Es[2] = 0.0;
    /* k x x = (0, -K, -q); |k| = eta on the analytic branch, also for evanescent waves. */
    Ep[0] = 0.0;
    Ep[1] = -K / eta;
    Ep[2] = -q / eta;
}

static void finish_mode(biref_modes *m, int idx, double K)
{
    poynting_dir(m->E[idx], m->H[idx], m->poynting[idx]);
    double complex q = m->q[idx];
    m->eta_eff[idx] = (fabs(cimag(q)) > 0.0) ? NAN : sqrt(creal(q) * creal(q) + K * K); /* eq. 5 */
}

void biref_isotropic_modes(double eta, double K, biref_modes *m)
{
    memset(m, 0, sizeof *m);
    m->K = K;
    double complex qd, qu;
    iso_normal_components(eta * eta, K, &qd, &qu);
    m->q[BIREF_MODE_O_DOWN] = m->q[BIREF_MODE_E_DOWN] = qd;
    m->q[BIREF_MODE_O_UP] = m->q[BIREF_MODE_E_UP] = qu;
    sp_fields(qd, K, eta, m->E[BIREF_MODE_O_DOWN], m->E[BIREF_MODE_E_DOWN]);
    sp_fields(qu, K, eta, m->E[BIREF_MODE_O_UP], m->E[BIREF_MODE_E_UP]);
    for (int i = 0; i < 4; i++) {
        /* In an isotropic medium energy flows along Re k (per-sample path: no general cross
         * products); an evanescent wave carries it along the surface, towards -z. */
        double complex q = m->q[i];
        curl_field(q, K, m->E[i], m->H[i]);
        int ev = cimag(q) != 0.0;
        m->poynting[i][0] = 0.0;
        m->poynting[i][1] = ev ? 0.0 : creal(q) / eta;
        m->poynting[i][2] = ev ? -1.0 : -K / eta;
        m->eta_eff[i] = ev ? NAN : eta;
    }
    m->K_max_o = m->K_max_e = eta;
    m->evanescent_o = m->evanescent_e = K >= eta;
}

/* Relative size below which E_o = -k x A is treated as zero (k parallel to A). At that
 * point o and e are degenerate and any orthogonal transverse pair is an exact basis. */
#define DEGENERATE_REL 1e-9

void biref_uniaxial_normal_components(double eta_o, double eta_e, const double A[3], double K, double complex q[4])
{
    double be = A[1], ga = A[2];
    double eo = eta_o * eta_o, ee = eta_e * eta_e, de = ee - eo;
    /* Ordinary: |k|^2 = eps_o (eq. 2). */
    iso_normal_components(eo, K, &q[BIREF_MODE_O_DOWN], &q[BIREF_MODE_O_UP]);
    /* Extraordinary: k^T eps k = eps_o eps_e with eps = eps_o I + de A A^T and k = (0, q, -K):
     * (eps_o + be^2 de) q^2 - 2 be ga K de q + K^2 (eps_o + ga^2 de) - eps_o eps_e = 0.
     * The paper's eq. 2 put be*ga*K*de inside the square root (OCR); it belongs outside.
     * The + root carries energy upwards (d/dq of the dispersion relation is +2 sqrt(eps_o disc)). */
    double a = eo + be * be * de;
    double disc = ee * (eo + be * be * de) + K * K * (A[0] * A[0] * de - ee);
    double complex root = disc >= 0.0 ? sqrt(eo * disc) + 0.0 * I : I * sqrt(-eo * disc);
    q[BIREF_MODE_E_DOWN] = (be * ga * K * de - root) / a;
    q[BIREF_MODE_E_UP] = (be * ga * K * de + root) / a;
}

void biref_uniaxial_mode_fields(double eta_o, double eta_e, const double A[3], double K, biref_modes *m)
{
    memset(m, 0, sizeof *m);
    m->K = K;
    double al = A[0], be = A[1], ga = A[2];
    double eo = eta_o * eta_o, ee = eta_e * eta_e, de = ee - eo;

    biref_uniaxial_normal_components(eta_o, eta_e, A, K, m->q);

    double disc = ee * (eo + be * be * de) + K * K * (al * al * de - ee);

    /* Maximal incidence parameters (eq. 6 corrected: the extracted text has gamma^2 where
     * the x component alpha^2 belongs; disc = 0 gives K^2 = eps_e (eps_o + be^2 de) / (eps_e - al^2 de)). */
    m->K_max_o = eta_o;
    m->K_max_e = sqrt(ee * (eo + be * be * de) / (ee - al * al * de));
    m->evanescent_o = K >= eta_o;
    m->evanescent_e = disc <= 0.0;

    for (int dir = 0; dir < 2; dir++) {
        int io = dir ? BIREF_MODE_O_UP : BIREF_MODE_O_DOWN;
        int ie = dir ? BIREF_MODE_E_UP : BIREF_MODE_E_DOWN;
        double complex qo = m->q[io], qe = m->q[ie];
        /* eq. 3: E_o = -k x A. */
        double complex *Eo = m->E[io];
        Eo[0] = -be * K - ga * qo;
        Eo[1] = al * K;
        Eo[2] = al * qo;
        double scale_o = sqrt(creal(qo * conj(qo)) + K * K);
        double no = herm_norm3(Eo);
        /* eq. 3: E_e = eps_o A - (A.k) k, i.e. the component of D along the e polarisation. */
        double complex *Ee = m->E[ie];
        double complex ak = be * qe - ga * K;
        Ee[0] = eo * al;
        Ee[1] = eo * be - ak * qe;
        Ee[2] = eo * ga + ak * K;
        double scale_e = eo;
        double ne = herm_norm3(Ee);
        if (no <= DEGENERATE_REL * (scale_o > 0 ? scale_o : 1.0) || ne <= DEGENERATE_REL * scale_e) {
            /* k parallel to A: q_o = q_e and every transverse field is a mode. */
            double complex tmp[3];
            sp_fields(qo, K, eta_o, Eo, tmp);
            memcpy(Ee, tmp, sizeof tmp);
            m->q[ie] = qo;
        } else {
            scale3(Eo, 1.0 / no);
            scale3(Ee, 1.0 / ne);
        }
    }
    /* H = k x E: the interface solves need it. */
    for (int i = 0; i < 4; i++) curl_field(m->q[i], K, m->E[i], m->H[i]);
}

void biref_uniaxial_modes(double eta_o, double eta_e, const double A[3], double K, biref_modes *m)
{
    biref_uniaxial_mode_fields(eta_o, eta_e, A, K, m);
    for (int i = 0; i < 4; i++) finish_mode(m, i, K);
}

biref_status biref_medium_modes(const biref_medium *med, double K, biref_modes *out)
{
    biref_status s = biref_medium_check(med, NULL, 0);
    if (s != BIREF_OK) return s;
    if (!isfinite(K) || K < 0.0) return BIREF_ERR_INVALID;
    if (med->isotropic) {
        biref_isotropic_modes(med->eta_o, K, out);
    } else {
        double A[3];
        biref_axis_normalize(med->axis, A); /* checked above */
        biref_uniaxial_modes(med->eta_o, med->eta_e, A, K, out);
    }
    return BIREF_OK;
}
