/* The path expansion of a stack (docs/STACKS.md §2): every path a wave can take through the
 * layers — an o or e leg per crossing, a reflection or a transmission at every interface — with
 * the paths of equal optical path merged into one group, followed one leg at a time until the
 * light still inside (plus what was dropped) bounds the truncation error below the tolerance. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "spectral/stack_internal.h"

/* Paths whose optical paths differ by less than this (nm) are one group: a phase error of
 * 2 pi 1e-6 / 380 rad at most, far below any tolerance. */
#define MERGE_NM 1e-6
/* A path whose amplitude bound is below tolerance * DROP is dropped (its bound still counts). */
#define DROP 1e-5
/* Legs followed at most, and live paths at most, before giving up (fall back). */
#define MAX_LEGS 4096
#define MAX_LIVE (1 << 18)

typedef struct {
    double phi;
    int id;              /* dispersive: the id of the path's leg counts (stack_legs.c), else 0 */
    double complex a[2]; /* amplitude per input s/p */
    int key;             /* layer * 4 + BIREF_MODE_* (down o/e, up o/e) */
} packet;

typedef struct {
    packet *p;
    int n, cap;
} packets;

typedef struct {
    biref_stack_group *g;
    int n, cap;
} groups;

static int packets_push(packets *v, packet x)
{
    if (v->n == v->cap) {
        int cap = v->cap ? 2 * v->cap : 256;
        packet *np = realloc(v->p, (size_t)cap * sizeof *np);
        if (!np) return -1;
        v->p = np, v->cap = cap;
    }
    v->p[v->n++] = x;
    return 0;
}

static int groups_push(groups *v, double phi, int id, const double complex M[2][2])
{
    if (v->n == v->cap) {
        int cap = v->cap ? 2 * v->cap : 64;
        biref_stack_group *ng = realloc(v->g, (size_t)cap * sizeof *ng);
        if (!ng) return -1;
        v->g = ng, v->cap = cap;
    }
    biref_stack_group *g = &v->g[v->n++];
    g->phi = phi;
    g->id = id;
    memcpy(g->M, M, sizeof g->M);
    return 0;
}

static int by_key_phi(const void *pa, const void *pb)
{
    const packet *a = pa, *b = pb;
    if (a->key != b->key) return a->key < b->key ? -1 : 1;
    return (a->phi > b->phi) - (a->phi < b->phi);
}

static int by_phi(const void *pa, const void *pb)
{
    const biref_stack_group *a = pa, *b = pb;
    return (a->phi > b->phi) - (a->phi < b->phi);
}

/* Sorts and merges packets of one key and (nearly) one optical path. */
static void merge_packets(packets *v)
{
    if (v->n < 2) return;
    qsort(v->p, (size_t)v->n, sizeof *v->p, by_key_phi);
    int w = 0;
    for (int r = 1; r < v->n; r++) {
        packet *last = &v->p[w];
        if (v->p[r].key == last->key && v->p[r].phi - last->phi < MERGE_NM && v->p[r].id == last->id) {
            last->a[0] += v->p[r].a[0];
            last->a[1] += v->p[r].a[1];
        } else {
            v->p[++w] = v->p[r];
        }
    }
    v->n = w + 1;
}

static void merge_groups(groups *v)
{
    if (v->n < 2) return;
    qsort(v->g, (size_t)v->n, sizeof *v->g, by_phi);
    int w = 0;
    for (int r = 1; r < v->n; r++) {
        if (v->g[r].phi - v->g[w].phi < MERGE_NM && v->g[r].id == v->g[w].id) {
            for (int i = 0; i < 2; i++)
                for (int o = 0; o < 2; o++) v->g[w].M[i][o] += v->g[r].M[i][o];
        } else {
            v->g[++w] = v->g[r];
        }
    }
    v->n = w + 1;
}

/* Bound on the amplitude this packet can still send into any one output: sqrt of its power
 * (a single mode wave in a lossless stack delivers exactly its power in total). */
static double packet_amplitude(const biref_stack_state *st, const packet *p)
{
    double a = fmax(cabs(p->a[0]), cabs(p->a[1]));
    return a * sqrt(st->flux[p->key / 4][p->key % 4]);
}

typedef struct {
    const biref_stack_state *st;
    const double (*grp)[4];  /* dispersive: each leg's group path [layer][BIREF_MODE_*], else NULL */
    biref_stack_legs *legs;  /* dispersive: the legs' classes and the paths' counts, else NULL */
    packets *next;
    groups *exits; /* [0] bottom, [1] top */
    double drop, dropped;
} step_ctx;

/* A child of amplitude a * c[m][.] in layer L, direction up (1) or down (0); or leaving. */
static int scatter(step_ctx *c, const packet *p, const biref_complex f[2][2], int m, int layer, int up, int exit)
{
    if (exit >= 0) {
        const double complex M[2][2] = {{p->a[0] * f[m][0], p->a[0] * f[m][1]}, {p->a[1] * f[m][0], p->a[1] * f[m][1]}};
        return groups_push(&c->exits[exit], p->phi, p->id, M);
    }
    for (int x = 0; x < 2; x++) {
        packet q = {p->phi, p->id, {p->a[0] * f[m][x], p->a[1] * f[m][x]},
                    layer * 4 + (up ? BIREF_MODE_O_UP : 0) + x};
        if (q.a[0] == 0.0 && q.a[1] == 0.0) continue; /* no o/e coupling (isotropic neighbours) */
        double amp = packet_amplitude(c->st, &q);
        if (amp < c->drop) {
            c->dropped += amp;
            continue;
        }
        if (packets_push(c->next, q)) return -1;
    }
    return 0;
}

