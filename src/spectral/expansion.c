/* Exact spectral integration of the path-group expansion, for any polarizer and analyzer
 * (beyond the paper; issue #5).
 *
 * Ignoring dispersion within a band, J(k) = sum_g M_g e^{ik Phi_g}: a group g collects the
 * paths with the same numbers of o/e legs down and up, hence the same optical path Phi_g. For an
 * incident coherency matrix C and an analyzer P the detected intensity is
 *     I(k) = sum_{g,h} c_gh e^{ik(Phi_g - conj Phi_h)},   c_gh = sum C_ij (M_g P)_io conj((M_h P)_jo),
 * so its band integral is exact given S(cos kD) and S(sin kD) at the pairwise differences. The
 * paper's eq. 26 keeps only some pairs (order 0 and "descendants"); here every pair up to the
 * cut-off order interferes. Orders beyond it add their energy incoherently, summed in closed form
 * (the geometric series of eq. 20-21 started at order n + 1); the adaptive order is the smallest
 * whose tail is below a tolerance of the total. */
#include <complex.h>
#include <math.h>
#include <string.h>

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
 * difference depends only on the difference of the integer coordinates: the look-up table is
 * queried once per distinct difference (a small hash on the stack), not once per pair. */
static inline int phase_key(int m, int de, int ue) { return (m + 32) * 4096 + (de + 32) * 64 + (ue + 32); }

enum { CACHE_SLOTS = 1024, CACHE_MAX_FILL = 768 };

typedef struct {
    int key[CACHE_SLOTS];
    int fill;
    double c[CACHE_SLOTS][3], s[CACHE_SLOTS][3];
    double spill_c[3], spill_s[3]; /* uncached result once the table is 3/4 full (high orders) */
    const biref_spectral *sp;
    double A, B, C; /* real parts, nm */
} phase_cache;

static void cache_init(phase_cache *pc, const biref_spectral *sp, const biref_slab_state *st)
{
    pc->sp = sp;
    pc->A = creal(st->opl_down[0] + st->opl_up[0]);
    pc->B = creal(st->opl_down[1] - st->opl_down[0]);
    pc->C = creal(st->opl_up[1] - st->opl_up[0]);
    for (int i = 0; i < CACHE_SLOTS; i++) pc->key[i] = -1;
    pc->fill = 0;
}

/* Slot of the path difference with integer coordinates (dm, dde, due), its S(cos), S(sin)
 * computed on first use; -1 once the table is 3/4 full (keeps probes short at high orders). */
static int cache_slot(phase_cache *pc, int dm, int dde, int due)
{
    int key = phase_key(dm, dde, due);
    unsigned h = ((unsigned)key * 2654435761u) >> 22; /* 10 bits */
    for (;;) {
        if (pc->key[h] == key) return (int)h;
        if (pc->key[h] < 0) {
            if (pc->fill >= CACHE_MAX_FILL) return -1;
            pc->key[h] = key;
            pc->fill++;
            biref_spectral_phase_integrals(pc->sp, dm * pc->A + dde * pc->B + due * pc->C, pc->c[h], pc->s[h]);
            return (int)h;
        }
        h = (h + 1) & (CACHE_SLOTS - 1u);
    }
}

/* S(cos), S(sin) at the real path difference with integer coordinates (dm, dde, due). */
static void cache_get(phase_cache *pc, int dm, int dde, int due, const double **c, const double **s)
{
    int h = cache_slot(pc, dm, dde, due);
    if (h < 0) {
        biref_spectral_phase_integrals(pc->sp, dm * pc->A + dde * pc->B + due * pc->C, pc->spill_c, pc->spill_s);
        *c = pc->spill_c;
        *s = pc->spill_s;
        return;
    }
    *c = pc->c[h];
    *s = pc->s[h];
}

/* Without evanescent legs a pair's contribution is 2 Re(c_ab S(e^{ik D_ab})) and depends on the
 * pair only through c_ab and the slot of D_ab: c_ab is summed per slot first (one complex
 * multiply-add per pair and form), and the band integrals applied once per distinct difference
 * — the autocorrelation of the group amplitudes over the integer path-difference lattice. */
