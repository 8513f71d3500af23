/* The packet kernel for any x86-64 (or other) CPU: 4 lanes of double in generic vector code. */
#include "spectral/simd/baseline.h"
#define PACKET_HITS_FN biref_packet_hits_baseline
#include "spectral/analytic_packet_kernel.inc"
