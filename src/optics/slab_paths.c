/* The path expansion of a slab's Jones matrices (paper §4, eqs. 12–16): every sequence of
 * o/e legs up to a given order, with its wavelength-independent amplitude and optical path. */
#include "biref/optics.h"
#include "optics/cmat2.h"

#define MAX_ORDER 12

size_t biref_path_count(int which, int max_order)
{
    if (max_order < 0 || max_order > MAX_ORDER) return 0;
    size_t n = which == BIREF_REFLECTION ? 1 : 0;
    for (int o = (which == BIREF_REFLECTION ? 1 : 0); o <= max_order; o++)
        n += (size_t)1 << (which == BIREF_REFLECTION ? 2 * o : 2 * o + 1);
    return n;
}

/* Leg i of a path: transmission legs alternate down, up, down ... (2n+1 legs); reflection
 * legs alternate down, up, ... (2n legs). Each down leg ends with a reflection at the bottom
 * (r12) unless it is the last leg of a transmitted path (t12); each up leg ends with a
 * reflection at the top (r10) unless it is the last leg of a reflected path (t10). */
static void build_path(const biref_slab_state *st, int which, int order, uint32_t legs, biref_path *p)
{
    int n_legs = which == BIREF_REFLECTION ? 2 * order : 2 * order + 1;
    cmat2 amp = cmat2_from(st->top.t_down);
    double complex opl = 0.0;
    int prev = -1, n_down_e = 0, n_up_e = 0;
    for (int i = 0; i < n_legs; i++) {
        int type = (legs >> i) & 1u;
        int down = (i % 2) == 0;
        if (prev >= 0) {
            /* Reflection that turned leg prev into leg type: bottom after a down leg, top after an up leg. */
            const double complex(*r)[2] = down ? st->top.r_up : st->bottom.r_down;
            for (int a = 0; a < 2; a++) {
                double complex v = amp.m[a][prev] * r[prev][type];
                amp.m[a][0] = amp.m[a][1] = 0.0;
                amp.m[a][type] = v;
            }
        } else {
            for (int a = 0; a < 2; a++) amp.m[a][1 - type] = 0.0;
        }
        opl += down ? st->opl_down[type] : st->opl_up[type];
        if (type) {
            if (down)
                n_down_e++;
            else
                n_up_e++;
        }
        prev = type;
    }
    const double complex(*exit)[2] = which == BIREF_REFLECTION ? st->top.t_up : st->bottom.t_down;
    for (int a = 0; a < 2; a++) {
        double complex v = amp.m[a][prev];
        p->amp[a][0] = v * exit[prev][0];
        p->amp[a][1] = v * exit[prev][1];
    }
    p->opl_nm = opl;
    p->legs = legs;
    p->order = (uint8_t)order;
    p->n_down_e = (uint8_t)n_down_e;
    p->n_up_e = (uint8_t)n_up_e;
    p->n_legs = (uint8_t)n_legs;
}

size_t biref_slab_paths(const biref_slab_state *st, int which, int max_order, biref_path *out, size_t cap)
{
    size_t need = biref_path_count(which, max_order);
    if (need == 0 || need > cap) return 0;
    size_t k = 0;
    int first = 0;
    if (which == BIREF_REFLECTION) {
        biref_path *p = &out[k++];
        for (int a = 0; a < 2; a++)
            for (int b = 0; b < 2; b++) p->amp[a][b] = st->top.r_down[a][b];
        p->opl_nm = 0.0;
        p->legs = 0;
        p->order = 0;
        p->n_down_e = p->n_up_e = 0;
        p->n_legs = 0;
        first = 1;
    }
    for (int o = first; o <= max_order; o++) {
        int n_legs = which == BIREF_REFLECTION ? 2 * o : 2 * o + 1;
        for (uint32_t legs = 0; legs < (1u << n_legs); legs++) build_path(st, which, o, legs, &out[k++]);
    }
    return k;
}
