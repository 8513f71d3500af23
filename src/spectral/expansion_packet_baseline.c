/* The expansion's packet kernel for any x86-64 (or other) CPU: 4 lanes of double in generic vector code (expansion_packet.h). */
#include "spectral/simd/baseline.h"
#define EXPANSION_HITS_FN biref_expansion_hits_baseline
#include "spectral/expansion_packet_kernel.inc"
