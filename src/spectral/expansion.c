/* Exact spectral integration of the path-group expansion, for any polarizer and analyzer
 * (beyond the paper).
 *
 * Ignoring dispersion within a band, J(k) = sum_g M_g e^{ik Phi_g}: a group g collects the
 * paths with the same numbers of o/e legs down and up, hence the same optical path Phi_g. For an
 * incident coherency matrix C and an analyzer P the detected intensity is
 *     I(k) = sum_{g,h} c_gh e^{ik(Phi_g - conj Phi_h)},   c_gh = sum C_ij (M_g P)_io conj((M_h P)_jo),
 * so its band integral is exact given S(cos kD) and S(sin kD) at the pairwise differences. The
 * paper's eq. 26 keeps only some pairs (order 0 and "descendants"); here every pair up to the
 * pair order interferes, groups of up to two more orders add their own intensity (the paths of a
 * group are coherent with each other), and the paths beyond add their energy incoherently, summed
 * in closed form (the geometric series of eq. 20-21); see choose_orders and docs/PHYSICS.md §5. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "spectral/phase_prefilter.h"
#include "spectral/spectral_internal.h"

#define EXP_MAX_ORDER BIREF_EXPANSION_MAX_ORDER
/* Transmission: sum_{m<=8} (m+2)(m+1) = 330 groups; reflection: 1 + sum_{m=1..8} (m+1)^2 = 285. */
#define EXP_MAX_GROUPS 330
#define EXP_MAX_FORMS 4

typedef struct {
    double complex M[2][2]; /* [in][out] */
    double complex opl;     /* nm */
    int m, de, ue;          /* round trips, extraordinary legs down, up: see phase_key */
} path_group;

/* Every optical path is a + m A + n_de B + n_ue C with A a round trip of ordinary legs and
 * B, C the extra path of an extraordinary leg down / up, so the real part of a pairwise
 * difference depends only on the difference of the integer coordinates (a lag): the band
 * integrals are needed once per distinct lag, not once per pair. */
static inline int phase_key(int m, int de, int ue) { return (m + 32) * 4096 + (de + 32) * 64 + (ue + 32); }

enum { CACHE_SLOTS = 1024, CACHE_MAX_FILL = 768 };

typedef struct {
    const biref_spectral *sp;
    const biref_opl_footprint *fp; /* NULL: point values */
    double A, B, C; /* real parts, nm */
    /* Lags between different orders (dm != 0): a small open-addressing hash, initialised on
     * first use (thick slabs never need it: see block_pair_vanishes). */
    int hash_ready;
    int key[CACHE_SLOTS];
    int fill;
    double c[CACHE_SLOTS][3], s[CACHE_SLOTS][3];
    /* Same-order lags with |dde|, |due| <= 1: asked for by the order choice and again by the
     * pair sums (at order 1 they are all the lags there are). */
    unsigned char near_have[3][3];
    double near_c[3][3][3], near_s[3][3][3];
} phase_cache;

static void cache_init(phase_cache *pc, const biref_spectral *sp, const biref_slab_state *st,
                       const biref_opl_footprint *fp)
{
    pc->sp = sp;
    pc->fp = fp;
    pc->A = creal(st->opl_down[0] + st->opl_up[0]);
    pc->B = creal(st->opl_down[1] - st->opl_down[0]);
    pc->C = creal(st->opl_up[1] - st->opl_up[0]);
    pc->hash_ready = 0;
    memset(pc->near_have, 0, sizeof pc->near_have);
}

static inline double lag_opd(const phase_cache *pc, int dm, int dde, int due)
{
    return dm * pc->A + dde * pc->B + due * pc->C;
}

/* S(cos), S(sin) of the lag (dm, dde, due), averaged over the pixel's footprint if there is one:
 * its legs are dm (o down + o up) + dde (e down - o down) + due (e up - o up). */
static void lag_integrals(const phase_cache *pc, int dm, int dde, int due, double c[3], double s[3])
{
    const int n[4] = {dm - dde, dde, dm - due, due};
    biref_phase_integrals_footprint(pc->sp, pc->fp, lag_opd(pc, dm, dde, due), n, c, s);
}

