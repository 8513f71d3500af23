/* The expansion's incoherent tail (the paths beyond the chosen orders, summed in closed form as
 * the geometric series of eqs. 20-21) and the choice of orders it drives (expansion.c). */
#include "spectral/analytic_terms.h"
#include "spectral/expansion_internal.h"
#include "spectral/subband.h"

static void inv_one_minus(const double M[2][2], double out[2][2])
{
    double a = 1.0 - M[0][0], b = -M[0][1], c = -M[1][0], d = 1.0 - M[1][1], det = a * d - b * c;
    out[0][0] = d / det, out[0][1] = -b / det, out[1][0] = -c / det, out[1][1] = a / det;
}

void biref_xp_tail_setup(const biref_spectral *sp, const biref_slab_state *st, int which, const quad_form *forms,
                       int nf, tail_model *tm)
{
    const double complex(*t01)[2] = st->top.t_down, (*r10)[2] = st->top.r_up, (*t10)[2] = st->top.t_up;
    const double complex(*r12)[2] = st->bottom.r_down, (*t12)[2] = st->bottom.t_down;
    const double complex(*exit)[2] = which == BIREF_REFLECTION ? t10 : t12;
    double ed[2][3], eu[2][3], in_q[EXP_MAX_FORMS][2], out_q[EXP_MAX_FORMS][2];
    tm->bands = st->total_reflection ? 3 : 1;
    tm->lowest = which == BIREF_TRANSMISSION ? 0 : 1;
    for (int m = 0; m < 2; m++) biref_leg_energy(sp, st->opl_down[m], ed[m]), biref_leg_energy(sp, st->opl_up[m], eu[m]);
    for (int k = 0; k < nf; k++) {
        const double complex(*C)[2] = forms[k].C, (*P)[2] = forms[k].P;
        for (int x = 0; x < 2; x++) {
            double q = 0.0;
            for (int i = 0; i < 2; i++)
                for (int jj = 0; jj < 2; jj++) q += creal(C[i][jj] * t01[i][x] * conj(t01[jj][x]));
            in_q[k][x] = q;
            double o2 = 0.0;
            for (int o = 0; o < 2; o++) {
                double complex v = P ? exit[x][0] * P[0][o] + exit[x][1] * P[1][o] : exit[x][o];
                o2 += biref_abs2(v);
            }
            out_q[k][x] = o2;
        }
    }
    for (int j = 0; j < tm->bands; j++) {
        for (int a = 0; a < 2; a++)
            for (int c = 0; c < 2; c++) {
                double e = 0.0;
                for (int b = 0; b < 2; b++)
                    e += which == BIREF_TRANSMISSION ? biref_abs2(r12[a][b]) * eu[b][j] * biref_abs2(r10[b][c]) * ed[c][j]
                                                     : biref_abs2(r10[a][b]) * ed[b][j] * biref_abs2(r12[b][c]) * eu[c][j];
                tm->Dbar[j][a][c] = e;
            }
        double inv[2][2];
        inv_one_minus(tm->Dbar[j], inv);
        for (int k = 0; k < nf; k++)
            for (int a = 0; a < 2; a++) {
                if (which == BIREF_TRANSMISSION)
                    tm->first[k][j][a] = in_q[k][a] * ed[a][j];
                else
                    tm->first[k][j][a] = (in_q[k][0] * ed[0][j] * biref_abs2(r12[0][a]) + in_q[k][1] * ed[1][j] * biref_abs2(r12[1][a])) * eu[a][j];
                tm->y[k][j][a] = inv[a][0] * out_q[k][0] + inv[a][1] * out_q[k][1];
            }
    }
}

/* One round trip of the incoherent energies: v <- v Dbar. */
static inline void tail_step(const double D[2][2], double v[2])
{
    double w0 = v[0] * D[0][0] + v[1] * D[1][0], w1 = v[0] * D[0][1] + v[1] * D[1][1];
    v[0] = w0, v[1] = w1;
}

/* Incoherent energy of the paths of orders > order, per band, for form k. */
void biref_xp_tail_energy(const tail_model *tm, int k, int order, double out[3])
{
    for (int j = 0; j < tm->bands; j++) {
        double v[2] = {tm->first[k][j][0], tm->first[k][j][1]};
        for (int s = tm->lowest; s <= order; s++) tail_step(tm->Dbar[j], v);
        out[j] = v[0] * tm->y[k][j][0] + v[1] * tm->y[k][j][1];
    }
    if (tm->bands == 1) out[1] = out[2] = out[0];
}

/* Each order is the smallest whose truncation error is below tol (relative to the energy of
 * the orders the expansion covers, per form and band):
 *  - groups: the incoherent tail ignores the coherence inside the groups beyond the order, an
 *    error of the order of E_tail;
 *  - pairs: the interference left out beyond the order (a) among groups of one order, at most
 *    ~E_tail times the band coherence at the birefringent lags within an order, and (b) between
 *    orders, at most 2 sqrt(E_tail E_total) times the coherence at the shortest round trip. For
 *    mm-thick slabs both coherences are ~1e-5 away from the optic axis, so order 1 suffices;
 *    thin or near-axis slabs get more orders.
 * Measured on the fig. 9 sweep (docs/ACCURACY.md) rather than proven: (a) counts only the
 * shortest lags. */
