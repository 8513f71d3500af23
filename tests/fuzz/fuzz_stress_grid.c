/* libFuzzer target: the stress-grid loader (CSV text -> biref_pe_grid), then look-ups on it. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "biref/photoelastic.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    biref_pe_grid *g = NULL;
    char msg[320];
    if (biref_pe_grid_parse((const char *)data, size, &g, msg, sizeof msg) != BIREF_OK) return 0;
    double b[4];
    int nx, ny;
    biref_pe_grid_bounds(g, b);
    biref_pe_grid_size(g, &nx, &ny);
    if (!(nx >= 2 && ny >= 2) || !isfinite(b[0]) || !isfinite(b[1]) || !isfinite(b[2]) || !isfinite(b[3]))
        __builtin_trap();
    /* Corners, centre and a point outside: interpolation stays finite inside, refuses outside. */
    const double px[] = {b[0], b[1], 0.5 * (b[0] + b[1]), b[1] + 1.0};
    const double py[] = {b[2], b[3], 0.5 * (b[2] + b[3]), b[3] + 1.0};
    for (int i = 0; i < 4; i++) {
        biref_pe_stress s;
        if (biref_pe_grid_stress(g, px[i], py[i], &s) && !(isfinite(s.sxx) && isfinite(s.syy) && isfinite(s.txy)))
            __builtin_trap();
    }
    biref_pe_grid_destroy(g);
    return 0;
}