/* S(cos), S(sin) of the same-order lag (dde, due). */
static void lag0_integrals(phase_cache *pc, int dde, int due, double c[3], double s[3])
{
    if (dde < -1 || dde > 1 || due < -1 || due > 1) {
        lag_integrals(pc, 0, dde, due, c, s);
        return;
    }
    if (!pc->near_have[dde + 1][due + 1]) {
        lag_integrals(pc, 0, dde, due, pc->near_c[dde + 1][due + 1],
                                       pc->near_s[dde + 1][due + 1]);
        pc->near_have[dde + 1][due + 1] = 1;
    }
    memcpy(c, pc->near_c[dde + 1][due + 1], 3 * sizeof *c);
    memcpy(s, pc->near_s[dde + 1][due + 1], 3 * sizeof *s);
}

/* Hash slot of the lag (dm, dde, due), its S(cos), S(sin) computed on first use; -1 once the
 * table is 3/4 full (keeps probes short for thin slabs at high orders). */
static int cache_slot(phase_cache *pc, int dm, int dde, int due)
{
    if (!pc->hash_ready) {
        for (int i = 0; i < CACHE_SLOTS; i++) pc->key[i] = -1;
        pc->fill = 0;
        pc->hash_ready = 1;
    }
    int key = phase_key(dm, dde, due);
    unsigned h = ((unsigned)key * 2654435761u) >> 22; /* 10 bits */
    for (;;) {
        if (pc->key[h] == key) return (int)h;
        if (pc->key[h] < 0) {
            if (pc->fill >= CACHE_MAX_FILL) return -1;
            pc->key[h] = key;
            pc->fill++;
            lag_integrals(pc, dm, dde, due, pc->c[h], pc->s[h]);
            return (int)h;
        }
        h = (h + 1) & (CACHE_SLOTS - 1u);
    }
}

/* The detected intensity of a form is sum_{a,b} <v_a, v_b> e^{ik(Phi_a - conj Phi_b)}, with one
 * vector v_g of up to MAX_COMP components per group (the coherency matrix and the analyzer
 * factored as sums of outer products, see form_vectors): the pair sums below work per
 * component and never see the polarizers. */
enum { MAX_COMP = 4 };
/* Same-order lags: dde in [-(2 max + 1), 2 max + 1] (merged degenerate groups carry de + ue),
 * due in [-max, max]. */
#define LAG0_DE (2 * (2 * EXP_MAX_ORDER + 1) + 1)
#define LAG0_UE (2 * EXP_MAX_ORDER + 1)

typedef struct {
    double complex lag0[LAG0_DE * LAG0_UE][MAX_COMP]; /* dm = 0, dense */
    double complex hash[CACHE_SLOTS][MAX_COMP];       /* dm != 0, per hash slot */
    unsigned char used[CACHE_SLOTS];
    short list[CACHE_SLOTS];
    int n;
} pair_accumulator;

/* The box of integer coordinates (m, de, ue) spanned by one block of equal order. */
typedef struct {
    int lo[3], hi[3];
} lag_box;

static inline double dmin2(double a, double b) { return a < b ? a : b; }
static inline double dmax2(double a, double b) { return a > b ? a : b; }

/* Whether every pair between two blocks of different orders has a real path difference beyond
 * the look-up table's far limit, where the band integrals are exactly zero: the difference is
 * linear in the integer lags, so its range over the box of lags is spanned by the box's
 * corners. For mm-thick slabs a round trip is far beyond it and every cross-order block is
 * skipped; the pair count then falls from ~G^2/2 to ~sum_m G_m^2/2. */
static int block_pair_vanishes(const phase_cache *pc, const lag_box *p, const lag_box *q)
{
    const double coef[3] = {pc->A, pc->B, pc->C};
    double dmin = 0.0, dmax = 0.0;
    for (int i = 0; i < 3; i++) {
        double l = coef[i] * (p->lo[i] - q->hi[i]), h = coef[i] * (p->hi[i] - q->lo[i]);
        dmin += dmin2(l, h);
        dmax += dmax2(l, h);
    }
    const double far = pc->sp->d_far * (1.0 + 1e-9);
    return dmin > far || dmax < -far;
}

/* out[c] += 2 Re(z[c] S(e^{ikD})) per band, given S(cos kD), S(sin kD): the pairs (a, b) and (b, a)
 * of one lag together. */
static inline void add_pair_integral(double out[][3], const double complex z[MAX_COMP], const double cc[3],
                                     const double ss[3])
{
    for (int c = 0; c < MAX_COMP; c++)
        for (int j = 0; j < 3; j++) out[c][j] += 2.0 * (creal(z[c]) * cc[j] - cimag(z[c]) * ss[j]);
}

/* Band integrals of the pair sums per component: out[c][j] = sum_{a,b} S_j(v_a[c] conj(v_b[c])
 * e^{ik(Phi_a - conj Phi_b)}) over the pairs among the first Gp groups, plus the own intensity
 * of all G groups. Groups must be sorted by order m. Always MAX_COMP components (unused ones
 * zero): fixed trip counts let the compiler unroll the inner loops. */
