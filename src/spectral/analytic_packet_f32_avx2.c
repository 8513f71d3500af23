/* The packet kernel with float lanes for AVX2 + FMA: 8 lanes of float for the terms, two packets
 * of 4 lanes of double for the set-up and the look-ups. Compiled with -mavx2 -mfma and contracted
 * multiply-adds (CMakeLists.txt); called only when the CPU has both (analytic_packet.c). */
#include "spectral/simd/avx2.h"
#define PACKET_HITS_FN biref_packet_hits_f32_avx2
#define PACKET_HITS_F64_FN biref_packet_hits_avx2
#include "spectral/analytic_packet_f32_kernel.inc"
