/* The float-lane packet kernel of the analytic-pairs method for avx2 (analytic_packet_f32_avx2.c
 * with the siblings and entry pairs compiled in). */
#define PACKET_PAIRS 1
#include "spectral/simd/avx2.h"
#define PACKET_HITS_FN biref_packet_hits_f32_pairs_avx2
#define PACKET_HITS_F64_FN biref_packet_hits_pairs_avx2
#include "spectral/analytic_packet_f32_kernel.inc"
