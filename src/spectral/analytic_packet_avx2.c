/* The packet kernel for AVX2 + FMA: 4 lanes of double. Compiled with -mavx2 -mfma and contracted
 * multiply-adds (CMakeLists.txt); called only when the CPU has both (analytic_packet.c). */
#include "spectral/simd/avx2.h"
#define PACKET_HITS_FN biref_packet_hits_avx2
#include "spectral/analytic_packet_kernel.inc"
