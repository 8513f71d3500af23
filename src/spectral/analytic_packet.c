/* The packet kernel's run-time choice of instruction set and which states it may take
 * (analytic_packet.h). */
#include <complex.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "spectral/analytic_packet.h"
#include "spectral/spectral_internal.h"

static const char *const ISA_NAMES[BIREF_SIMD_COUNT] = {"scalar", "baseline", "avx2", "avx512"};

const char *biref_simd_isa_name(biref_simd_isa isa)
{
    return (int)isa >= 0 && isa < BIREF_SIMD_COUNT ? ISA_NAMES[isa] : NULL;
}

int biref_simd_isa_supported(biref_simd_isa isa)
{
    switch (isa) {
    case BIREF_SIMD_SCALAR:
    case BIREF_SIMD_BASELINE: return 1;
#if defined(__x86_64__) && defined(__GNUC__)
    /* __builtin_cpu_supports also checks that the operating system saves the wide registers. */
    case BIREF_SIMD_AVX2: return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    case BIREF_SIMD_AVX512: return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx2") &&
                                   __builtin_cpu_supports("fma");
#endif
    default: return 0;
    }
}

static biref_simd_isa fastest(void)
{
    for (int i = BIREF_SIMD_COUNT - 1; i > BIREF_SIMD_SCALAR; i--)
        if (biref_simd_isa_supported((biref_simd_isa)i)) return (biref_simd_isa)i;
    return BIREF_SIMD_SCALAR;
}

biref_status biref_simd_isa_pick(biref_simd_isa *out, char *msg, size_t msg_len)
{
    *out = fastest();
    const char *want = getenv("BIREF_SIMD");
    if (!want || !*want) return BIREF_OK;
    for (int i = 0; i < BIREF_SIMD_COUNT; i++) {
        if (strcmp(want, ISA_NAMES[i])) continue;
        if (!biref_simd_isa_supported((biref_simd_isa)i))
            return biref_fail(msg, msg_len, "BIREF_SIMD=%s: this CPU cannot run it (it runs scalar, baseline%s%s)",
                              want, biref_simd_isa_supported(BIREF_SIMD_AVX2) ? ", avx2" : "",
                              biref_simd_isa_supported(BIREF_SIMD_AVX512) ? ", avx512" : "");
        *out = (biref_simd_isa)i;
        return BIREF_OK;
    }
    return biref_fail(msg, msg_len, "BIREF_SIMD=%.40s: expected scalar, baseline, avx2 or avx512", want);
}

biref_simd_isa biref_simd_isa_choose(void)
{
    biref_simd_isa isa;
    return biref_simd_isa_pick(&isa, NULL, 0) == BIREF_OK ? isa : fastest();
}

static int real_matrix(const biref_complex (*m)[2])
{
    return cimag(m[0][0]) == 0.0 && cimag(m[0][1]) == 0.0 && cimag(m[1][0]) == 0.0 && cimag(m[1][1]) == 0.0;
}

static int real_interface(const biref_interface *f)
{
    return real_matrix(f->r_down) && real_matrix(f->t_down) && real_matrix(f->r_up) && real_matrix(f->t_up);
}

int biref_packet_eligible(const biref_spectral *sp, const biref_slab_state *st)
{
    (void)sp;
    if (st->total_reflection) return 0;
    for (int k = 0; k < 2; k++)
        if (cimag(st->opl_down[k]) != 0.0 || cimag(st->opl_up[k]) != 0.0) return 0;
    if (!real_interface(&st->top) || !real_interface(&st->bottom)) return 0;
    /* The flipped state has the same round trips (down and up legs swapped), so the same answer. */
    return !biref_coherent_real_paths(st);
}

biref_packet_hits_kernel biref_simd_hits_kernel(biref_simd_isa isa)
{
    switch (isa) {
    case BIREF_SIMD_AVX2: return biref_packet_hits_f32_avx2;
    case BIREF_SIMD_AVX512: return biref_packet_hits_f32_avx512;
    default: return biref_simd_hits_kernel_f64(isa);
    }
}

biref_packet_hits_kernel biref_simd_hits_kernel_f64(biref_simd_isa isa)
{
    switch (isa) {
    case BIREF_SIMD_BASELINE: return biref_packet_hits_baseline;
    case BIREF_SIMD_AVX2: return biref_packet_hits_avx2;
    case BIREF_SIMD_AVX512: return biref_packet_hits_avx512;
    default: return NULL;
    }
}

biref_packet_hits_kernel biref_simd_hits_kernel_pairs(biref_simd_isa isa)
{
    switch (isa) {
    case BIREF_SIMD_AVX2: return biref_packet_hits_f32_pairs_avx2;
    case BIREF_SIMD_AVX512: return biref_packet_hits_f32_pairs_avx512;
    default: return biref_simd_hits_kernel_f64_pairs(isa);
    }
}

biref_packet_hits_kernel biref_simd_hits_kernel_f64_pairs(biref_simd_isa isa)
{
    switch (isa) {
    case BIREF_SIMD_BASELINE: return biref_packet_hits_pairs_baseline;
    case BIREF_SIMD_AVX2: return biref_packet_hits_pairs_avx2;
    case BIREF_SIMD_AVX512: return biref_packet_hits_pairs_avx512;
    default: return NULL;
    }
}