static void pair_sums(phase_cache *pc, const path_group *g, int G, int Gp, const double complex (*v)[MAX_COMP],
                      int evanescent, double out[][3])
{
    const double *kc = pc->sp->k_centroid;
    for (int c = 0; c < MAX_COMP; c++) out[c][0] = out[c][1] = out[c][2] = 0.0;
    for (int a = 0; a < G; a++) {
        double att[3] = {1.0, 1.0, 1.0};
        double im = 2.0 * cimag(g[a].opl); /* decay of evanescent legs */
        if (im != 0.0)
            for (int j = 0; j < 3; j++) att[j] = exp(-kc[j] * im);
        for (int c = 0; c < MAX_COMP; c++) {
            double e = creal(v[a][c]) * creal(v[a][c]) + cimag(v[a][c]) * cimag(v[a][c]);
            for (int j = 0; j < 3; j++) out[c][j] += att[j] * e;
        }
    }
    if (evanescent) {
        /* Rare (total internal reflection inside): every pair with its own decay. */
        for (int a = 0; a < Gp; a++)
            for (int b = a + 1; b < Gp; b++) {
                double cc[3], ss[3], att[3];
                lag_integrals(pc, g[a].m - g[b].m, g[a].de - g[b].de, g[a].ue - g[b].ue,
                                               cc, ss);
                double im = cimag(g[a].opl) + cimag(g[b].opl);
                for (int j = 0; j < 3; j++) att[j] = im != 0.0 ? exp(-kc[j] * im) : 1.0;
                for (int c = 0; c < MAX_COMP; c++) {
                    double complex p = v[a][c] * conj(v[b][c]);
                    for (int j = 0; j < 3; j++) out[c][j] += 2.0 * att[j] * (creal(p) * cc[j] - cimag(p) * ss[j]);
                }
            }
        return;
    }
    /* Blocks of equal order. */
    int start[EXP_MAX_ORDER + 2], nb = 0, maxde = 0, maxue = 0;
    lag_box box[EXP_MAX_ORDER + 1];
    for (int a = 0; a < Gp; a++) {
        const int x[3] = {g[a].m, g[a].de, g[a].ue};
        if (a == 0 || g[a].m != g[a - 1].m) {
            start[nb] = a;
            for (int i = 0; i < 3; i++) box[nb].lo[i] = box[nb].hi[i] = x[i];
            nb++;
        }
        for (int i = 0; i < 3; i++) {
            lag_box *bx = &box[nb - 1];
            bx->lo[i] = x[i] < bx->lo[i] ? x[i] : bx->lo[i];
            bx->hi[i] = x[i] > bx->hi[i] ? x[i] : bx->hi[i];
        }
        maxde = g[a].de > maxde ? g[a].de : maxde;
        maxue = g[a].ue > maxue ? g[a].ue : maxue;
    }
    start[nb] = Gp;
    pair_accumulator acc;
    const int wu = 2 * maxue + 1, nlag0 = (2 * maxde + 1) * wu, center = maxde * wu + maxue;
    memset(acc.lag0, 0, (size_t)nlag0 * sizeof acc.lag0[0]);
    acc.n = 0;
    int hash_touched = 0;
    for (int p = 0; p < nb; p++) {
        /* Same order: dense lag table. */
        for (int a = start[p]; a < start[p + 1]; a++)
            for (int b = a + 1; b < start[p + 1]; b++) {
                double complex *t = acc.lag0[center + (g[a].de - g[b].de) * wu + (g[a].ue - g[b].ue)];
                for (int c = 0; c < MAX_COMP; c++) t[c] += v[a][c] * conj(v[b][c]);
            }
        for (int q = p + 1; q < nb; q++) {
            if (block_pair_vanishes(pc, &box[p], &box[q])) continue;
            if (!hash_touched) {
                memset(acc.used, 0, sizeof acc.used);
                hash_touched = 1;
            }
            for (int a = start[p]; a < start[p + 1]; a++)
                for (int b = start[q]; b < start[q + 1]; b++) {
                    int dm = g[a].m - g[b].m, dde = g[a].de - g[b].de, due = g[a].ue - g[b].ue;
                    int h = cache_slot(pc, dm, dde, due);
                    if (h < 0) {
                        double cc[3], ss[3];
                        double complex z[MAX_COMP];
                        lag_integrals(pc, dm, dde, due, cc, ss);
                        for (int c = 0; c < MAX_COMP; c++) z[c] = v[a][c] * conj(v[b][c]);
                        add_pair_integral(out, z, cc, ss);
                        continue;
                    }
                    if (!acc.used[h]) {
                        acc.used[h] = 1;
                        acc.list[acc.n++] = (short)h;
                        for (int c = 0; c < MAX_COMP; c++) acc.hash[h][c] = 0.0;
                    }
                    for (int c = 0; c < MAX_COMP; c++) acc.hash[h][c] += v[a][c] * conj(v[b][c]);
                }
        }
    }
    /* Same-order lags l and -l share one band integral: S(e^{-ikD}) = conj S(e^{ikD}), so
     * 2 Re(z S(-D)) = 2 Re(conj(z) S(D)). */
    for (int i = center + 1; i < nlag0; i++) {
        const double complex *t = acc.lag0[i], *u = acc.lag0[2 * center - i];
        double complex z[MAX_COMP];
        int any = 0;
        for (int c = 0; c < MAX_COMP; c++) {
            z[c] = t[c] + conj(u[c]);
            any |= z[c] != 0.0;
        }
        if (!any) continue;
        int dde = (i / wu) - maxde, due = (i % wu) - maxue;
        double cc[3], ss[3];
        lag0_integrals(pc, dde, due, cc, ss);
        add_pair_integral(out, z, cc, ss);
    }
    for (int t = 0; t < acc.n; t++) add_pair_integral(out, acc.hash[acc.list[t]], pc->c[acc.list[t]], pc->s[acc.list[t]]);
}

