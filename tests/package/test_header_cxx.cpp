// The public header as a C++17 program sees it: it must compile warning-free, and the complex
// amplitudes the C library writes must read back correctly through std::complex<double>.
#include <biref/biref.h>

#include <cmath>
#include <cstdio>
#include <type_traits>

static_assert(sizeof(biref_complex) == 2 * sizeof(double), "biref_complex is {re, im}");
static_assert(alignof(biref_complex) == alignof(double), "biref_complex aligns as double");
static_assert(std::is_standard_layout<biref_jones>::value, "public structs stay plain data");

int main()
{
    int failures = 0;
    // Analyzer along s: projection onto (1, 0), so P = [[1, 0], [0, 0]] exactly.
    biref_complex P[2][2];
    biref_analyzer_linear(0.0, P);
    if (P[0][0] != biref_complex(1.0, 0.0) || std::abs(P[1][1]) > 1e-15) {
        std::printf("FAIL analyzer_linear(0): P00 = %g%+gi\n", P[0][0].real(), P[0][0].imag());
        failures++;
    }
    // Lossless slab: |T|^2 + |R|^2 = 1 for each input, read through std::complex (a wrong layout
    // would scramble real and imaginary parts and break the sum).
    const double axis[3] = {0.084, 0.979, -0.187};
    biref_slab slab = {1.775, 1.231, {axis[0], axis[1], axis[2]}, 1.15e6, 1.0};
    biref_jones T, R;
    biref_status st = biref_slab_jones(&slab, 30.0 * M_PI / 180.0, 550.0, &T, &R);
    if (st != BIREF_OK) {
        std::printf("FAIL biref_slab_jones: %s\n", biref_status_string(st));
        return 1;
    }
    for (int i = 0; i < 2; i++) {
        double sum = 0;
        for (int o = 0; o < 2; o++) sum += std::norm(T.m[i][o]) + std::norm(R.m[i][o]);
        if (std::fabs(sum - 1.0) > 1e-9) {
            std::printf("FAIL energy for input %d: %.15f\n", i, sum);
            failures++;
        }
    }
    if (!failures) std::printf("ok: C++17 header, std::complex layout, energy conserved\n");
    return failures ? 1 : 0;
}
