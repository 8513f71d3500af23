/* The polariscope: ideal input and output optics, the fast two-mode shading of a stressed plate
 * at normal incidence, and the general-path reference it is verified against
 * (docs/PHOTOELASTICITY.md, "Polariscope" and "Fast path"). */
#include <math.h>
#include <stdlib.h>

#include "biref/photoelastic.h"
#include "photoelastic/pe_footprint.h"
#include "photoelastic/shade_internal.h"
#include "spectral/spectral_internal.h"

biref_status biref_pe_polariscope_custom(const double stokes[4], const double complex P[2][2],
                                         biref_pe_polariscope *out)
{
    if (biref_stokes_to_coherency(stokes, out->C) != BIREF_OK) return BIREF_ERR_INVALID;
    /* Recover u from P[k][o] = conj(u_k) u_o (up to a global phase, which no intensity sees):
     * take the larger diagonal element for the real component. */
    double p00 = creal(P[0][0]), p11 = creal(P[1][1]);
    double complex u0, u1;
    if (!(p00 >= 0.0 && p11 >= 0.0)) return BIREF_ERR_INVALID;
    if (p00 >= p11) {
        u0 = sqrt(p00);
        if (creal(u0) <= 0.0) return BIREF_ERR_INVALID;
        u1 = P[0][1] / u0;
    } else {
        u1 = sqrt(p11);
        u0 = conj(P[0][1]) / u1;
    }
    double complex u[2] = {u0, u1};
    for (int k = 0; k < 2; k++)
        for (int o = 0; o < 2; o++)
            if (!(cabs(conj(u[k]) * u[o] - P[k][o]) <= 1e-9)) return BIREF_ERR_INVALID;
    if (fabs(cabs(u0) * cabs(u0) + cabs(u1) * cabs(u1) - 1.0) > 1e-9) return BIREF_ERR_INVALID;
    for (int k = 0; k < 2; k++)
        for (int o = 0; o < 2; o++) out->P[k][o] = P[k][o];
    out->u[0] = u0;
    out->u[1] = u1;
    return BIREF_OK;
}

void biref_pe_polariscope_make(biref_pe_polariscope_kind kind, biref_pe_field_type field, double psi,
                               biref_pe_polariscope *out)
{
    double complex P[2][2];
    if (kind == BIREF_PE_PLANE) {
        /* Linear light at psi: S1 = cos 2 psi, S2 = sin 2 psi (docs/PHYSICS.md §5 convention). */
        const double stokes[4] = {1.0, cos(2.0 * psi), sin(2.0 * psi), 0.0};
        biref_analyzer_linear(field == BIREF_PE_DARK ? psi + 0.5 * M_PI : psi, P);
        (void)biref_pe_polariscope_custom(stokes, P, out);
    } else {
        const double stokes[4] = {1.0, 0.0, 0.0, 1.0};
        biref_analyzer_circular(field == BIREF_PE_DARK ? -1 : +1, P);
        (void)biref_pe_polariscope_custom(stokes, P, out);
    }
}

double biref_pe_polariscope_background(const biref_pe_polariscope *pol)
{
    /* I = sum_ij C_ij (P P^H)_ij = sum_ij C_ij conj(u_i) u_j for a projector P = conj(u) u^T. */
    double complex s = 0;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) s += pol->C[i][j] * conj(pol->u[i]) * pol->u[j];
    return creal(s);
}

double biref_pe_retardation_nm(const biref_pe_setup *s, const biref_pe_principal *p)
{
    return s->material.C_per_Pa * (p->s1 - p->s2) * s->thickness * 1e9;
}

double biref_pe_retardation_at_nm(const biref_pe_setup *s, const biref_pe_principal *p, double lambda_nm)
{
    return biref_pe_C_at(&s->material, lambda_nm) * (p->s1 - p->s2) * s->thickness * 1e9;
}

double biref_pe_retardation_oblique_nm(const biref_pe_setup *s, const biref_pe_principal *p, double theta)
{
    biref_slab slab = biref_pe_slab_best(&s->material, s->thickness, s->eta_i, p);
    biref_slab_state st;
    if (biref_slab_prepare(&slab, theta, &st) != BIREF_OK) return NAN;
    return fabs(creal(st.opl_down[BIREF_E] - st.opl_down[BIREF_O]));
}

/* Single-pass amplitude tau = t01 t10 and internal reflectance rho^2 of an isotropic slab of
 * index n in a medium eta at normal incidence (Fresnel; s and p coincide there). */