void biref_expansion_opts_default(biref_expansion_opts *o)
{
    o->order = -1;
    o->tolerance = 1e-3;
    o->max_order = EXP_MAX_ORDER;
}

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
static void build_groups(const biref_slab_state *st, int nT, path_group *gT, int *GT, int nR, path_group *gR, int *GR)
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

static inline double abs2(double complex z) { return creal(z) * creal(z) + cimag(z) * cimag(z); }

typedef struct {
    const double complex (*C)[2];
    const double complex (*P)[2];
} quad_form;

/* Incoherent energies of the paths, per form and band, as a geometric series over round trips:
 * v_n = first Dbar^n is the energy arriving in each mode at order lowest + n, and
 * v_n y with y = (I - Dbar)^{-1} out_q the energy that leaves from there on. */
typedef struct {
    double Dbar[3][2][2];
    double first[EXP_MAX_FORMS][3][2]; /* energy arriving in each mode at the lowest order */
    double y[EXP_MAX_FORMS][3][2];
    int bands;  /* 3 with evanescent legs (their decay depends on the band), else 1: all bands equal */
    int lowest; /* lowest order: 0 in transmission, 1 in reflection (order 0 is the direct reflection) */
} tail_model;

static void inv_one_minus(const double M[2][2], double out[2][2])
{
    double a = 1.0 - M[0][0], b = -M[0][1], c = -M[1][0], d = 1.0 - M[1][1], det = a * d - b * c;
    out[0][0] = d / det, out[0][1] = -b / det, out[1][0] = -c / det, out[1][1] = a / det;
}

