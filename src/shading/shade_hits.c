/* biref_shade_hits (shading.h): a caller's hits in packets of the analytic kernel, the rest one by one. */
#include <math.h>

#include "shading/shader_internal.h"

/* Hits per kernel call: several packets of the widest kernel, small enough for the stack. */
#define CHUNK 32

static int finite3(const double v[3]) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

/* Hits k0 .. k0 + n - 1: the frames and checks of biref_shade_hit, then the kernel. */
static biref_status shade_chunk(const biref_shader *sh, size_t n, const biref_surface *surfaces,
                                const double (*view_dirs)[3], double (*T)[3], double (*R)[3], biref_status *status)
{
    biref_hit_frames fr[CHUNK];
    biref_packet_hit in[CHUNK];
    biref_packet_hit_light lights[CHUNK];
    const biref_packet_light_source *ls = biref_shader_packet_light(sh);
    biref_status st[CHUNK];
    unsigned char scalar[CHUNK];
    size_t m = 0, idx[CHUNK];
    for (size_t k = 0; k < n; k++) {
        st[k] = biref_hit_frames_make(&surfaces[k], view_dirs[k], &fr[k]);
        if (st[k] == BIREF_OK) st[k] = biref_slab_check(&fr[k].slab, NULL, 0);
        if (st[k] != BIREF_OK) continue;
        const biref_slab *b = &fr[k].slab;
        in[m] = (biref_packet_hit){b->eta_o, b->eta_e, {b->axis[0], b->axis[1], b->axis[2]}, b->thickness_nm,
                                   b->eta_i, b->eta_i * sin(fr[k].theta)};
        if (ls) {
            const double d[3] = {-fr[k].k_view[0], -fr[k].k_view[1], -fr[k].k_view[2]};
            biref_packet_light_of(ls, fr[k].x_T, d, fr[k].mirror, &lights[m]);
        }
        idx[m++] = k;
    }
    double pT[CHUNK][3], pR[CHUNK][3];
    biref_shader_packet(sh, in, ls ? lights : NULL, NULL, m, pT, pR, scalar);
    for (size_t j = 0; j < m; j++) {
        const size_t k = idx[j];
        if (scalar[j]) {
            st[k] = biref_shader_eval(sh, &fr[k], NULL, T[k], R[k]) == BIREF_OK ? BIREF_OK : BIREF_ERR_ILLCOND;
            continue;
        }
        for (int c = 0; c < 3; c++) T[k][c] = pT[j][c], R[k][c] = pR[j][c];
        st[k] = finite3(T[k]) && finite3(R[k]) ? BIREF_OK : BIREF_ERR_ILLCOND;
    }
    biref_status first = BIREF_OK;
    for (size_t k = 0; k < n; k++) {
        if (status) status[k] = st[k];
        if (st[k] != BIREF_OK && first == BIREF_OK) first = st[k];
    }
    return first;
}

biref_status biref_shade_hits(const biref_shader *sh, size_t n, const biref_surface *surfaces,
                              const double (*view_dirs)[3], double (*T_xyz)[3], double (*R_xyz)[3],
                              biref_status *status)
{
    if (!sh || (n && (!surfaces || !view_dirs || !T_xyz || !R_xyz))) return BIREF_ERR_INVALID;
    biref_status first = BIREF_OK;
    for (size_t k0 = 0; k0 < n; k0 += CHUNK) {
        const size_t c = n - k0 < CHUNK ? n - k0 : CHUNK;
        biref_status s = shade_chunk(sh, c, surfaces + k0, view_dirs + k0, T_xyz + k0, R_xyz + k0,
                                     status ? status + k0 : NULL);
        if (s != BIREF_OK && first == BIREF_OK) first = s;
    }
    return first;
}
