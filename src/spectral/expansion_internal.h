/* The path-group expansion's parts (expansion.c and the files it is split into): the groups of
 * paths (expansion_groups.c), the band integrals of their lags (this header: a cache shared by the
 * order choice and the pair sums), the pair sums (expansion_pairs.c), the incoherent tail and the
 * choice of orders (expansion_tail.c). */
#ifndef BIREF_EXPANSION_INTERNAL_H
#define BIREF_EXPANSION_INTERNAL_H

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

static inline void cache_init(phase_cache *pc, const biref_spectral *sp, const biref_slab_state *st,
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
static inline void lag_integrals(const phase_cache *pc, int dm, int dde, int due, double c[3], double s[3])
{
    const int n[4] = {dm - dde, dde, dm - due, due};
    biref_phase_integrals_footprint(pc->sp, pc->fp, lag_opd(pc, dm, dde, due), n, c, s);
}

/* S(cos), S(sin) of the same-order lag (dde, due). */
static inline void lag0_integrals(phase_cache *pc, int dde, int due, double c[3], double s[3])
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
static inline int cache_slot(phase_cache *pc, int dm, int dde, int due)
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

static inline double dmin2(double a, double b) { return a < b ? a : b; }
static inline double dmax2(double a, double b) { return a > b ? a : b; }

/* max over bands of |S(e^{ikD}, Λ_j)|: how much of a coherent superposition at path difference D
 * survives the band integration. */
static inline double band_coherence(phase_cache *pc, int dm, int dde, int due)
{
    double c[3], s[3], m = 0.0;
    if (dm == 0)
        lag0_integrals(pc, dde, due, c, s);
    else
        lag_integrals(pc, dm, dde, due, c, s);
    for (int j = 0; j < 3; j++) m = dmax2(m, c[j] * c[j] + s[j] * s[j]);
    return sqrt(m);
}

/* The detected intensity of a form is sum_{a,b} <v_a, v_b> e^{ik(Phi_a - conj Phi_b)}, with one
 * vector v_g of up to MAX_COMP components per group (the coherency matrix and the analyzer
 * factored as sums of outer products, see form_vectors): the pair sums below work per
 * component and never see the polarizers. */
enum { MAX_COMP = 4 };
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

/* The two orders of the expansion: every pair of groups up to order `pairs` interferes; the
 * groups of orders pairs+1 .. `groups` add their own intensity |M_g|^2 (exact at lag 0: the
 * paths inside a group share one optical path and are fully coherent with each other); paths
 * beyond `groups` add their energy incoherently (closed form). */
typedef struct {
    int pairs, groups;
} expansion_orders;

/* Transmission groups of orders 0..nT into gT (nT < 0: none) and reflection groups of orders
 * 0..nR into gR (nR < 0: none), sorted by order; returns their numbers in *GT, *GR
 * (expansion_groups.c). */
void biref_xp_build_groups(const biref_slab_state *st, int nT, path_group *gT, int *GT, int nR, path_group *gR, int *GR);
/* Groups of exactly equal optical path merged when the extraordinary legs are degenerate; returns
 * the new count. */
int biref_xp_merged(const biref_slab_state *st, path_group *g, int G);
/* Number of leading groups of order <= n (groups are sorted by order). */
int biref_xp_groups_below(const path_group *g, int G, int n);

/* The vectors of one form per group and their pair sums (expansion_pairs.c). */
void biref_xp_form_vectors(const path_group *g, int G, const quad_form *f, double complex (*v)[MAX_COMP]);
void biref_xp_pair_sums(phase_cache *pc, const path_group *g, int G, int Gp, const double complex (*v)[MAX_COMP],
                        int evanescent, double out[][3]);

/* The incoherent tail and the orders (expansion_tail.c). */
void biref_xp_tail_setup(const biref_spectral *sp, const biref_slab_state *st, int which, const quad_form *forms,
                         int nf, tail_model *tm);
void biref_xp_tail_energy(const tail_model *tm, int k, int order, double out[3]);
expansion_orders biref_xp_choose_orders(phase_cache *pc, const biref_slab_state *st, const tail_model *tm, int nf,
                                        const biref_expansion_opts *o);

#endif