static void tail_setup(const biref_spectral *sp, const biref_slab_state *st, int which, const quad_form *forms,
                       int nf, tail_model *tm)
{
    const double complex(*t01)[2] = st->top.t_down, (*r10)[2] = st->top.r_up, (*t10)[2] = st->top.t_up;
    const double complex(*r12)[2] = st->bottom.r_down, (*t12)[2] = st->bottom.t_down;
    const double complex(*exit)[2] = which == BIREF_REFLECTION ? t10 : t12;
    double ed[2][3], eu[2][3], in_q[EXP_MAX_FORMS][2], out_q[EXP_MAX_FORMS][2];
    tm->bands = st->total_reflection ? 3 : 1;
    tm->lowest = which == BIREF_TRANSMISSION ? 0 : 1;
    for (int m = 0; m < 2; m++)
        for (int j = 0; j < 3; j++) {
            double imd = cimag(st->opl_down[m]), imu = cimag(st->opl_up[m]);
            ed[m][j] = imd != 0.0 ? exp(-2.0 * sp->k_centroid[j] * imd) : 1.0;
            eu[m][j] = imu != 0.0 ? exp(-2.0 * sp->k_centroid[j] * imu) : 1.0;
        }
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
                o2 += abs2(v);
            }
            out_q[k][x] = o2;
        }
    }
    for (int j = 0; j < tm->bands; j++) {
        for (int a = 0; a < 2; a++)
            for (int c = 0; c < 2; c++) {
                double e = 0.0;
                for (int b = 0; b < 2; b++)
                    e += which == BIREF_TRANSMISSION ? abs2(r12[a][b]) * eu[b][j] * abs2(r10[b][c]) * ed[c][j]
                                                     : abs2(r10[a][b]) * ed[b][j] * abs2(r12[b][c]) * eu[c][j];
                tm->Dbar[j][a][c] = e;
            }
        double inv[2][2];
        inv_one_minus(tm->Dbar[j], inv);
        for (int k = 0; k < nf; k++)
            for (int a = 0; a < 2; a++) {
                if (which == BIREF_TRANSMISSION)
                    tm->first[k][j][a] = in_q[k][a] * ed[a][j];
                else
                    tm->first[k][j][a] = (in_q[k][0] * ed[0][j] * abs2(r12[0][a]) + in_q[k][1] * ed[1][j] * abs2(r12[1][a])) * eu[a][j];
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
static void tail_energy(const tail_model *tm, int k, int order, double out[3])
{
    for (int j = 0; j < tm->bands; j++) {
        double v[2] = {tm->first[k][j][0], tm->first[k][j][1]};
        for (int s = tm->lowest; s <= order; s++) tail_step(tm->Dbar[j], v);
        out[j] = v[0] * tm->y[k][j][0] + v[1] * tm->y[k][j][1];
    }
    if (tm->bands == 1) out[1] = out[2] = out[0];
}

/* max over bands of |S(e^{ikD}, Λ_j)|: how much of a coherent superposition at path difference D
 * survives the band integration. */
static double band_coherence(phase_cache *pc, int dm, int dde, int due)
{
    double c[3], s[3], m = 0.0;
    if (dm == 0)
        lag0_integrals(pc, dde, due, c, s);
    else
        lag_integrals(pc, dm, dde, due, c, s);
    for (int j = 0; j < 3; j++) m = dmax2(m, c[j] * c[j] + s[j] * s[j]);
    return sqrt(m);
}

/* The two orders of the expansion: every pair of groups up to order `pairs` interferes; the
 * groups of orders pairs+1 .. `groups` add their own intensity |M_g|^2 (exact at lag 0: the
 * paths inside a group share one optical path and are fully coherent with each other); paths
 * beyond `groups` add their energy incoherently (closed form). */
typedef struct {
    int pairs, groups;
} expansion_orders;

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
static expansion_orders choose_orders(phase_cache *pc, const biref_slab_state *st, const tail_model *tm, int nf,
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
    return r;
}

/* Group vectors of one form: the coherency matrix C = sum_r l_r l_r^H (Cholesky) and the
 * analyzer's Q = P P^H = sum_s w_s w_s^H, so that
 *     c_gh = sum_ij C_ij (M_g Q M_h^H)_ij = sum_{r,s} (l_r^T M_g w_s) conj(l_r^T M_h w_s),
 * an inner product of vectors with rank(C) rank(Q) <= 4 components. */
/* A (Hermitian, positive semi-definite) = sum_r l_r l_r^H; returns the number of vectors. */
static int cholesky2(const double complex A[2][2], double complex l[2][2])
{
    double a = creal(A[0][0]), d = creal(A[1][1]);
    int n = 0;
    if (a > 0.0) {
        double sa = sqrt(a);
        l[n][0] = sa;
        l[n][1] = conj(A[0][1]) / sa;
        n++;
        d -= (creal(A[0][1]) * creal(A[0][1]) + cimag(A[0][1]) * cimag(A[0][1])) / a;
    }
    if (d > 0.0) {
        l[n][0] = 0.0;
        l[n][1] = sqrt(d);
        n++;
    }
    return n;
}

static void form_vectors(const path_group *g, int G, const quad_form *f, double complex (*v)[MAX_COMP])
{
    double complex l[2][2], w[2][2], Q[2][2];
    int nl = cholesky2(f->C, l), nw;
    if (f->P) {
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) Q[i][j] = f->P[i][0] * conj(f->P[j][0]) + f->P[i][1] * conj(f->P[j][1]);
        nw = cholesky2(Q, w);
    } else {
        w[0][0] = 1.0, w[0][1] = 0.0, w[1][0] = 0.0, w[1][1] = 1.0;
        nw = 2;
    }
    for (int a = 0; a < G; a++) {
        int c = 0;
        for (int r = 0; r < nl; r++) {
            double complex row0 = l[r][0] * g[a].M[0][0] + l[r][1] * g[a].M[1][0];
            double complex row1 = l[r][0] * g[a].M[0][1] + l[r][1] * g[a].M[1][1];
            for (int s = 0; s < nw; s++) v[a][c++] = row0 * w[s][0] + row1 * w[s][1];
        }
        while (c < MAX_COMP) v[a][c++] = 0.0;
    }
}

/* Degenerate legs merged (see merge_degenerate). */
static int merged(const biref_slab_state *st, path_group *g, int G) { return legs_degenerate(st) ? merge_degenerate(g, G) : G; }

/* Number of leading groups of order <= n (groups are sorted by order). */
static int groups_below(const path_group *g, int G, int n)
{
    int a = 0;
    while (a < G && g[a].m <= n) a++;
    return a;
}

/* The pair sums of one direction's groups and its tail, for the four pure pairs (input i fully
 * polarized, analyzer passing output o): one component per form, v_g = M_g[i][o]. */
static void pure_pair_intensities(phase_cache *pc, const biref_slab_state *st, const tail_model *tm,
                                  expansion_orders ord, path_group *g, int G, double out[4][3])
{
    G = merged(st, g, G);
    int Gp = groups_below(g, G, ord.pairs);
    double complex v[EXP_MAX_GROUPS][MAX_COMP];
    for (int a = 0; a < G; a++)
        for (int k = 0; k < 4; k++) v[a][k] = g[a].M[k >> 1][k & 1];
    pair_sums(pc, g, G, Gp, (const double complex(*)[MAX_COMP])v, st->total_reflection, out);
    for (int k = 0; k < 4; k++) {
        double tail[3];
        tail_energy(tm, k, ord.groups, tail);
        for (int j = 0; j < 3; j++) out[k][j] += tail[j];
    }
}

/* The detected intensity of one general form (any coherency matrix and analyzer). */
static int expansion_core(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp, int which,
                          const quad_form *form, const biref_expansion_opts *opts, double out[3])
{
    tail_model tm;
    tail_setup(sp, st, which, form, 1, &tm);
    phase_cache pc;
    cache_init(&pc, sp, st, fp);
    expansion_orders ord = choose_orders(&pc, st, &tm, 1, opts);
    path_group g[EXP_MAX_GROUPS];
    int G;
    if (which == BIREF_TRANSMISSION)
        build_groups(st, ord.groups, g, &G, -1, NULL, NULL);
    else
        build_groups(st, -1, NULL, NULL, ord.groups, g, &G);
    G = merged(st, g, G);
    int Gp = groups_below(g, G, ord.pairs);
    double complex v[EXP_MAX_GROUPS][MAX_COMP];
    form_vectors(g, G, form, v);
    double comp[MAX_COMP][3];
    pair_sums(&pc, g, G, Gp, (const double complex(*)[MAX_COMP])v, st->total_reflection, comp);
    tail_energy(&tm, 0, ord.groups, out);
    for (int c = 0; c < MAX_COMP; c++)
        for (int j = 0; j < 3; j++) out[j] += comp[c][j];
    return ord.pairs;
}

void biref_expansion_tail(const biref_spectral *sp, const biref_slab_state *st, int which, const double complex C[2][2],
                          const double complex P[2][2], int order, double out[3])
{
    quad_form f = {C, P};
    tail_model tm;
    tail_setup(sp, st, which, &f, 1, &tm);
    tail_energy(&tm, 0, order, out);
}

/* The series functions with the phase integrals averaged over the footprint fp (NULL: points). */
static biref_status series_polarized(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                                     int which, const double complex C[2][2], const double complex P[2][2],
                                     const biref_expansion_opts *opts, double xyz[3], int *order_used)
{
    if (!sp || !st || !C || !xyz || (which != BIREF_TRANSMISSION && which != BIREF_REFLECTION)) return BIREF_ERR_INVALID;
    biref_expansion_opts def;
    if (!opts) {
        biref_expansion_opts_default(&def);
        opts = &def;
    }
    if (!(opts->tolerance > 0.0) && opts->order < 0) return BIREF_ERR_INVALID;
    quad_form f = {C, P};
    int order = expansion_core(sp, st, fp, which, &f, opts, xyz);
    if (order_used) *order_used = order;
    return BIREF_OK;
}

biref_status biref_expansion_series_polarized(const biref_spectral *sp, const biref_slab_state *st, int which,
                                              const double complex C[2][2], const double complex P[2][2],
                                              const biref_expansion_opts *opts, double xyz[3], int *order_used)
{
    return series_polarized(sp, st, NULL, which, C, P, opts, xyz, order_used);
}

static biref_status series(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                           const biref_expansion_opts *opts, biref_spectrum *out)
{
    if (!sp || !st || !out) return BIREF_ERR_INVALID;
    biref_expansion_opts def;
    if (!opts) {
        biref_expansion_opts_default(&def);
        opts = &def;
    }
    if (!(opts->tolerance > 0.0) && opts->order < 0) return BIREF_ERR_INVALID;
    /* Forms: input i fully polarized (C = e_i e_i^H), analyzer passing output o only. */
    static const double complex Cin[2][2][2] = {{{1, 0}, {0, 0}}, {{0, 0}, {0, 1}}};
    static const double complex Pout[2][2][2] = {{{1, 0}, {0, 0}}, {{0, 0}, {0, 1}}};
    quad_form f[4];
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++) f[2 * i + o] = (quad_form){Cin[i], Pout[o]};
    /* Transmission and reflection share the path differences, hence the band integrals, and
     * the amplitude recursion. */
    phase_cache pc;
    cache_init(&pc, sp, st, fp);
    tail_model tm[2];
    expansion_orders ord[2];
    for (int which = 0; which < 2; which++) {
        tail_setup(sp, st, which, f, 4, &tm[which]);
        ord[which] = choose_orders(&pc, st, &tm[which], 4, opts);
    }
    path_group gT[EXP_MAX_GROUPS], gR[EXP_MAX_GROUPS];
    int G[2];
    build_groups(st, ord[0].groups, gT, &G[0], ord[1].groups, gR, &G[1]);
    for (int which = 0; which < 2; which++) {
        double res[4][3];
        pure_pair_intensities(&pc, st, &tm[which], ord[which], which ? gR : gT, G[which], res);
        double(*X)[2][3] = which == BIREF_REFLECTION ? out->R : out->T;
        for (int i = 0; i < 2; i++)
            for (int o = 0; o < 2; o++) memcpy(X[i][o], res[2 * i + o], sizeof res[0]);
    }
    return BIREF_OK;
}

