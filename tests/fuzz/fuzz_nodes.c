/* libFuzzer target: a finite-element node table and a boundary (text -> biref_pe_mesh), then
 * look-ups. The input is split at its first form feed (0x0c): the node table before it, the
 * boundary after it (no form feed: nodes only). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "biref/photoelastic.h"

static void check_lookup(const biref_pe_mesh *m, double x, double y)
{
    biref_pe_stress s;
    if (biref_pe_mesh_stress(m, x, y, &s) && !(isfinite(s.sxx) && isfinite(s.syy) && isfinite(s.txy)))
        __builtin_trap();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* Node tables grow triangulations superlinearly; the loader's limits are for files, and a
     * fuzzer's seconds are better spent on many small inputs. */
    if (size > 1 << 17) return 0;
    const char *text = (const char *)data;
    const char *ff = memchr(text, '\f', size);
    const size_t nodes_len = ff ? (size_t)(ff - text) : size;
    biref_pe_node_format fmt;
    biref_pe_node_format_default(&fmt);
    biref_pe_mesh *m = NULL;
    char msg[320];
    if (biref_pe_mesh_parse(text, nodes_len, &fmt, &m, msg, sizeof msg) != BIREF_OK) {
        if (m || !msg[0] || strchr(msg, '\n')) __builtin_trap(); /* no mesh, one line saying why */
        return 0;
    }
    if (ff && biref_pe_mesh_boundary_parse(m, ff + 1, size - nodes_len - 1, 1e-3, msg, sizeof msg) != BIREF_OK &&
        (!msg[0] || strchr(msg, '\n')))
        __builtin_trap();
    biref_pe_mesh_info info;
    biref_pe_mesh_get_info(m, &info);
    double b[4];
    biref_pe_mesh_bounds(m, b);
    if (info.nodes < 3 || info.triangles < 1 || !(isfinite(b[0]) && isfinite(b[1]) && isfinite(b[2]) && isfinite(b[3])) ||
        !(b[1] >= b[0] && b[3] >= b[2]))
        __builtin_trap();
    /* Corners, centre, a point outside, and a few inside. */
    check_lookup(m, b[0], b[2]);
    check_lookup(m, b[1], b[3]);
    check_lookup(m, 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]));
    check_lookup(m, b[1] + 1.0, b[3] + 1.0);
    for (int i = 1; i < 8; i++) check_lookup(m, b[0] + (b[1] - b[0]) * i / 8.0, b[2] + (b[3] - b[2]) * (8 - i) / 8.0);
    biref_pe_mesh_destroy(m);
    return 0;
}
