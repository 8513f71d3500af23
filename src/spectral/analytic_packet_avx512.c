/* The packet kernel for AVX-512F: 8 lanes of double. Compiled with -mavx512f -mavx2 -mfma and
 * contracted multiply-adds (CMakeLists.txt); called only when the CPU has AVX-512F
 * (analytic_packet.c). */
#include "spectral/simd/avx512.h"
#define PACKET_HITS_FN biref_packet_hits_avx512
#include "spectral/analytic_packet_kernel.inc"