static inline void airy_coeffs(double n, double eta, double *tau, double *rho2)
{
    double sum = n + eta, r = (n - eta) / sum;
    *tau = 4.0 * n * eta / (sum * sum);
    *rho2 = r * r;
}

/* Largest m kept in the white-light series of <t_e conj t_o>; the series stops once the next
 * weight q^m is below 1e-7 (in air q ~ 3e-3: m = 0, 1, 2, truncation error ~2e-8). */
#define PE_MAX_ORDER 6

void biref_pe_shade(const biref_pe_setup *s, const biref_spectral *sp, const biref_pe_principal *p, double xyz[3])
{
    biref_pe_shade_footprint(s, sp, NULL, 0.0, p, xyz);
}

/* <t_e conj t_o> of monochromatic light, each term e^{ik D} averaged over a box of width
 * (2m + 1) w around D = (2m + 1) delta: times sinc((2m + 1) a), a = k w / 2. z = e^{ik delta};
 * sin((2m + 1) a) by the recurrence sin((n + 2) a) = 2 cos(2a) sin(n a) - sin((n - 2) a). */
static double complex mono_cross_box(double tt, double q, double complex z, double w_nm, double lambda_nm)
{
    const double a = M_PI * w_nm / lambda_nm, sa = sin(a), c2 = 1.0 - 2.0 * sa * sa;
    double complex sum = 0, zm = z;
    const double complex z2 = z * z;
    double wm = tt, s_prev = -sa, s_cur = sa;
    for (int m = 0; m <= PE_MAX_ORDER && wm >= 1e-7 * tt; m++, wm *= q, zm *= z2) {
        const double n_a = (2.0 * m + 1.0) * a;
        sum += wm * zm * (n_a > 1e-8 ? s_cur / n_a : 1.0);
        const double s_next = 2.0 * c2 * s_cur - s_prev;
        s_prev = s_cur, s_cur = s_next;
    }
    return sum;
}

/* Fewest samples of the dispersive white-light sum, and samples per cycle of the fastest phase
 * k (2m + 1) delta(λ) across the band that it keeps (the m = 1 term, weight q ~ 3e-3 in air). */
#define PE_DISPERSIVE_MIN_SAMPLES 192
#define PE_DISPERSIVE_PER_CYCLE 8

/* The plan of the context's midpoint plans (48 * 2^i samples) that resolves a retardation of
 * delta_ref at the reference wavelength, C(λ) = C (ref / λ)^alpha: the phase k delta(λ) runs
 * over delta_ref ref^alpha |λmin^-(1+alpha) - λmax^-(1+alpha)| cycles across the band; the largest
 * plan where no plan does (such orders are the higher-order white of any sampling). */
static const biref_numeric_plan *dispersive_plan(const biref_spectral *sp, const biref_pe_material *m, double delta_ref)
{
    const double ref = m->lambda_ref_nm > 0.0 ? m->lambda_ref_nm : BIREF_PE_LAMBDA_REF_NM, a = m->dispersion_alpha;
    const double lo = sp->cfg.lambda_min_nm, hi = sp->cfg.lambda_max_nm;
    const double cycles = fabs(delta_ref) * fabs(pow(ref / lo, a) / lo - pow(ref / hi, a) / hi);
    const double need = fmax(PE_DISPERSIVE_MIN_SAMPLES, 3.0 * PE_DISPERSIVE_PER_CYCLE * cycles);
    const biref_numeric_plan *plan = NULL;
    for (int i = 0; i < sp->n_coherent; i++) {
        plan = sp->coherent[i];
        if (plan->samples >= need) break;
    }
    return plan;
}

/* White light with dispersion of C (docs/PHOTOELASTICITY.md, "Dispersion of birefringence"):
 * the retardation is delta(λ) = delta_ref (ref / λ)^alpha, so the phase k delta(λ) is no longer
 * linear in k and the table's S(e^{ikD}) does not apply; <t_e conj t_o> per band is the plan's
 * weighted sum of the monochromatic series at each sample (box-averaged over the footprint's
 * width, which scales with C(λ) as delta does). */
