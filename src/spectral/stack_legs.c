/* The legs of a stack with dispersive layers across the band, and the phase integrals of a pair
 * of path groups from the sub-band tables (docs/STACKS.md, "Layers of a dispersive material";
 * the slab's machinery, subband.h and docs/PHYSICS.md §7).
 *
 * Every leg (a layer crossed in one mode and direction) has the phase φ(k) = k Re opl(k); legs of
 * equal phase at every sample point (the o legs of two equal plates, the two directions of a
 * plate whose axis lies in its surface) are one leg class. A path's phase is Σ_c n_c φ_c(k) over
 * its counts n_c of crossings per class, so the paths are followed with their count vectors (an
 * id here, equal counts one id), and a pair of groups has the exact phase difference
 * Φ(k) = Σ_c (n_c(h) − n_c(a)) φ_c(k), integrated as the slab's lags: tangents at the midpoints
 * of the coarsest level of sub-bands that keeps them within BIREF_SUBBAND_PHASE_TOL of Φ. */
#include <complex.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "optics/slab_internal.h"
#include "spectral/stack_internal.h"
#include "spectral/subband.h"

/* Legs within this (nm of optical path, at every sample point) are one class: the stack's own
 * merging distance (stack_paths.c). */
#define CLASS_NM 1e-6

typedef struct {
    int a, h; /* a < 0: free */
    double residual;
    double complex at[BIREF_BAND_NODES][3];
} lag_entry;

struct biref_stack_legs {
    const biref_spectral *sp;
    const biref_subbands *sb;
    int nc;                                  /* leg classes */
    unsigned char *flat;                     /* [class]: its path is the same at every point */
    int cls[BIREF_STACK_MAX_LAYERS][4];      /* [layer][BIREF_MODE_*] */
    double (*phi)[BIREF_SUBBAND_POINTS];     /* [class][point]: k Re opl */
    double (*grp)[BIREF_SUBBAND_POINTS];     /* [class][point]: d(k Re opl)/dk, the group path */
    uint16_t *counts;                        /* [id][class] */
    int n_ids, cap_ids;
    int *slots, n_slots; /* open addressing over ids by their counts, -1 free */
    /* The pairs' integrals under both nodes' weights, by (a, h): a band's two runs and the three
     * bands look up the same pairs. Open addressing, at most half full; beyond, computed anew. */
    lag_entry *cache;
    int n_cache, cap_cache;
};

/* Re opl and the group path of every leg of layer l at λ: a material's by its indices and
 * slopes, a constant layer's from the state (its group path is its path). A constant material's
 * slopes are 0: its group paths are its paths. */
static biref_status layer_legs(const biref_stack_state *st, int l, double lambda, double opl[4], double grp[4])
{
    const biref_layer *layer = &st->stack.layers[l];
    if (!layer->material) {
        for (int x = 0; x < 2; x++) {
            opl[BIREF_MODE_O_DOWN + x] = grp[BIREF_MODE_O_DOWN + x] = creal(st->opl_down[l][x]);
            opl[BIREF_MODE_O_UP + x] = grp[BIREF_MODE_O_UP + x] = creal(st->opl_up[l][x]);
        }
        return BIREF_OK;
    }
    double axis[3] = {0.0, 1.0, 0.0}, dopl[4];
    const double *a = layer->axis;
    if (!layer->isotropic && a[0] * a[0] + a[1] * a[1] + a[2] * a[2] > 0.0) biref_axis_unit_unchecked(a, axis);
    /* biref_opl_footprint's leg order is BIREF_MODE_*'s: down o, down e, up o, up e */
    biref_status s = biref_leg_paths_and_slopes(layer->material, axis, st->K, st->thickness_nm[l], lambda, opl, dopl);
    for (int m = 0; m < 4; m++) grp[m] = opl[m] - lambda * dopl[m];
    return s;
}