expansion_orders biref_xp_choose_orders(phase_cache *pc, const biref_slab_state *st, const tail_model *tm, int nf,
                                      const biref_expansion_opts *o)
{
    const int lowest = tm->lowest;
    if (o->order >= 0) {
        int n = o->order < lowest ? lowest : (o->order > EXP_MAX_ORDER ? EXP_MAX_ORDER : o->order);
        return (expansion_orders){n, n};
    }
    int cap = o->max_order < 1 ? 1 : (o->max_order > EXP_MAX_ORDER ? EXP_MAX_ORDER : o->max_order);
    const double complex *od = st->opl_down, *ou = st->opl_up;
    double d_rt = INFINITY;
    int rx = 0, ry = 0;
    for (int x = 0; x < 2; x++)
        for (int y = 0; y < 2; y++)
            if (creal(od[x] + ou[y]) < d_rt) d_rt = creal(od[x] + ou[y]), rx = x, ry = y;
    double coh_cross = band_coherence(pc, 1, rx, ry);
    /* Degenerate legs (B = C) make this 1: merged groups differ by whole e legs, and the bound
     * must count the interference between them. */
    double coh_intra = dmax2(dmax2(band_coherence(pc, 0, 1, 0), band_coherence(pc, 0, 0, 1)),
                             dmax2(band_coherence(pc, 0, 1, 1), band_coherence(pc, 0, 1, -1)));
    /* Tail energies by forward iteration (tail_energy for every candidate order at once). */
    const int nb = tm->bands;
    double total[EXP_MAX_FORMS][3], v[EXP_MAX_FORMS][3][2];
    for (int k = 0; k < nf; k++)
        for (int j = 0; j < nb; j++) {
            v[k][j][0] = tm->first[k][j][0];
            v[k][j][1] = tm->first[k][j][1];
            total[k][j] = v[k][j][0] * tm->y[k][j][0] + v[k][j][1] * tm->y[k][j][1];
        }
    expansion_orders r = {cap, cap};
    int have_pairs = 0, have_groups = 0;
    for (int n = 1; n < cap && !(have_pairs && have_groups); n++) {
        int ok_pairs = 1, ok_groups = 1;
        for (int k = 0; k < nf; k++)
            for (int j = 0; j < nb; j++) {
                /* from the energy arriving at order n (at the lowest order for n = 1) to order n + 1 */
                for (int step = n == 1 ? 2 - lowest : 1; step > 0; step--) tail_step(tm->Dbar[j], v[k][j]);
                double tail = v[k][j][0] * tm->y[k][j][0] + v[k][j][1] * tm->y[k][j][1];
                double limit = o->tolerance * total[k][j] + 1e-300;
                if (tail > limit) ok_groups = 0;
                if (tail * coh_intra + 2.0 * sqrt(tail * total[k][j]) * coh_cross > limit) ok_pairs = 0;
            }
        if (ok_pairs && !have_pairs) r.pairs = n, have_pairs = 1;
        if (ok_groups && !have_groups) r.groups = n, have_groups = 1;
    }
    /* At most two orders of own intensities beyond the interfering ones: they carry most of the
     * tail (it falls by the round-trip reflectance per order), and the amplitude recursion costs
     * ~ order^3 (bench_spectral --truncation, 70-85 deg: worst relative error 0.18 with none,
     * 0.045 with two, 0.0068 without the limit at 1.2x the cost; docs/PHYSICS.md §5). */
    if (r.groups > r.pairs + 2) r.groups = r.pairs + 2;
    if (r.groups < r.pairs) r.groups = r.pairs;
    /* A dispersive slab's band runs (analytic_dispersive.c): a band's two runs, on slabs a little
     * apart in k, may land on either side of a threshold; their results are added, so they take
     * the same orders (the floor; the larger of two choices keeps both invariants above). */
    struct biref_leg_dispersion *ld = pc->fp ? pc->fp->disp : NULL;
    if (ld) {
        const int d = tm->lowest; /* 0: transmission, 1: reflection */
        r.pairs = r.pairs > ld->order_floor[d][0] ? r.pairs : ld->order_floor[d][0];
        r.groups = r.groups > ld->order_floor[d][1] ? r.groups : ld->order_floor[d][1];
        if (r.pairs > ld->order_seen[d][0]) ld->order_seen[d][0] = r.pairs;
        if (r.groups > ld->order_seen[d][1]) ld->order_seen[d][1] = r.groups;
    }
    return r;
}


void biref_expansion_tail(const biref_spectral *sp, const biref_slab_state *st, int which, const double complex C[2][2],
                          const double complex P[2][2], int order, double out[3])
{
    quad_form f = {C, P};
    tail_model tm;
    biref_xp_tail_setup(sp, st, which, &f, 1, &tm);
    biref_xp_tail_energy(&tm, 0, order, out);
}

