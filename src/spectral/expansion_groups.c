/* The path groups of the expansion (expansion.c): amplitudes M_g of all paths with the same
 * numbers of o/e legs down and up, by dynamic programming over half round trips. */
#include "spectral/expansion_internal.h"

/* When an extraordinary leg has the same optical path down and up (B = C, e.g. an optic axis in
 * the plane of incidence's normal section), groups differing only in where the e legs sit share
 * one optical path: they are exactly coherent and are merged into one group per (m, de + ue).
 * The merge tolerance keeps the phase error of the merged groups below ~0.01 rad at every order. */
#define DEGENERATE_LEG_NM (0.5 / (2 * EXP_MAX_ORDER + 2))

static int legs_degenerate(const biref_slab_state *st)
{
    double b = creal(st->opl_down[1] - st->opl_down[0]), c = creal(st->opl_up[1] - st->opl_up[0]);
    double bi = cimag(st->opl_down[1] - st->opl_down[0]), ci = cimag(st->opl_up[1] - st->opl_up[0]);
    return fabs(b - c) < DEGENERATE_LEG_NM && fabs(bi - ci) < DEGENERATE_LEG_NM;
}

/* Merges groups with equal (m, de + ue) in place; returns the new count. Group order is kept
 * by order m, so the first group of each class stays where it was. */
static int merge_degenerate(path_group *g, int G)
{
    int n = 0;
    for (int a = 0; a < G; a++) {
        int s = g[a].de + g[a].ue, found = -1;
        for (int b = n - 1; b >= 0 && g[b].m == g[a].m; b--)
            if (g[b].de == s) {
                found = b;
                break;
            }
        if (found < 0) {
            g[n] = g[a];
            g[n].de = s;
            g[n].ue = 0;
            n++;
        } else {
            for (int i = 0; i < 2; i++)
                for (int o = 0; o < 2; o++) g[found].M[i][o] += g[a].M[i][o];
        }
    }
    return n;
}

/* Group amplitudes by dynamic programming over legs: state = (e legs down, e legs up, current
 * mode), value = row vector over the two inputs. Transmission and reflection share it: after
 * m + 1 down and m up legs the light at the bottom face either leaves (transmission, order m)
 * or is reflected and goes up, and at the top face after m + 1 legs each way it either leaves
 * (reflection, order m + 1) or is reflected down again. One recursion in half round trips
 * serves both. */
typedef double complex dp_layer[EXP_MAX_ORDER + 2][EXP_MAX_ORDER + 2][2][2]; /* [de][ue][mode][input] */

/* dst[de + (down ? mode : 0)][ue + (down ? 0 : mode)][mode] += src[de][ue][x] r[x][mode] over the
 * region de <= nd, ue <= nu of src: one reflection and the following leg. */
static void dp_half_step(const dp_layer *src, int nd, int nu, const double complex (*r)[2], int down, dp_layer *dst)
{
    for (int de = 0; de <= nd + down; de++) memset((*dst)[de], 0, (size_t)(nu + 2 - down) * sizeof (*dst)[de][0]);
    for (int de = 0; de <= nd; de++)
        for (int ue = 0; ue <= nu; ue++) {
            /* [mode x][input i] as re, im: both modes and inputs at once, in real arithmetic. */
            const double *x = (const double *)(*src)[de][ue];
            for (int y = 0; y < 2; y++) {
                double *t = (double *)(*dst)[de + (down ? y : 0)][ue + (down ? 0 : y)][y];
                const double fr0 = creal(r[0][y]), fi0 = cimag(r[0][y]), fr1 = creal(r[1][y]), fi1 = cimag(r[1][y]);
                t[0] += x[0] * fr0 - x[1] * fi0 + x[4] * fr1 - x[5] * fi1;
                t[1] += x[0] * fi0 + x[1] * fr0 + x[4] * fi1 + x[5] * fr1;
                t[2] += x[2] * fr0 - x[3] * fi0 + x[6] * fr1 - x[7] * fi1;
                t[3] += x[2] * fi0 + x[3] * fr0 + x[6] * fi1 + x[7] * fr1;
            }
        }
}

/* The groups of one order leaving through `exit`, appended to g. */
static int emit_groups(const biref_slab_state *st, const dp_layer *cur, int m, int n_down, int n_up,
                       const double complex (*exit)[2], path_group *g, int n)
{
    const double complex *od = st->opl_down, *ou = st->opl_up;
    for (int de = 0; de <= n_down; de++)
        for (int ue = 0; ue <= n_up; ue++) {
            path_group *p = &g[n++];
            const double complex(*v)[2] = (*cur)[de][ue];
            for (int i = 0; i < 2; i++)
                for (int o = 0; o < 2; o++) p->M[i][o] = v[0][i] * exit[0][o] + v[1][i] * exit[1][o];
            /* Only the decay of evanescent legs needs it: lags come from the integer coordinates.
             * Transmission's extra down leg is common to all its groups and cancels in differences. */
            p->opl = st->total_reflection ? (n_down - de) * od[0] + de * od[1] + (n_up - ue) * ou[0] + ue * ou[1] : 0.0;
            p->m = m;
            p->de = de;
            p->ue = ue;
        }
    return n;
}

/* Transmission groups of orders 0..nT into gT (nT < 0: none) and reflection groups of orders
 * 0..nR into gR (nR < 0: none), sorted by order; returns their numbers in *GT, *GR. */
void biref_xp_build_groups(const biref_slab_state *st, int nT, path_group *gT, int *GT, int nR, path_group *gR, int *GR)
{
    const double complex(*t01)[2] = st->top.t_down, (*r10)[2] = st->top.r_up, (*t10)[2] = st->top.t_up;
    const double complex(*r12)[2] = st->bottom.r_down, (*t12)[2] = st->bottom.t_down;
    dp_layer down, up; /* light at the bottom face (after m + 1 down, m up legs), at the top face */
    int nt = 0, nr = 0;
    if (nR >= 0) {
        memcpy(gR[0].M, st->top.r_down, sizeof gR[0].M);
        gR[0].m = gR[0].de = gR[0].ue = 0;
        gR[0].opl = 0.0;
        nr = 1;
    }
    const int rounds = nT > nR - 1 ? nT : nR - 1;
    if (rounds >= 0) {
        memset(down, 0, 2 * sizeof down[0]);
        for (int x = 0; x < 2; x++)
            for (int i = 0; i < 2; i++) down[x][0][x][i] = t01[i][x];
    }
    for (int m = 0; m <= rounds; m++) {
        if (m <= nT) nt = emit_groups(st, (const dp_layer *)&down, m, m + 1, m, t12, gT, nt);
        if (m + 1 > nR && m == rounds) break;
        dp_half_step((const dp_layer *)&down, m + 1, m, r12, 0, &up);
        if (m + 1 <= nR) nr = emit_groups(st, (const dp_layer *)&up, m + 1, m + 1, m + 1, t10, gR, nr);
        if (m == rounds) break;
        dp_half_step((const dp_layer *)&up, m + 1, m + 1, r10, 1, &down);
    }
    if (GT) *GT = nt;
    if (GR) *GR = nr;
}

/* Degenerate legs merged (see merge_degenerate). */
int biref_xp_merged(const biref_slab_state *st, path_group *g, int G) { return legs_degenerate(st) ? merge_degenerate(g, G) : G; }

/* Number of leading groups of order <= n (groups are sorted by order). */
int biref_xp_groups_below(const path_group *g, int G, int n)
{
    int a = 0;
    while (a < G && g[a].m <= n) a++;
    return a;
}

