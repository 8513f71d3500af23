/* The interference of the path groups (expansion.c): each form's vectors per group and their
 * band-integrated pair sums, one band integral per distinct lag. */
#include "spectral/expansion_internal.h"

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
void biref_xp_pair_sums(phase_cache *pc, const path_group *g, int G, int Gp, const double complex (*v)[MAX_COMP],
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

void biref_xp_form_vectors(const path_group *g, int G, const quad_form *f, double complex (*v)[MAX_COMP])
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

