/* The inner loop shared by the two demodulated tables (spectral_context.c, phase_prefilter.c):
 * one wavelength sample's contribution to a run of nodes. */
#ifndef BIREF_SPECTRAL_TABLE_BUILD_H
#define BIREF_SPECTRAL_TABLE_BUILD_H

#include <complex.h>

/* rows[m] (12 doubles: [band][re, im, dre/dD, dim/dD]) += w[band] * (z, dz z) for m = 0..count-1,
 * z advancing by one rotation per node; returns z after the last node. The four values of a
 * band are one vector of two pairs, each element a product and a sum as in scalar code (the
 * library is compiled without contraction), so the table is the same to the bit as element by
 * element, and about half the instructions. */
static inline double complex biref_table_accumulate(double *rows, int count, const double w[3], double complex z,
                                                    double complex rot, double complex dz)
{
    typedef double pair __attribute__((vector_size(16)));
    const pair w2[3] = {{w[0], w[0]}, {w[1], w[1]}, {w[2], w[2]}};
    for (int m = 0; m < count; m++) {
        double *row = rows + (size_t)m * 12;
        const double complex zd = dz * z;
        const pair v = {creal(z), cimag(z)}, v_d = {creal(zd), cimag(zd)};
        for (int j = 0; j < 3; j++) {
            pair a, b;
            __builtin_memcpy(&a, row + 4 * j, sizeof a);
            __builtin_memcpy(&b, row + 4 * j + 2, sizeof b);
            a += w2[j] * v;
            b += w2[j] * v_d;
            __builtin_memcpy(row + 4 * j, &a, sizeof a);
            __builtin_memcpy(row + 4 * j + 2, &b, sizeof b);
        }
        z *= rot;
    }
    return z;
}

/* The packet kernel's copy of a demodulated table (12 doubles per node, as above) and its node
 * carriers ([m][re, im]): per node 16 doubles, [F_j re, im for the bands j = 0..2, carrier re,
 * im | dF_j/dD re, im, 0, 0]. One lane's Hermite interpolation between nodes m and m + 1 then
 * reads the 32 contiguous doubles from 16 m: whole vector loads instead of one gather per value
 * (analytic_packet_kernel.inc, v_table_rows). The values are copied, not recomputed, so the
 * kernel interpolates the same numbers as spectral_table_eval. */
#define BIREF_PACKET_TABLE_STRIDE 16
static inline void biref_table_packet_layout(const double *table, const double *carrier, int nodes, double *out)
{
    for (int m = 0; m < nodes; m++) {
        const double *in = table + (size_t)m * 12;
        double *row = out + (size_t)m * BIREF_PACKET_TABLE_STRIDE;
        for (int j = 0; j < 3; j++) {
            row[2 * j] = in[4 * j];
            row[2 * j + 1] = in[4 * j + 1];
            row[8 + 2 * j] = in[4 * j + 2];
            row[8 + 2 * j + 1] = in[4 * j + 3];
        }
        row[6] = carrier[2 * m];
        row[7] = carrier[2 * m + 1];
        row[14] = row[15] = 0.0; /* weighted like derivatives: must add exactly 0 */
    }
}

/* The float lanes' copy (analytic_packet_f32_kernel.inc): per node m the 32 floats one lane
 * reads, [F_j(m), carrier(m) | dF_j(m)/dD, 0, 0 | F_j(m + 1), carrier(m) | dF_j(m + 1)/dD, 0, 0]
 * from the packet layout above, each value rounded once. The carrier sits in both value blocks,
 * so the Hermite weights h00 + h01 = 1 give it without masking the weights per lane. The last
 * node has no successor (look-ups use nodes m <= nodes - 2): its second half is 0 but for the
 * carrier. */
#define BIREF_PACKET_TABLE_F32_STRIDE 32
static inline void biref_table_packet_layout_f32(const double *packet, int nodes, float *out)
{
    for (int m = 0; m < nodes; m++) {
        const double *row = packet + (size_t)m * BIREF_PACKET_TABLE_STRIDE;
        const double *next = m + 1 < nodes ? row + BIREF_PACKET_TABLE_STRIDE : NULL;
        float *o = out + (size_t)m * BIREF_PACKET_TABLE_F32_STRIDE;
        for (int v = 0; v < 16; v++) {
            o[v] = (float)row[v];
            o[16 + v] = next ? (float)next[v] : 0.0f;
        }
        o[16 + 6] = (float)row[6];
        o[16 + 7] = (float)row[7];
    }
}

#endif
