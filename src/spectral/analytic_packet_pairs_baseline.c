/* The packet kernel of the analytic-pairs method for baseline (analytic_packet_baseline.c with the
 * siblings and entry pairs compiled in). */
#define PACKET_PAIRS 1
#include "spectral/simd/baseline.h"
#define PACKET_HITS_FN biref_packet_hits_pairs_baseline
#include "spectral/analytic_packet_kernel.inc"