typedef struct {
    double complex acc[CACHE_SLOTS][EXP_MAX_FORMS];
    unsigned char used[CACHE_SLOTS];
    short list[CACHE_SLOTS];
    int n;
} slot_sums;

static inline double complex *slot_acc(slot_sums *ss, int h, int nf)
{
    if (!ss->used[h]) {
        ss->used[h] = 1;
        ss->list[ss->n++] = (short)h;
        for (int k = 0; k < nf; k++) ss->acc[h][k] = 0.0;
    }
    return ss->acc[h];
}

static void slot_sums_apply(const slot_sums *ss, const phase_cache *pc, int nf, double out[][3])
{
    for (int t = 0; t < ss->n; t++) {
        int h = ss->list[t];
        for (int k = 0; k < nf; k++) {
            double re = 2.0 * creal(ss->acc[h][k]), im = 2.0 * cimag(ss->acc[h][k]);
            for (int j = 0; j < 3; j++) out[k][j] += re * pc->c[h][j] - im * pc->s[h][j];
        }
    }
}

void biref_expansion_opts_default(biref_expansion_opts *o)
{
    o->order = -1;
    o->tolerance = 1e-3;
    o->max_order = EXP_MAX_ORDER;
}

biref_status biref_stokes_to_coherency(const double S[4], double complex C[2][2])
{
    for (int i = 0; i < 4; i++)
        if (!isfinite(S[i])) return BIREF_ERR_INVALID;
    if (S[0] < 0.0 || S[1] * S[1] + S[2] * S[2] + S[3] * S[3] > S[0] * S[0] * (1.0 + 1e-12)) return BIREF_ERR_INVALID;
    C[0][0] = 0.5 * (S[0] + S[1]);
    C[1][1] = 0.5 * (S[0] - S[1]);
    C[0][1] = 0.5 * (S[2] - I * S[3]);
    C[1][0] = 0.5 * (S[2] + I * S[3]);
    return BIREF_OK;
}

static void projector(const double complex u[2], double complex P[2][2])
{
    for (int k = 0; k < 2; k++)
        for (int o = 0; o < 2; o++) P[k][o] = conj(u[k]) * u[o];
}

void biref_analyzer_linear(double psi, double complex P[2][2])
{
    double complex u[2] = {cos(psi), sin(psi)};
    projector(u, P);
}

void biref_analyzer_circular(int handedness, double complex P[2][2])
{
    double complex u[2] = {M_SQRT1_2, (handedness >= 0 ? I : -I) * M_SQRT1_2};
    projector(u, P);
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
 * mode), value = row vector over the two inputs. Returns the number of groups. */
