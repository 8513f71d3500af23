/* The numeric methods' lanes for AVX2 + FMA: 4 lanes of double (numeric_lanes.inc; compiled with the set's flags,
 * CMakeLists.txt biref_isa_object; called only where the CPU has them, numeric_lanes.c). */
#define _GNU_SOURCE /* sincos */
#include "spectral/simd/avx2.h"
#define NUMERIC_LANES_FN biref_numeric_lanes_avx2
#define NUMERIC_SINCOS_FN biref_numeric_lanes_sincos_avx2
#define NUMERIC_HITS_FN biref_numeric_hits_avx2
#include "spectral/numeric_lanes.inc"