biref_status biref_expansion_series(const biref_spectral *sp, const biref_slab_state *st,
                                    const biref_expansion_opts *opts, biref_spectrum *out)
{
    return series(sp, st, NULL, opts, out);
}

static biref_status expansion_pairs(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                                    const biref_expansion_opts *opts, biref_spectrum *out);

static int is_diagonal(const double complex M[2][2]) { return M[0][1] == 0.0 && M[1][0] == 0.0; }

/* Thin slabs and evanescent legs that couple the faces: the path series converges too slowly
 * (or, with amplifying evanescent reflections, not at all) and its incoherent tail is wrong;
 * the exact integral of eq. 17 instead (src/spectral/coherent.c). *order_used is 0 then.
 * Elsewhere the truncated series can leave [0, 1] slightly where internal reflections are strong
 * (up to ~1e-2 at grazing incidence and high indices): for the paper's light model (C and P
 * diagonal) the result is that of biref_spectrum_expansion, kept physical with both directions
 * (biref_physical_limit); for other polarizers it is kept >= 0 by moving it towards the
 * incoherent energy of the paths. */
static biref_status expansion_polarized(const biref_spectral *sp, const biref_slab_state *st,
                                       const biref_opl_footprint *fp, int which, const double complex C[2][2],
                                       const double complex P[2][2], const biref_expansion_opts *opts, double xyz[3],
                                       int *order_used)
{
    if (!sp || !st || !C || !xyz || (which != BIREF_TRANSMISSION && which != BIREF_REFLECTION)) return BIREF_ERR_INVALID;
    const biref_numeric_plan *coherent = biref_coherent_plan(sp, st);
    if (coherent) {
        if (opts && !(opts->tolerance > 0.0) && opts->order < 0) return BIREF_ERR_INVALID;
        biref_spectrum_numeric_polarized(coherent, st, which, C, P, xyz);
        if (order_used) *order_used = 0;
        return BIREF_OK;
    }
    if (is_diagonal(C) && (!P || is_diagonal(P))) {
        biref_spectrum x;
        biref_status s = expansion_pairs(sp, st, fp, opts, &x);
        if (s != BIREF_OK) return s;
        if (order_used) s = series_polarized(sp, st, fp, which, C, P, opts, xyz, order_used);
        if (s != BIREF_OK) return s;
        const double(*X)[2][3] = which == BIREF_REFLECTION ? x.R : x.T;
        for (int j = 0; j < 3; j++) {
            xyz[j] = 0.0;
            for (int i = 0; i < 2; i++)
                for (int o = 0; o < 2; o++) xyz[j] += creal(C[i][i]) * (P ? cabs(P[o][o]) * cabs(P[o][o]) : 1.0) * X[i][o][j];
        }
        return BIREF_OK;
    }
    biref_status s = series_polarized(sp, st, fp, which, C, P, opts, xyz, order_used);
    if (s != BIREF_OK) return s;
    if (xyz[0] < 0.0 || xyz[1] < 0.0 || xyz[2] < 0.0) {
        quad_form f = {C, P};
        tail_model tm;
        tail_setup(sp, st, which, &f, 1, &tm);
        double e[3];
        tail_energy(&tm, 0, tm.lowest - 1, e); /* every order */
        if (which == BIREF_REFLECTION) {
            /* plus the direct reflection, order 0 */
            const double complex(*r01)[2] = st->top.r_down;
            for (int o = 0; o < 2; o++) {
                double complex v[2];
                for (int i = 0; i < 2; i++) v[i] = P ? r01[i][0] * P[0][o] + r01[i][1] * P[1][o] : r01[i][o];
                double d = 0.0;
                for (int i = 0; i < 2; i++)
                    for (int jj = 0; jj < 2; jj++) d += creal(C[i][jj] * v[i] * conj(v[jj]));
                for (int j = 0; j < 3; j++) e[j] += d;
            }
        }
        double t = 1.0;
        for (int j = 0; j < 3; j++)
            if (xyz[j] < 0.0) t = fmin(t, e[j] > 0.0 ? e[j] / (e[j] - xyz[j]) : 0.0);
        for (int j = 0; j < 3; j++) xyz[j] = e[j] + t * (xyz[j] - e[j]);
    }
    return BIREF_OK;
}