static int build_groups(const biref_slab_state *st, int which, int order, path_group *g)
{
    const double complex(*t01)[2] = st->top.t_down, (*r10)[2] = st->top.r_up, (*t10)[2] = st->top.t_up;
    const double complex(*r12)[2] = st->bottom.r_down, (*t12)[2] = st->bottom.t_down;
    const double complex *od = st->opl_down, *ou = st->opl_up;
    /* amp[de][ue][mode][input]; only the reachable corner [0..order+1][0..order+1] is used and
     * zeroed (the full arrays are 13 KB; per-sample cost matters at order 1). */
    double complex cur[EXP_MAX_ORDER + 2][EXP_MAX_ORDER + 2][2][2], nxt[EXP_MAX_ORDER + 2][EXP_MAX_ORDER + 2][2][2];
    const int span = order + 2;
    for (int a = 0; a < span; a++) memset(cur[a], 0, (size_t)span * sizeof cur[a][0]);
    int n = 0;
    const double complex(*exit)[2] = which == BIREF_REFLECTION ? t10 : t12;
    int m0;
    if (which == BIREF_TRANSMISSION) {
        for (int x = 0; x < 2; x++)
            for (int i = 0; i < 2; i++) cur[x][0][x][i] = t01[i][x];
        m0 = 0;
    } else {
        memcpy(g[n].M, st->top.r_down, sizeof g[n].M);
        g[n].m = g[n].de = g[n].ue = 0;
        g[n++].opl = 0.0;
        for (int x = 0; x < 2; x++)
            for (int y = 0; y < 2; y++)
                for (int i = 0; i < 2; i++) cur[x][y][y][i] += t01[i][x] * r12[x][y];
        m0 = 1;
    }
    for (int m = m0; m <= order; m++) {
        /* Legs so far: transmission m+1 down, m up; reflection m down, m up. */
        int n_down = which == BIREF_TRANSMISSION ? m + 1 : m, n_up = m;
        for (int de = 0; de <= n_down; de++)
            for (int ue = 0; ue <= n_up; ue++) {
                path_group *p = &g[n++];
                for (int i = 0; i < 2; i++)
                    for (int o = 0; o < 2; o++) p->M[i][o] = cur[de][ue][0][i] * exit[0][o] + cur[de][ue][1][i] * exit[1][o];
                p->opl = (n_down - de) * od[0] + de * od[1] + (n_up - ue) * ou[0] + ue * ou[1];
                /* Transmission's extra down leg is common to all groups and cancels in differences. */
                p->m = m;
                p->de = de;
                p->ue = ue;
            }
        if (m == order) break;
        /* One more round trip: transmission reflects at the bottom (x -> y), goes up, reflects at
         * the top (y -> x'), goes down; reflection the other way round. */
        for (int a = 0; a < span; a++) memset(nxt[a], 0, (size_t)span * sizeof nxt[a][0]);
        const double complex(*ra)[2] = which == BIREF_TRANSMISSION ? r12 : r10;
        const double complex(*rb)[2] = which == BIREF_TRANSMISSION ? r10 : r12;
        for (int de = 0; de <= n_down; de++)
            for (int ue = 0; ue <= n_up; ue++)
                for (int a = 0; a < 2; a++) {
                    if (cur[de][ue][a][0] == 0.0 && cur[de][ue][a][1] == 0.0) continue;
                    for (int b = 0; b < 2; b++)
                        for (int c = 0; c < 2; c++) {
                            double complex f = ra[a][b] * rb[b][c];
                            /* transmission: b is the up leg, c the down leg; reflection: b down, c up */
                            int dde = which == BIREF_TRANSMISSION ? c : b, due = which == BIREF_TRANSMISSION ? b : c;
                            for (int i = 0; i < 2; i++) nxt[de + dde][ue + due][c][i] += cur[de][ue][a][i] * f;
                        }
                }
        for (int a = 0; a < span; a++) memcpy(cur[a], nxt[a], (size_t)span * sizeof cur[a][0]);
    }
    return n;
}

static inline double abs2(double complex z) { return creal(z) * creal(z) + cimag(z) * cimag(z); }

typedef struct {
    const double complex (*C)[2];
    const double complex (*P)[2];
} quad_form;

/* Incoherent energies of the paths of order > order for each form and band. Returns, per form,
 * the tail and the total (all orders, incoherent) so the adaptive rule can compare them. */
typedef struct {
    double in_q[EXP_MAX_FORMS][2], out_q[EXP_MAX_FORMS][2];
    double Dbar[3][2][2];
    double inv[3][2][2]; /* (I - Dbar)^{-1} */
    double first[EXP_MAX_FORMS][3][2]; /* energy arriving in each mode after the lowest order */
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
    double ed[2][3], eu[2][3];
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
            tm->in_q[k][x] = q;
            double o2 = 0.0;
            for (int o = 0; o < 2; o++) {
                double complex v = P ? exit[x][0] * P[0][o] + exit[x][1] * P[1][o] : exit[x][o];
                o2 += abs2(v);
            }
            tm->out_q[k][x] = o2;
        }
    }
    for (int j = 0; j < 3; j++) {
        for (int a = 0; a < 2; a++)
            for (int c = 0; c < 2; c++) {
                double e = 0.0;
                for (int b = 0; b < 2; b++)
                    e += which == BIREF_TRANSMISSION ? abs2(r12[a][b]) * eu[b][j] * abs2(r10[b][c]) * ed[c][j]
                                                     : abs2(r10[a][b]) * ed[b][j] * abs2(r12[b][c]) * eu[c][j];
                tm->Dbar[j][a][c] = e;
            }
        inv_one_minus(tm->Dbar[j], tm->inv[j]);
        for (int k = 0; k < nf; k++)
            for (int a = 0; a < 2; a++) {
                if (which == BIREF_TRANSMISSION)
                    tm->first[k][j][a] = tm->in_q[k][a] * ed[a][j];
                else
                    tm->first[k][j][a] = (tm->in_q[k][0] * ed[0][j] * abs2(r12[0][a]) + tm->in_q[k][1] * ed[1][j] * abs2(r12[1][a])) * eu[a][j];
            }
    }
}

