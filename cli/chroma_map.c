/* Chroma map of a rendered image (see chroma_map.h). */
#include "chroma_map.h"

#include <math.h>
#include <stdlib.h>

#include "cli_render.h"
#include "de_scale.h"

int cli_chroma_map_write(const char *cmd, const char *path, int W, int H, const float *xyz, cli_chroma_stats *stats)
{
    const size_t n = (size_t)W * H;
    unsigned char *map = calloc(n ? n * 3 : 1, 1);
    double *de = malloc(n * sizeof *de);
    if (!map || !de) {
        free(map);
        free(de);
        return cli_error(cmd, "out of memory for the chroma map"), CLI_EXIT_FAIL;
    }
    double sum = 0;
    for (size_t i = 0; i < n; i++) {
        const double c[3] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
        /* White E is (1, 1, 1) in these units, so the neutral of luminance Y is (Y, Y, Y). */
        const double grey[3] = {c[1], c[1], c[1]};
        double d = c[1] > 0 ? biref_delta_e00_xyz(c, grey) : 0.0;
        if (!isfinite(d)) d = 0.0;
        de[i] = d;
        sum += d;
        cli_de_color(d, map + 3 * i);
    }
    int rc = cli_de_map_write(cmd, path, W, H, map, "dE00 from grey:");
    if (stats) {
        qsort(de, n, sizeof *de, cli_cmp_double);
        size_t rank = (size_t)ceil(0.99 * (double)n);
        stats->mean = sum / (double)n;
        stats->p99 = de[rank > 0 ? rank - 1 : 0];
        stats->max = de[n - 1];
    }
    free(map);
    free(de);
    return rc;
}
