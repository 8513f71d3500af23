/* Stacks of layers: checks, the wavelength-independent state (modes, interfaces, optical paths)
 * and the exact Jones matrices, by the transfer matrix of the stack in its scattering form
 * (docs/STACKS.md §1): the reflection and transmission of everything below a layer's bottom
 * face, carried upwards one interface and one layer at a time. Only decaying exponentials
 * appear, so evanescent layers and total reflection are as safe as in the slab (slab.c), whose
 * eq. 17 is the one-layer case of the same recursion, operation for operation. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "biref/stack.h"
#include "optics/cmat2.h"
#include "optics/modes_internal.h"
#include "optics/slab_internal.h"
#include "optics/validate.h"

static biref_status layer_check(const biref_layer *l, int i, char *msg, size_t msg_len)
{
    if (l->material) {
        biref_material_info info;
        biref_material_get_info(l->material, &info);
        char why[128] = "";
        if (!l->isotropic && !info.isotropic && biref_check_axis(l->axis, why, sizeof why) != BIREF_OK)
            return biref_fail(msg, msg_len, "layers[%d]: %s", i, why);
        if (!isfinite(l->thickness_nm) || l->thickness_nm <= 0.0)
            return biref_fail(msg, msg_len, "layers[%d]: thickness must be a positive finite length (got %g nm)", i,
                              l->thickness_nm);
        return BIREF_OK;
    }
    char name[48];
    snprintf(name, sizeof name, "layers[%d].%s", i, l->isotropic ? "eta" : "eta_o");
    biref_status s = biref_check_index(name, l->eta_o, msg, msg_len);
    if (s != BIREF_OK) return s;
    if (!l->isotropic) {
        snprintf(name, sizeof name, "layers[%d].eta_e", i);
        if ((s = biref_check_index(name, l->eta_e, msg, msg_len)) != BIREF_OK) return s;
        char why[128] = "";
        if (biref_check_axis(l->axis, why, sizeof why) != BIREF_OK)
            return biref_fail(msg, msg_len, "layers[%d]: %s", i, why);
    }
    if (!isfinite(l->thickness_nm) || l->thickness_nm <= 0.0)
        return biref_fail(msg, msg_len, "layers[%d]: thickness must be a positive finite length (got %g nm)", i,
                          l->thickness_nm);
    return BIREF_OK;
}

biref_status biref_stack_check(const biref_stack *stack, char *msg, size_t msg_len)
{
    if (!stack) return biref_fail(msg, msg_len, "stack is NULL");
    biref_status s = biref_check_index("eta_i", stack->eta_i, msg, msg_len);
    if (s != BIREF_OK) return s;
    if (stack->n_layers < 1 || stack->n_layers > BIREF_STACK_MAX_LAYERS)
        return biref_fail(msg, msg_len, "a stack has 1 to %d layers (got %d)", BIREF_STACK_MAX_LAYERS,
                          stack->n_layers);
    for (int i = 0; i < stack->n_layers; i++)
        if ((s = layer_check(&stack->layers[i], i, msg, msg_len)) != BIREF_OK) return s;
    return BIREF_OK;
}

void biref_stack_from_slab(const biref_slab *slab, biref_stack *out)
{
    memset(out, 0, sizeof *out);
    out->eta_i = slab->eta_i;
    out->n_layers = 1;
    biref_layer *l = &out->layers[0];
    l->eta_o = slab->eta_o;
    l->eta_e = slab->eta_e;
    memcpy(l->axis, slab->axis, sizeof l->axis);
    l->thickness_nm = slab->thickness_nm;
}

int biref_stack_dispersive(const biref_stack *stack)
{
    for (int i = 0; i < stack->n_layers && i < BIREF_STACK_MAX_LAYERS; i++)
        if (stack->layers[i].material) return 1;
    return 0;
}

biref_status biref_stack_at(const biref_stack *stack, double lambda_nm, biref_stack *out)
{
    if (biref_check_lambda(lambda_nm, NULL, 0) != BIREF_OK || stack->n_layers < 1 ||
        stack->n_layers > BIREF_STACK_MAX_LAYERS)
        return BIREF_ERR_INVALID;
    out->eta_i = stack->eta_i;
    out->n_layers = stack->n_layers;
    for (int i = 0; i < stack->n_layers; i++) {
        biref_layer *l = &out->layers[i];
        *l = stack->layers[i];
        if (!l->material) continue;
        double n[2];
        biref_status s = biref_material_indices(l->material, lambda_nm, n, NULL);
        if (s != BIREF_OK) return s;
        biref_material_info info;
        biref_material_get_info(l->material, &info);
        l->isotropic = l->isotropic || info.isotropic;
        l->eta_o = n[0];
        l->eta_e = l->isotropic ? n[0] : n[1];
        l->material = NULL;
    }
    return BIREF_OK;
}

/* Power across y per unit amplitude, Re(E* x H)_y, of each mode (0 when evanescent). */
static void mode_flux(const biref_modes *m, int evanescent_o, int evanescent_e, double incident, double out[4])
{
    for (int i = 0; i < 4; i++) {
        int ev = (i == BIREF_MODE_O_DOWN || i == BIREF_MODE_O_UP) ? evanescent_o : evanescent_e;
        double complex s = conj(m->E[i][2]) * m->H[i][0] - conj(m->E[i][0]) * m->H[i][2];
        out[i] = ev ? 0.0 : fabs(creal(s)) / incident;
    }
}