/* Energy of orders >= lowest + skip (incoherent), per form and band. */
static void tail_energy(const tail_model *tm, int k, int skip, double out[3])
{
    for (int j = 0; j < 3; j++) {
        double v[2] = {tm->first[k][j][0], tm->first[k][j][1]};
        for (int s = 0; s < skip; s++) {
            double w0 = v[0] * tm->Dbar[j][0][0] + v[1] * tm->Dbar[j][1][0];
            double w1 = v[0] * tm->Dbar[j][0][1] + v[1] * tm->Dbar[j][1][1];
            v[0] = w0, v[1] = w1;
        }
        double u0 = v[0] * tm->inv[j][0][0] + v[1] * tm->inv[j][1][0];
        double u1 = v[0] * tm->inv[j][0][1] + v[1] * tm->inv[j][1][1];
        out[j] = u0 * tm->out_q[k][0] + u1 * tm->out_q[k][1];
    }
}

/* max over bands of |S(e^{ikD}, Λ_j)|: how much of a coherent superposition at path difference D
 * survives the band integration. */
static double band_coherence(phase_cache *pc, int dm, int dde, int due)
{
    const double *c, *s;
    cache_get(pc, dm, dde, due, &c, &s);
    double m = 0.0;
    for (int j = 0; j < 3; j++) m = fmax(m, sqrt(c[j] * c[j] + s[j] * s[j]));
    return m;
}

/* Smallest order whose truncation error is below tol (relative to the total energy). The energy
 * of the dropped orders is kept (incoherently), so what is lost is only interference: (a) among
 * the dropped paths, at most E_tail times the band coherence at the birefringent path differences
 * within an order, and (b) between dropped and kept paths, at most 2 sqrt(E_tail E_total) times
 * the coherence at the shortest round trip. For mm-thick slabs both coherences are ~1e-5 away
 * from the optic axis, so order 1 suffices; thin or near-axis slabs get more orders. */
static int choose_order(phase_cache *pc, const biref_slab_state *st, const tail_model *tm, int which, int nf,
                        const biref_expansion_opts *o)
{
    int lowest = which == BIREF_TRANSMISSION ? 0 : 1;
    if (o->order >= 0) return o->order < lowest ? lowest : (o->order > EXP_MAX_ORDER ? EXP_MAX_ORDER : o->order);
    int cap = o->max_order < 1 ? 1 : (o->max_order > EXP_MAX_ORDER ? EXP_MAX_ORDER : o->max_order);
    const double complex *od = st->opl_down, *ou = st->opl_up;
    double d_rt = INFINITY;
    int rx = 0, ry = 0;
    for (int x = 0; x < 2; x++)
        for (int y = 0; y < 2; y++)
            if (creal(od[x] + ou[y]) < d_rt) d_rt = creal(od[x] + ou[y]), rx = x, ry = y;
    double coh_cross = band_coherence(pc, 1, rx, ry);
    /* Degenerate legs (B = C) make this 1: the tail's merged classes are exactly coherent, and the
     * tail model adds their paths incoherently, so the bound must count them. */
    double coh_intra = fmax(fmax(band_coherence(pc, 0, 1, 0), band_coherence(pc, 0, 0, 1)),
                            fmax(band_coherence(pc, 0, 1, 1), band_coherence(pc, 0, 1, -1)));
    for (int n = 1; n < cap; n++) {
        int ok = 1;
        for (int k = 0; k < nf && ok; k++) {
            double total[3], tail[3];
            tail_energy(tm, k, 0, total);
            tail_energy(tm, k, n + 1 - lowest, tail);
            for (int j = 0; j < 3; j++) {
                double err = tail[j] * coh_intra + 2.0 * sqrt(tail[j] * total[j]) * coh_cross;
                if (err > o->tolerance * total[j] + 1e-300) ok = 0;
            }
        }
        if (ok) return n;
    }
    return cap;
}