biref_status biref_stack_legs_group_paths(const biref_stack_state *st, double lambda, double grp[][4])
{
    for (int l = 0; l < st->n_layers; l++) {
        double opl[4], g[4];
        biref_status s = layer_legs(st, l, lambda, opl, g);
        if (s != BIREF_OK) return s;
        /* the state's own paths less their λ dopl/dλ: a constant material's are the state's */
        for (int x = 0; x < 2; x++) {
            const int d = BIREF_MODE_O_DOWN + x, u = BIREF_MODE_O_UP + x;
            grp[l][d] = creal(st->opl_down[l][x]) - (opl[d] - g[d]);
            grp[l][u] = creal(st->opl_up[l][x]) - (opl[u] - g[u]);
        }
    }
    return BIREF_OK;
}

/* The class of a leg sampled as phi, grp: an existing one within CLASS_NM, or a new one. */
static int classify(biref_stack_legs *L, const double *k, const double *phi, const double *grp)
{
    for (int c = 0; c < L->nc; c++) {
        int same = 1;
        for (int p = 0; same && p < BIREF_SUBBAND_POINTS; p++)
            same = fabs(L->phi[c][p] - phi[p]) <= k[p] * CLASS_NM && fabs(L->grp[c][p] - grp[p]) <= CLASS_NM;
        if (same) return c;
    }
    memcpy(L->phi[L->nc], phi, sizeof L->phi[0]);
    memcpy(L->grp[L->nc], grp, sizeof L->grp[0]);
    L->flat[L->nc] = 1;
    for (int p = 0; p < BIREF_SUBBAND_POINTS; p++) L->flat[L->nc] &= phi[p] == k[p] * grp[p];
    return L->nc++;
}

static biref_status sample_classes(biref_stack_legs *L, const biref_stack_state *st)
{
    const double *k = biref_subband_points(L->sb);
    double(*phi)[4][BIREF_SUBBAND_POINTS] = malloc((size_t)st->n_layers * sizeof *phi);
    double(*grp)[4][BIREF_SUBBAND_POINTS] = malloc((size_t)st->n_layers * sizeof *grp);
    biref_status s = phi && grp ? BIREF_OK : BIREF_ERR_NOMEM;
    for (int p = 0; p < BIREF_SUBBAND_POINTS && s == BIREF_OK; p++) {
        const double lambda = 2.0 * M_PI / k[p];
        for (int l = 0; l < st->n_layers && s == BIREF_OK; l++) {
            double opl[4], g[4];
            s = layer_legs(st, l, lambda, opl, g);
            for (int m = 0; m < 4; m++) phi[l][m][p] = k[p] * opl[m], grp[l][m][p] = g[m];
        }
    }
    for (int l = 0; l < st->n_layers && s == BIREF_OK; l++)
        for (int m = 0; m < 4; m++) L->cls[l][m] = classify(L, k, phi[l][m], grp[l][m]);
    free(phi);
    free(grp);
    return s;
}

/* The slot of the count vector v: where it is, or the free slot where it would go. */
static int find_slot(const biref_stack_legs *L, const uint16_t *v)
{
    uint64_t h = 1469598103934665603ull;
    for (int c = 0; c < L->nc; c++) h = (h ^ v[c]) * 1099511628211ull;
    for (int i = (int)(h % (uint64_t)L->n_slots);; i = (i + 1) % L->n_slots) {
        const int id = L->slots[i];
        if (id < 0 || !memcmp(L->counts + (size_t)id * (size_t)L->nc, v, (size_t)L->nc * sizeof *v)) return i;
    }
}

/* The id of count vector v (a new one if unseen); -1 when out of memory. */
static int intern(biref_stack_legs *L, const uint16_t *v)
{
    if (2 * (L->n_ids + 1) > L->n_slots) { /* keep the table at most half full */
        const int n = L->n_slots ? 2 * L->n_slots : 1024;
        int *slots = malloc((size_t)n * sizeof *slots);
        if (!slots) return -1;
        free(L->slots);
        L->slots = slots, L->n_slots = n;
        for (int i = 0; i < n; i++) slots[i] = -1;
        for (int id = 0; id < L->n_ids; id++) slots[find_slot(L, L->counts + (size_t)id * (size_t)L->nc)] = id;
    }
    const int i = find_slot(L, v);
    if (L->slots[i] >= 0) return L->slots[i];
    if (L->n_ids == L->cap_ids) {
        const int cap = L->cap_ids ? 2 * L->cap_ids : 256;
        uint16_t *c = realloc(L->counts, (size_t)cap * (size_t)L->nc * sizeof *c);
        if (!c) return -1;
        L->counts = c, L->cap_ids = cap;
    }
    memcpy(L->counts + (size_t)L->n_ids * (size_t)L->nc, v, (size_t)L->nc * sizeof *v);
    L->slots[i] = L->n_ids;
    return L->n_ids++;
}