static void white_dispersive_cross(const biref_pe_setup *s, const biref_spectral *sp, double delta_ref,
                                   double width_ref, double tt, double q, double re[3], double im[3])
{
    const biref_numeric_plan *plan = dispersive_plan(sp, &s->material, delta_ref + width_ref);
    const double ref = s->material.lambda_ref_nm > 0.0 ? s->material.lambda_ref_nm : BIREF_PE_LAMBDA_REF_NM;
    for (int n = 0; n < plan->samples; n++) {
        const double f = pow(ref / plan->lambda[n], s->material.dispersion_alpha);
        const double complex z = cexp(I * plan->k[n] * delta_ref * f);
        const double complex c = width_ref > 0.0 ? mono_cross_box(tt, q, z, width_ref * f, plan->lambda[n])
                                                 : tt * z / (1.0 - q * z * z);
        for (int j = 0; j < 3; j++) {
            re[j] += plan->weight[n][j] * creal(c);
            im[j] += plan->weight[n][j] * cimag(c);
        }
    }
}

void biref_pe_shade_footprint(const biref_pe_setup *s, const biref_spectral *sp, const biref_phase_prefilter *pf,
                              double width_nm, const biref_pe_principal *p, double xyz[3])
{
    /* Principal directions a (axis, e-mode) and b (o-mode) in the s/p basis. cos phi, sin phi by
     * the half-angle formulas: phi in (-pi/2, pi/2] has cos phi >= 0 and sin phi of the sign of
     * sin 2 phi (the sign of a or b never matters: each appears twice below). */
    const double ca = sqrt(fmax(0.0, 0.5 * (1.0 + p->cos2phi)));
    const double sa = copysign(sqrt(fmax(0.0, 0.5 * (1.0 - p->cos2phi))), p->sin2phi);
    const double a[2] = {ca, sa}, b[2] = {-sa, ca};
    const biref_pe_polariscope *pol = &s->pol;
    /* J_T = t_e a a^T + t_o b b^T (row-vector convention, out = in J_T): the two modes do not mix
     * at normal incidence with the axis in the plane. With the analyzer P = conj(u) u^T the
     * detected field is (J_T conj(u)) u, so the intensity is v^T C conj(v) with
     * v = t_e a (a . conj u) + t_o b (b . conj u), i.e.
     *   I = alpha |t_e|^2 + beta |t_o|^2 + 2 Re(gamma t_e conj(t_o)),
     *   alpha = |a.u*|^2 a^T C a, beta = |b.u*|^2 b^T C b, gamma = (a.u*) conj(b.u*) a^T C b. */
    const double complex au = a[0] * conj(pol->u[0]) + a[1] * conj(pol->u[1]);
    const double complex bu = b[0] * conj(pol->u[0]) + b[1] * conj(pol->u[1]);
    double complex aCa = 0, bCb = 0, aCb = 0;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            aCa += pol->C[i][j] * a[i] * a[j];
            bCb += pol->C[i][j] * b[i] * b[j];
            aCb += pol->C[i][j] * a[i] * b[j];
        }
    const double alpha = creal(au * conj(au)) * creal(aCa);
    const double beta = creal(bu * conj(bu)) * creal(bCb);
    const double complex gamma = au * conj(bu) * aCb;

    /* Indices of the two modes (the model of docs/PHOTOELASTICITY.md) and their Airy series
     * t_x = tau_x e^{i k n_x h} sum_m rho_x^{2m} e^{2 i k m n_x h}. Orders m != m' differ in optical
     * path by about 2 n h (millimetres): far beyond the coherence length of a white or spectral-
     * lamp source, their interference averages out (for white light it is the table value
     * S(cos k 2nh) ~ 1e-6, docs). Within one order the e and o paths differ by (2m + 1) delta. */
    /* Monochromatic light: C at its wavelength (dispersion of birefringence; exactly C_per_Pa when
     * alpha is 0); white light: C at the reference wavelength, scaled per sample below. */
    const double C = s->light == BIREF_PE_MONO ? biref_pe_C_at(&s->material, s->lambda_nm) : s->material.C_per_Pa;
    const double n_o = s->material.n0;
    const double dn = C * (p->s1 - p->s2);
    const double n_e = n_o + dn;
    const double delta_nm = dn * s->thickness * 1e9;
    double tau_e, tau_o, rho2_e, rho2_o;
    airy_coeffs(n_e, s->eta_i, &tau_e, &rho2_e);
    airy_coeffs(n_o, s->eta_i, &tau_o, &rho2_o);
    /* <|t_x|^2> = tau_x^2 sum_m rho_x^{4m} = tau_x^2 / (1 - rho_x^4). */
    const double te2 = tau_e * tau_e / (1.0 - rho2_e * rho2_e);
    const double to2 = tau_o * tau_o / (1.0 - rho2_o * rho2_o);
    const double incoherent = alpha * te2 + beta * to2;
    const double q = rho2_e * rho2_o; /* weight ratio of consecutive orders in <t_e conj t_o> */
    const double tt = tau_e * tau_o;

    if (s->light == BIREF_PE_MONO) {
        /* <t_e conj t_o> = tau_e tau_o sum_m q^m e^{i k (2m+1) delta} = tau_e tau_o e^{ik delta} / (1 - q e^{2ik delta}). */
        const double ph = 2.0 * M_PI * delta_nm / s->lambda_nm;
        const double complex z = cexp(I * ph);
        const double complex cross = width_nm > 0.0 ? mono_cross_box(tt, q, z, width_nm * (C / s->material.C_per_Pa), s->lambda_nm)
                                                    : tt * z / (1.0 - q * z * z);
        const double v = incoherent + 2.0 * creal(gamma * cross);
        xyz[0] = xyz[1] = xyz[2] = v;
        return;
    }
    /* White light: band integrals S(e^{i k D}) = S(cos) + i S(sin) from the spectral table. */
    double cross_re[3] = {0, 0, 0}, cross_im[3] = {0, 0, 0};
    double w = s->material.dispersion_alpha != 0.0 ? 0.0 : tt;
    if (w == 0.0) white_dispersive_cross(s, sp, delta_nm, pf ? width_nm : 0.0, tt, q, cross_re, cross_im);
    for (int m = 0; m <= PE_MAX_ORDER && w > 0.0; m++) {
        double c[3], si[3];
        if (pf)
            biref_phase_integrals_box(pf, (2.0 * m + 1.0) * delta_nm, (2.0 * m + 1.0) * width_nm, c, si);
        else
            biref_spectral_phase_integrals(sp, (2.0 * m + 1.0) * delta_nm, c, si);
        for (int j = 0; j < 3; j++) {
            cross_re[j] += w * c[j];
            cross_im[j] += w * si[j];
        }
        w *= q;
        /* Prefiltered, the third order (weight q^2 ~ 1e-5 in air) is left out: it costs two
         * look-ups and changes the intensity by ~1e-5. */
        if (w < (pf && width_nm > 0.0 ? 1e-4 : 1e-7) * tt) break;
    }
    for (int j = 0; j < 3; j++)
        xyz[j] = incoherent + 2.0 * (creal(gamma) * cross_re[j] - cimag(gamma) * cross_im[j]);
}