/* The phase integral of one group pair: S(cos), S(sin) of Re(D) and the evanescent decay. */
static inline void pair_integrals(phase_cache *pc, const path_group *a, const path_group *b, double c[3],
                                  double s[3], double att[3])
{
    if (a == b) {
        c[0] = c[1] = c[2] = 1.0;
        s[0] = s[1] = s[2] = 0.0;
    } else {
        const double *cc, *ss;
        cache_get(pc, a->m - b->m, a->de - b->de, a->ue - b->ue, &cc, &ss);
        for (int j = 0; j < 3; j++) c[j] = cc[j], s[j] = ss[j];
    }
    double im = cimag(a->opl) + cimag(b->opl); /* Im(Phi_a - conj Phi_b): decay of evanescent legs */
    for (int j = 0; j < 3; j++) att[j] = im != 0.0 ? exp(-pc->sp->k_centroid[j] * im) : 1.0;
}

/* Fast path for the four pure pairs (input i fully polarized, analyzer passing output o):
 * c_gh = M_g[i][o] conj(M_h[i][o]). */
static int expansion_pairs(const biref_spectral *sp, const biref_slab_state *st, int which, const quad_form *forms,
                           const biref_expansion_opts *opts, double out[4][3])
{
    tail_model tm;
    tail_setup(sp, st, which, forms, 4, &tm);
    phase_cache pc;
    cache_init(&pc, sp, st);
    int order = choose_order(&pc, st, &tm, which, 4, opts);
    path_group g[EXP_MAX_GROUPS];
    int G = build_groups(st, which, order, g);
    if (legs_degenerate(st)) G = merge_degenerate(g, G);
    memset(out, 0, 4 * sizeof out[0]);
    /* Diagonal terms: |M_g|^2 with the decay of evanescent legs. */
    for (int a = 0; a < G; a++) {
        double c[3], s[3], att[3];
        pair_integrals(&pc, &g[a], &g[a], c, s, att);
        for (int k = 0; k < 4; k++) {
            double complex v = g[a].M[k >> 1][k & 1];
            double e = creal(v) * creal(v) + cimag(v) * cimag(v);
            for (int j = 0; j < 3; j++) out[k][j] += att[j] * e;
        }
    }
    /* Cross terms 2 Re(M_a conj(M_b) S(e^{ik(Phi_a - Phi_b)})). Without evanescent legs (the
     * common case) there is no decay to apply and the loop is pure multiply-adds. */
    const int evanescent = st->total_reflection;
    slot_sums ss;
    ss.n = 0;
    memset(ss.used, 0, sizeof ss.used);
    for (int a = 0; a < G; a++)
        for (int b = a + 1; b < G; b++) {
            int h = evanescent ? -1 : cache_slot(&pc, g[a].m - g[b].m, g[a].de - g[b].de, g[a].ue - g[b].ue);
            if (h >= 0) {
                double complex *acc = slot_acc(&ss, h, 4);
                for (int k = 0; k < 4; k++) acc[k] += g[a].M[k >> 1][k & 1] * conj(g[b].M[k >> 1][k & 1]);
                continue;
            }
            double c[3], s[3], att[3];
            pair_integrals(&pc, &g[a], &g[b], c, s, att);
            for (int k = 0; k < 4; k++) {
                double complex v = g[a].M[k >> 1][k & 1] * conj(g[b].M[k >> 1][k & 1]);
                for (int j = 0; j < 3; j++) out[k][j] += 2.0 * att[j] * (creal(v) * c[j] - cimag(v) * s[j]);
            }
        }
    slot_sums_apply(&ss, &pc, 4, out);
    int lowest = which == BIREF_TRANSMISSION ? 0 : 1;
    for (int k = 0; k < 4; k++) {
        double tail[3];
        tail_energy(&tm, k, order + 1 - lowest, tail);
        for (int j = 0; j < 3; j++) out[k][j] += tail[j];
    }
    return order;
}