/* The state of a stack without dispersive layers. */
static biref_status prepare_constant(const biref_stack *stack, double theta, biref_stack_state *st)
{
    biref_status s = biref_stack_check(stack, NULL, 0);
    if (s == BIREF_OK) s = biref_theta_check(theta, NULL, 0);
    if (s != BIREF_OK) return s;
    memset(st, 0, sizeof *st);
    const int n = stack->n_layers;
    st->theta = theta;
    st->eta_i = stack->eta_i;
    st->K = stack->eta_i * sin(theta); /* eq. 1, conserved through every interface */
    st->n_layers = n;
    biref_modes above, below;
    biref_isotropic_modes(stack->eta_i, st->K, &above);
    const double incident = stack->eta_i * cos(theta);
    for (int j = 0; j <= n; j++) {
        if (j < n) {
            const biref_layer *l = &stack->layers[j];
            if (l->isotropic) {
                biref_isotropic_modes(l->eta_o, st->K, &below);
            } else {
                double a[3];
                biref_axis_unit_unchecked(l->axis, a);
                biref_uniaxial_mode_fields(l->eta_o, l->eta_e, a, st->K, &below);
            }
            const double d = l->thickness_nm;
            st->thickness_nm[j] = d;
            for (int x = 0; x < 2; x++) {
                st->opl_down[j][x] = -below.q[BIREF_MODE_O_DOWN + x] * d;
                st->opl_up[j][x] = below.q[BIREF_MODE_O_UP + x] * d;
            }
            mode_flux(&below, below.evanescent_o, below.evanescent_e, incident, st->flux[j]);
            st->evanescent += below.evanescent_o || below.evanescent_e;
        } else {
            biref_isotropic_modes(stack->eta_i, st->K, &below);
        }
        s = biref_interface_from_modes(&above, &below, &st->iface[j]);
        if (s != BIREF_OK) return s;
        above = below;
    }
    return BIREF_OK;
}

biref_status biref_stack_prepare_at(const biref_stack *stack, double theta, double lambda_nm, biref_stack_state *st)
{
    if (!stack || !st) return BIREF_ERR_INVALID;
    if (!biref_stack_dispersive(stack)) return prepare_constant(stack, theta, st);
    biref_stack at;
    biref_status s = biref_stack_check(stack, NULL, 0);
    if (s == BIREF_OK) s = biref_stack_at(stack, lambda_nm, &at);
    if (s == BIREF_OK) s = prepare_constant(&at, theta, st);
    if (s != BIREF_OK) return s;
    st->dispersive = 1;
    st->lambda_nm = lambda_nm;
    st->stack = *stack;
    return BIREF_OK;
}

biref_status biref_stack_prepare(const biref_stack *stack, double theta, biref_stack_state *st)
{
    return biref_stack_prepare_at(stack, theta, BIREF_STACK_REFERENCE_NM, st);
}

static void jones_nan(biref_jones *J)
{
    if (!J) return;
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++) J->m[i][o] = NAN;
}

void biref_stack_jones_at(const biref_stack_state *st, double lambda_nm, biref_jones *T, biref_jones *R)
{
    if (st->dispersive && lambda_nm != st->lambda_nm) {
        /* n(λ) everywhere: modes, interfaces and optical paths at this wavelength. */
        biref_stack_state at;
        if (biref_stack_prepare_at(&st->stack, st->theta, lambda_nm, &at) != BIREF_OK) {
            jones_nan(T);
            jones_nan(R);
            return;
        }
        biref_stack_jones_at(&at, lambda_nm, T, R);
        return;
    }
    const double k = 2.0 * M_PI / lambda_nm;
    const int n = st->n_layers;
    /* rho, tau: reflection (down-going -> up-going modes, both at the face) and transmission (to
     * the surround below) of everything under the bottom face of layer j, starting at the last. */
    cmat2 rho = cmat2_from(st->iface[n].r_down), tau = cmat2_from(st->iface[n].t_down);
    for (int j = n - 1; j >= 0; j--) {
        /* Layer j + 1 (index j) lies under interface j. */
        const double complex pd0 = cexp(I * k * st->opl_down[j][0]), pd1 = cexp(I * k * st->opl_down[j][1]);
        const double complex pu0 = cexp(I * k * st->opl_up[j][0]), pu1 = cexp(I * k * st->opl_up[j][1]);
        const biref_interface *f = &st->iface[j];
        cmat2 down_rho = cmat2_scale_rows(rho, pd0, pd1);
        cmat2 X = cmat2_mul(down_rho, cmat2_scale_rows(cmat2_from(f->r_up), pu0, pu1)); /* round trip, eq. 15 */
        cmat2 entry = cmat2_mul(cmat2_from(f->t_down), cmat2_inv_one_minus(X));
        cmat2 new_tau = cmat2_mul(entry, cmat2_scale_rows(tau, pd0, pd1)); /* eq. 17 */
        if (j > 0 || R) {
            cmat2 back = cmat2_mul(down_rho, cmat2_scale_rows(cmat2_from(f->t_up), pu0, pu1));
            rho = cmat2_add(cmat2_from(f->r_down), cmat2_mul(entry, back));
        }
        tau = new_tau;
    }
    if (T) memcpy(T->m, tau.m, sizeof tau.m);
    if (R) memcpy(R->m, rho.m, sizeof rho.m);
}

biref_status biref_stack_jones(const biref_stack *stack, double theta, double lambda_nm, biref_jones *T,
                               biref_jones *R)
{
    if (biref_check_lambda(lambda_nm, NULL, 0) != BIREF_OK) return BIREF_ERR_INVALID;
    biref_stack_state st;
    biref_status s = biref_stack_prepare_at(stack, theta, lambda_nm, &st);
    if (s != BIREF_OK) return s;
    biref_stack_jones_at(&st, lambda_nm, T, R);
    return BIREF_OK;
}