/* |e J P|^2 summed over the coherency C: sum_{i,j,o} C_ij (J P)_io conj((J P)_jo). */
static double detect(const biref_pe_polariscope *pol, const biref_jones *J)
{
    double complex JP[2][2];
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++) JP[i][o] = J->m[i][0] * pol->P[0][o] + J->m[i][1] * pol->P[1][o];
    double complex sum = 0;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int o = 0; o < 2; o++) sum += pol->C[i][j] * JP[i][o] * conj(JP[j][o]);
    return creal(sum);
}

/* Transmission paths to this order for the monochromatic oblique case: order n carries the
 * intensity factor (internal reflectance)^(2n) ~ 0.05^(2n) in air, so stopping after order 2
 * leaves ~1e-8 of the intensity. */
#define PE_OBLIQUE_ORDER 2
#define PE_OBLIQUE_PATHS 42 /* 2 + 8 + 32 */

/* Monochromatic light on the prepared plate: the transmission paths to PE_OBLIQUE_ORDER, each
 * order's paths summed coherently and the orders in intensity (docs, "Coherence"). */
static biref_status mono_paths(const biref_pe_setup *s, const biref_slab_state *st, double xyz[3])
{
    biref_path paths[PE_OBLIQUE_PATHS];
    size_t n = biref_slab_paths(st, BIREF_TRANSMISSION, PE_OBLIQUE_ORDER, paths, PE_OBLIQUE_PATHS);
    if (n == 0) return BIREF_ERR_INVALID;
    const double k = 2.0 * M_PI / s->lambda_nm;
    /* A path's phase is the product of its legs' phases (its optical path is the sum of the
     * legs'), so powers of the four leg phases replace one complex exponential per path. */
    double complex pw[4][PE_OBLIQUE_ORDER + 2]; /* [o down, e down, o up, e up][power] */
    const double complex leg[4] = {cexp(I * k * st->opl_down[0]), cexp(I * k * st->opl_down[1]),
                                   cexp(I * k * st->opl_up[0]), cexp(I * k * st->opl_up[1])};
    for (int l = 0; l < 4; l++) {
        pw[l][0] = 1.0;
        for (int e = 1; e < PE_OBLIQUE_ORDER + 2; e++) pw[l][e] = pw[l][e - 1] * leg[l];
    }
    double sum = 0.0;
    size_t i = 0;
    for (int order = 0; order <= PE_OBLIQUE_ORDER; order++) {
        /* Coherent sum of this order's paths (listed in order of increasing order): order + 1
         * down legs, order up legs. */
        biref_jones J = {{{0, 0}, {0, 0}}};
        for (; i < n && paths[i].order == order; i++) {
            const int de = paths[i].n_down_e, ue = paths[i].n_up_e;
            double complex ph = pw[0][order + 1 - de] * pw[1][de] * pw[2][order - ue] * pw[3][ue];
            for (int a = 0; a < 2; a++)
                for (int b = 0; b < 2; b++) J.m[a][b] += paths[i].amp[a][b] * ph;
        }
        sum += detect(&s->pol, &J);
    }
    xyz[0] = xyz[1] = xyz[2] = sum;
    return BIREF_OK;
}