/* Accumulates the detected intensity of nf quadratic forms over all group pairs. */
static int expansion_core(const biref_spectral *sp, const biref_slab_state *st, int which, const quad_form *forms,
                          int nf, const biref_expansion_opts *opts, double out[][3])
{
    tail_model tm;
    tail_setup(sp, st, which, forms, nf, &tm);
    phase_cache pc;
    cache_init(&pc, sp, st);
    int order = choose_order(&pc, st, &tm, which, nf, opts);
    path_group g[EXP_MAX_GROUPS];
    int G = build_groups(st, which, order, g);
    if (legs_degenerate(st)) G = merge_degenerate(g, G);
    /* N[k][g] = M_g P_k, c_gh = sum C_ij N_g[i][o] conj(N_h[j][o]). */
    double complex N[EXP_MAX_FORMS][EXP_MAX_GROUPS][2][2];
    for (int k = 0; k < nf; k++)
        for (int a = 0; a < G; a++)
            for (int i = 0; i < 2; i++)
                for (int o = 0; o < 2; o++)
                    N[k][a][i][o] = forms[k].P ? g[a].M[i][0] * forms[k].P[0][o] + g[a].M[i][1] * forms[k].P[1][o]
                                               : g[a].M[i][o];
    for (int k = 0; k < nf; k++) out[k][0] = out[k][1] = out[k][2] = 0.0;
    const int evanescent = st->total_reflection;
    slot_sums ss;
    ss.n = 0;
    memset(ss.used, 0, sizeof ss.used);
    for (int a = 0; a < G; a++) {
        for (int b = a; b < G; b++) {
            int h = (evanescent || a == b) ? -1 : cache_slot(&pc, g[a].m - g[b].m, g[a].de - g[b].de, g[a].ue - g[b].ue);
            double c[3] = {0, 0, 0}, s[3] = {0, 0, 0}, att[3] = {1, 1, 1};
            if (h < 0) pair_integrals(&pc, &g[a], &g[b], c, s, att);
            double complex *acc = h >= 0 ? slot_acc(&ss, h, nf) : NULL;
            double mult = b == a ? 1.0 : 2.0;
            for (int k = 0; k < nf; k++) {
                double complex cg = 0.0;
                const double complex(*C)[2] = forms[k].C;
                for (int i = 0; i < 2; i++)
                    for (int jj = 0; jj < 2; jj++) {
                        if (C[i][jj] == 0.0) continue;
                        cg += C[i][jj] * (N[k][a][i][0] * conj(N[k][b][jj][0]) + N[k][a][i][1] * conj(N[k][b][jj][1]));
                    }
                if (acc)
                    acc[k] += cg;
                else
                    for (int j = 0; j < 3; j++) out[k][j] += mult * att[j] * (creal(cg) * c[j] - cimag(cg) * s[j]);
            }
        }
    }
    slot_sums_apply(&ss, &pc, nf, out);
    int lowest = which == BIREF_TRANSMISSION ? 0 : 1;
    for (int k = 0; k < nf; k++) {
        double tail[3];
        tail_energy(&tm, k, order + 1 - lowest, tail);
        for (int j = 0; j < 3; j++) out[k][j] += tail[j];
    }
    return order;
}

void biref_expansion_tail(const biref_spectral *sp, const biref_slab_state *st, int which, const double complex C[2][2],
                          const double complex P[2][2], int order, double out[3])
{
    quad_form f = {C, P};
    tail_model tm;
    tail_setup(sp, st, which, &f, 1, &tm);
    int lowest = which == BIREF_TRANSMISSION ? 0 : 1;
    tail_energy(&tm, 0, order + 1 - lowest, out);
}

biref_status biref_spectrum_expansion_polarized(const biref_spectral *sp, const biref_slab_state *st, int which,
                                                const double complex C[2][2], const double complex P[2][2],
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
    double out[1][3];
    int order = expansion_core(sp, st, which, &f, 1, opts, out);
    memcpy(xyz, out[0], sizeof out[0]);
    if (order_used) *order_used = order;
    return BIREF_OK;
}

biref_status biref_spectrum_expansion(const biref_spectral *sp, const biref_slab_state *st,
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
    for (int which = 0; which < 2; which++) {
        double res[4][3];
        expansion_pairs(sp, st, which, f, opts, res);
        double(*X)[2][3] = which == BIREF_REFLECTION ? out->R : out->T;
        for (int i = 0; i < 2; i++)
            for (int o = 0; o < 2; o++) memcpy(X[i][o], res[2 * i + o], sizeof res[0]);
    }
    return BIREF_OK;
}