int biref_stack_legs_child(biref_stack_legs *L, int id, int layer, int mode)
{
    uint16_t v[4 * BIREF_STACK_MAX_LAYERS];
    memcpy(v, L->counts + (size_t)id * (size_t)L->nc, (size_t)L->nc * sizeof *v);
    v[L->cls[layer][mode]]++; /* a path has at most 4096 legs (stack_paths.c) */
    return intern(L, v);
}

biref_status biref_stack_legs_create(const biref_spectral *sp, const biref_stack_state *st, biref_stack_legs **out)
{
    *out = NULL;
    biref_stack_legs *L = calloc(1, sizeof *L);
    if (!L) return BIREF_ERR_NOMEM;
    L->sp = sp;
    L->sb = biref_spectral_subbands(sp);
    L->phi = malloc((size_t)(4 * st->n_layers) * sizeof *L->phi);
    L->grp = malloc((size_t)(4 * st->n_layers) * sizeof *L->grp);
    L->flat = malloc((size_t)(4 * st->n_layers));
    biref_status s = L->sb && L->phi && L->grp && L->flat ? sample_classes(L, st) : BIREF_ERR_NOMEM;
    const uint16_t none[4 * BIREF_STACK_MAX_LAYERS] = {0};
    if (s == BIREF_OK && intern(L, none) != 0) s = BIREF_ERR_NOMEM; /* id 0: no leg yet */
    if (s != BIREF_OK) {
        biref_stack_legs_destroy(L);
        return s;
    }
    *out = L;
    return BIREF_OK;
}

void biref_stack_legs_destroy(biref_stack_legs *L)
{
    if (!L) return;
    free(L->phi);
    free(L->grp);
    free(L->flat);
    free(L->counts);
    free(L->slots);
    free(L->cache);
    free(L);
}

int biref_stack_legs_flat(const biref_stack_legs *L)
{
    for (int q = 0; q < L->nc; q++)
        if (!L->flat[q]) return 0;
    return 1;
}

const biref_band_nodes *biref_stack_legs_nodes(const biref_stack_legs *L) { return biref_subband_nodes(L->sb); }

/* The error of the band's own table at the middle tangent for a phase whose group path G leaves
 * the sub-band tables at some points and not at others (it crosses their end, d_max, inside the
 * band; the tangent's residual, which only the sub-bands would bring down, does not measure it).
 * With a stationary point (G changes sign) the integral is not small and the middle tangent may
 * be far from it: the residual res0 of that tangent (0 within BIREF_SUBBAND_PHASE_TOL). Without one
 * the integral is its endpoint terms, of the size of a constant lag's at the smallest |G|, and so
 * is the tangent's (at a larger |G|): twice the band integral's modulus at the smallest |G|, the
 * largest of the three bands. */
static double crossing_error(const biref_spectral *sp, const double *G, double res0)
{
    double lo = fabs(G[0]);
    for (int p = 1; p < BIREF_SUBBAND_POINTS; p++) {
        if ((G[p] < 0.0) != (G[0] < 0.0)) return res0 > BIREF_SUBBAND_PHASE_TOL ? res0 : 0.0;
        lo = fmin(lo, fabs(G[p]));
    }
    double c[3], s[3], most = 0.0;
    biref_spectral_phase_integrals(sp, lo, c, s);
    for (int j = 0; j < 3; j++) most = fmax(most, hypot(c[j], s[j]));
    return 2.0 * most;
}