static biref_status expansion_pairs(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                                    const biref_expansion_opts *opts, biref_spectrum *out)
{
    if (!sp || !st || !out) return BIREF_ERR_INVALID;
    const biref_numeric_plan *coherent = biref_coherent_plan(sp, st);
    if (!coherent) {
        biref_status s = series(sp, st, fp, opts, out);
        if (s != BIREF_OK) return s;
        /* The truncated series and its incoherent tail can leave [0, 1] by up to ~1e-2 where
         * internal reflections are strong (grazing incidence, high indices). */
        double E[2][2][2][3], H[2][2][3], X[2][2][2][3];
        for (int which = 0; which < 2; which++) biref_analytic_paper_terms(sp, st, which, E[which], H);
        memcpy(X[0], out->T, sizeof out->T);
        memcpy(X[1], out->R, sizeof out->R);
        biref_physical_limit((const double(*)[2][2][3])E, X);
        memcpy(out->T, X[0], sizeof out->T);
        memcpy(out->R, X[1], sizeof out->R);
        return BIREF_OK;
    }
    if (opts && !(opts->tolerance > 0.0) && opts->order < 0) return BIREF_ERR_INVALID;
    biref_spectrum_numeric(coherent, st, out);
    return BIREF_OK;
}

/* A result that is not finite is an error (BIREF_ERR_ILLCOND), never an output. */
static int finite3(const double v[3]) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

