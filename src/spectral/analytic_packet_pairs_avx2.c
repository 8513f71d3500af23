/* The packet kernel of the analytic-pairs method for avx2 (analytic_packet_avx2.c with the
 * siblings and entry pairs compiled in). */
#define PACKET_PAIRS 1
#include "spectral/simd/avx2.h"
#define PACKET_HITS_FN biref_packet_hits_pairs_avx2
#include "spectral/analytic_packet_kernel.inc"