/* m0 = S(e^{iΦ}, Λ_j), m1 = S(k e^{iΦ}, Λ_j) of a phase Φ sampled at every point, as
 * biref_lag_integrals takes them: sub-bands while every group path is inside their tables, else
 * the band's own table at the middle tangent (*far). Returns the error estimate of the integrals:
 * the tangents' residual beyond BIREF_SUBBAND_PHASE_TOL (radians), crossing_error where the
 * group path crosses the tables' end, 0 within the tolerance and where the group path is beyond
 * the tables across the whole band (the integral has all but vanished there). */
static double phase_moments(const biref_stack_legs *L, const double *Phi, const double *G, double complex m0[3],
                            double complex m1[3], int *far)
{
    const biref_spectral *sp = L->sp;
    int inside = 1, beyond = 1;
    for (int p = 0; p < BIREF_SUBBAND_POINTS; p++) {
        inside &= fabs(G[p]) <= sp->d_max;
        beyond &= !(fabs(G[p]) <= sp->d_max);
    }
    double res;
    const int level =
        biref_subband_level(sp, Phi, G, biref_subband_points(L->sb), 0, BIREF_SUBBAND_POINTS - 1, NULL, NULL, &res);
    *far = !inside;
    biref_subband_moments(sp, L->sb, Phi, G, level, !inside, m0, m1);
    if (inside || beyond) return inside && res > BIREF_SUBBAND_PHASE_TOL ? res : 0.0;
    return crossing_error(sp, G, res);
}

/* The cache entry of pair (a, h): where it is, or the free one where it would go; NULL when the
 * cache cannot take it. */
static lag_entry *cache_slot(biref_stack_legs *L, int a, int h)
{
    if (!L->cache) {
        L->cap_cache = 4096;
        L->cache = malloc((size_t)L->cap_cache * sizeof *L->cache);
        if (!L->cache) return NULL;
        for (int i = 0; i < L->cap_cache; i++) L->cache[i].a = -1;
    }
    const unsigned hash = (unsigned)a * 2654435761u ^ (unsigned)h * 40503u;
    for (int probe = 0; probe < L->cap_cache; probe++) {
        lag_entry *e = &L->cache[(hash + (unsigned)probe) % (unsigned)L->cap_cache];
        if (e->a < 0) return 2 * L->n_cache < L->cap_cache ? e : NULL;
        if (e->a == a && e->h == h) return e;
    }
    return NULL;
}

void biref_stack_legs_lag(biref_stack_legs *L, int a, int h, double delta, int node, double c[3], double s[3],
                          double *residual)
{
    lag_entry *e = node >= 0 ? cache_slot(L, a, h) : NULL;
    if (e && e->a >= 0) {
        for (int j = 0; j < 3; j++) c[j] = creal(e->at[node][j]), s[j] = cimag(e->at[node][j]);
        *residual = e->residual;
        return;
    }
    const uint16_t *na = L->counts + (size_t)a * (size_t)L->nc, *nh = L->counts + (size_t)h * (size_t)L->nc;
    double Phi[BIREF_SUBBAND_POINTS] = {0}, G[BIREF_SUBBAND_POINTS] = {0};
    int flat = 1;
    for (int q = 0; q < L->nc; q++) {
        const int dn = (int)nh[q] - (int)na[q];
        if (!dn) continue;
        flat &= L->flat[q];
        for (int p = 0; p < BIREF_SUBBAND_POINTS; p++) Phi[p] += dn * L->phi[q][p], G[p] += dn * L->grp[q][p];
    }
    *residual = 0.0;
    if (flat && node < 0) { /* a constant path difference: the constant stack's look-up, to the bit */
        biref_spectral_phase_integrals(L->sp, delta, c, s);
        return;
    }
    double complex m0[3], m1[3] = {0, 0, 0}, at[BIREF_BAND_NODES][3];
    int far;
    *residual = phase_moments(L, Phi, G, m0, m1, &far);
    const double complex *out = m0;
    if (node >= 0) {
        biref_lag_node_integrals(biref_subband_nodes(L->sb), m0, m1, far, at);
        out = at[node];
        if (e) {
            e->a = a, e->h = h, e->residual = *residual;
            memcpy(e->at, at, sizeof at);
            L->n_cache++;
        }
    }
    for (int j = 0; j < 3; j++) c[j] = creal(out[j]), s[j] = cimag(out[j]);
}