biref_status biref_spectrum_expansion_polarized(const biref_spectral *sp, const biref_slab_state *st, int which,
                                                const double complex C[2][2], const double complex P[2][2],
                                                const biref_expansion_opts *opts, double xyz[3], int *order_used)
{
    return biref_expansion_polarized_footprint(sp, st, NULL, which, C, P, opts, xyz, order_used);
}

biref_status biref_expansion_polarized_footprint(const biref_spectral *sp, const biref_slab_state *st,
                                                 const biref_opl_footprint *fp, int which, const double complex C[2][2],
                                                 const double complex P[2][2], const biref_expansion_opts *opts,
                                                 double xyz[3], int *order_used)
{
    biref_status s = expansion_polarized(sp, st, fp, which, C, P, opts, xyz, order_used);
    return s == BIREF_OK && !finite3(xyz) ? BIREF_ERR_ILLCOND : s;
}

biref_status biref_spectrum_expansion(const biref_spectral *sp, const biref_slab_state *st,
                                      const biref_expansion_opts *opts, biref_spectrum *out)
{
    biref_status s = expansion_pairs(sp, st, NULL, opts, out);
    if (s != BIREF_OK) return s;
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++)
            if (!finite3(out->T[i][o]) || !finite3(out->R[i][o])) return BIREF_ERR_ILLCOND;
    return BIREF_OK;
}
