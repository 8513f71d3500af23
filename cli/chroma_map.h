/* How visible a render's colours are: each pixel's CIEDE2000 distance from the grey of the same
 * lightness, drawn on the one dE00 scale (de_scale.h). Makes colour bands that are real but too
 * faint to see in the sRGB image (dE00 below ~1) visible as a map. */
#ifndef BIREF_CLI_CHROMA_MAP_H
#define BIREF_CLI_CHROMA_MAP_H

#include <stddef.h>

typedef struct {
    double mean, p99, max; /* dE00 from grey over all pixels */
} cli_chroma_stats;

/* XYZ: the renderer's band-normalised floats (white E = (1,1,1)), W x H. Computed from the floats,
 * before 8-bit quantisation and clipping. Writes the map with its legend to PATH; stats may be
 * NULL. Returns 0, or CLI_EXIT_FAIL with an error printed as "biref CMD: error: ...". */
int cli_chroma_map_write(const char *cmd, const char *path, int W, int H, const float *xyz, cli_chroma_stats *stats);

#endif