biref_status biref_pe_shade_state(const biref_pe_setup *s, const biref_integrator *it, const biref_slab_state *st,
                                  double xyz[3])
{
    if (s->light != BIREF_PE_WHITE) return mono_paths(s, st, xyz);
    if (!it) return BIREF_ERR_INVALID;
    biref_light light;
    biref_pe_light(&s->pol, &light);
    biref_integration res;
    biref_status r = biref_integrate(it, st, BIREF_SIDE_TRANSMISSION, &light, &res);
    if (r != BIREF_OK) return r;
    for (int j = 0; j < 3; j++) xyz[j] = res.T[j];
    return BIREF_OK;
}

biref_status biref_pe_shade_general(const biref_pe_setup *setup, const biref_spectral *sp,
                                    const biref_pe_principal *p, int jitter, double span_nm, double xyz[3])
{
    /* One slab for the whole band: white light with dispersion of C has no such slab. */
    if (setup->light == BIREF_PE_WHITE && setup->material.dispersion_alpha != 0.0) return BIREF_ERR_INVALID;
    const biref_pe_setup at = biref_pe_setup_at_lambda(setup), *s = &at;
    biref_slab slab = biref_pe_slab_at(&s->material, s->thickness, s->eta_i, p);
    biref_slab_state st;
    biref_status r;
    if (s->light == BIREF_PE_WHITE) {
        if (!sp) return BIREF_ERR_INVALID;
        if ((r = biref_slab_prepare(&slab, 0.0, &st)) != BIREF_OK) return r;
        biref_integrator *it = NULL;
        if ((r = biref_pe_expansion_integrator(sp, &it)) != BIREF_OK) return r;
        r = biref_pe_shade_state(s, it, &st, xyz);
        biref_integrator_destroy(it);
        return r;
    }
    if (jitter < 1) jitter = 1;
    double sum = 0.0;
    const double h0 = slab.thickness_nm;
    for (int k = 0; k < jitter; k++) {
        slab.thickness_nm = jitter == 1 ? h0 : h0 + span_nm * ((k + 0.5) / jitter - 0.5);
        if ((r = biref_slab_prepare(&slab, 0.0, &st)) != BIREF_OK) return r;
        biref_jones T;
        biref_slab_jones_at(&st, s->lambda_nm, &T, NULL);
        sum += detect(&s->pol, &T);
    }
    xyz[0] = xyz[1] = xyz[2] = sum / jitter;
    return BIREF_OK;
}

biref_status biref_pe_shade_oblique(const biref_pe_setup *setup, const biref_spectral *sp,
                                    const biref_pe_principal *p, double theta, double xyz[3])
{
    if (setup->light == BIREF_PE_WHITE && setup->material.dispersion_alpha != 0.0) return BIREF_ERR_INVALID;
    const biref_pe_setup at = biref_pe_setup_at_lambda(setup), *s = &at;
    biref_status r = biref_theta_check(theta, NULL, 0);
    if (r != BIREF_OK) return r;
    biref_slab slab = biref_pe_slab_best(&s->material, s->thickness, s->eta_i, p);
    biref_slab_state st;
    if ((r = biref_slab_prepare(&slab, theta, &st)) != BIREF_OK) return r;
    if (s->light != BIREF_PE_WHITE) return biref_pe_shade_state(s, NULL, &st, xyz);
    biref_integrator *it = NULL;
    if (!sp || (r = biref_pe_expansion_integrator(sp, &it)) != BIREF_OK) return sp ? r : BIREF_ERR_INVALID;
    r = biref_pe_shade_state(s, it, &st, xyz);
    biref_integrator_destroy(it);
    return r;
}
