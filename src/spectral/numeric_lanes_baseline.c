/* The numeric methods' lanes for any x86-64 (or other) CPU: 4 lanes of double in generic vector code, the phases by libm's sincos (numeric_lanes.inc; compiled with the set's flags,
 * CMakeLists.txt biref_isa_object; called only where the CPU has them, numeric_lanes.c). */
#define _GNU_SOURCE /* sincos */
#include "spectral/simd/baseline.h"
#define NUMERIC_LANES_FN biref_numeric_lanes_baseline
#define NUMERIC_SINCOS_FN biref_numeric_lanes_sincos_baseline
#define NUMERIC_HITS_FN biref_numeric_hits_baseline
#include "spectral/numeric_lanes.inc"
