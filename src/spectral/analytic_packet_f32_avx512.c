/* The packet kernel with float lanes for AVX-512F: 16 lanes of float for the terms, two packets
 * of 8 lanes of double for the set-up and the look-ups. Compiled with -mavx512f -mavx2 -mfma and
 * contracted multiply-adds (CMakeLists.txt); called only when the CPU has AVX-512F
 * (analytic_packet.c). */
#include "spectral/simd/avx512.h"
#define PACKET_HITS_FN biref_packet_hits_f32_avx512
#define PACKET_HITS_F64_FN biref_packet_hits_avx512
#include "spectral/analytic_packet_f32_kernel.inc"