/* One leg for every live packet: cross the layer, then reflect and transmit at the face reached. */
static int step(step_ctx *c, const packets *cur)
{
    const biref_stack_state *st = c->st;
    const int n = st->n_layers;
    for (int k = 0; k < cur->n; k++) {
        packet p = cur->p[k];
        const int layer = p.key / 4, mode = p.key % 4, up = mode >= BIREF_MODE_O_UP, m = mode & 1;
        p.phi += c->grp ? c->grp[layer][mode] : creal(up ? st->opl_up[layer][m] : st->opl_down[layer][m]);
        if (c->legs && (p.id = biref_stack_legs_child(c->legs, p.id, layer, mode)) < 0) return -1;
        const biref_interface *f = &st->iface[up ? layer : layer + 1];
        int r;
        if (!up) {
            r = scatter(c, &p, f->r_down, m, layer, 1, -1);
            if (!r) r = scatter(c, &p, f->t_down, m, layer + 1, 0, layer + 1 == n ? 0 : -1);
        } else {
            r = scatter(c, &p, f->r_up, m, layer, 0, -1);
            if (!r) r = scatter(c, &p, f->t_up, m, layer - 1, 1, layer == 0 ? 1 : -1);
        }
        if (r) return -1;
    }
    return 0;
}

static double live_amplitude(const biref_stack_state *st, const packets *v)
{
    double a = 0.0;
    for (int k = 0; k < v->n; k++) a += packet_amplitude(st, &v->p[k]);
    return a;
}

/* Follows the paths; returns 0, or -1 when out of memory. */
static int follow(const biref_stack_state *st, const double (*grp)[4], biref_stack_legs *legs, double tolerance,
                  int max_groups, groups exits[2], biref_stack_groups *out)
{
    packets cur = {0}, next = {0};
    step_ctx c = {st, grp, legs, &next, exits, tolerance * DROP, 0.0};
    int rc = 0;
    /* The direct reflection, and the two modes refracted into the first layer. */
    if (groups_push(&exits[1], 0.0, 0, (const double complex(*)[2])st->iface[0].r_down)) {
        rc = -1;
        goto done;
    }
    for (int m = 0; m < 2; m++) {
        packet q = {0.0, 0, {st->iface[0].t_down[0][m], st->iface[0].t_down[1][m]}, m};
        if ((q.a[0] != 0.0 || q.a[1] != 0.0) && packets_push(&cur, q)) {
            rc = -1;
            goto done;
        }
    }
    for (out->legs = 0;; out->legs++) {
        const double A = c.dropped + live_amplitude(st, &cur);
        out->bound = 2 * A + 3 * A * A;
        if (out->bound <= tolerance || cur.n == 0) break;
        if (out->legs >= MAX_LEGS || cur.n > MAX_LIVE) {
            out->reason = "the truncation bound is not met within the path limit";
            break;
        }
        next.n = 0;
        if (step(&c, &cur)) {
            rc = -1;
            goto done;
        }
        merge_packets(&next);
        packets t = cur;
        cur = next, next = t;
        for (int f = 0; f < 2; f++) {
            if (exits[f].n > max_groups) merge_groups(&exits[f]);
            if (exits[f].n > max_groups) {
                out->reason = "too many path groups";
                goto done;
            }
        }
    }
    if (!out->reason && out->bound > tolerance) out->reason = "the truncation bound is not met (dropped paths)";
done:
    free(cur.p);
    free(next.p);
    return rc;
}

biref_status biref_stack_path_groups(const biref_stack_state *st, const double (*grp)[4], biref_stack_legs *legs,
                                     double tolerance, int max_groups, biref_stack_groups *out)
{
    memset(out, 0, sizeof *out);
    if (st->evanescent) {
        out->reason = "a layer has an evanescent mode (total reflection inside)";
        return BIREF_OK;
    }
    groups exits[2] = {{0}, {0}};
    int rc = follow(st, grp, legs, tolerance, max_groups, exits, out);
    for (int f = 0; f < 2 && !rc && !out->reason; f++) {
        merge_groups(&exits[f]);
        if (exits[f].n > max_groups) out->reason = "too many path groups";
    }
    if (rc || out->reason) {
        free(exits[0].g);
        free(exits[1].g);
        return rc ? BIREF_ERR_NOMEM : BIREF_OK;
    }
    for (int f = 0; f < 2; f++) out->g[f] = exits[f].g, out->n[f] = exits[f].n;
    return BIREF_OK;
}

void biref_stack_groups_free(biref_stack_groups *g)
{
    free(g->g[0]);
    free(g->g[1]);
    g->g[0] = g->g[1] = NULL;
    g->n[0] = g->n[1] = 0;
}
