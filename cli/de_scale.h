/* The one colour scale of every ΔE00 map (biref diff, biref figure fig9 and aliasing), and its
 * legend, so that maps from different commands read the same. */
#ifndef BIREF_CLI_DE_SCALE_H
#define BIREF_CLI_DE_SCALE_H

#include <cairo.h>

/* Linear between stops: 0 black, 1 blue (about the threshold of visibility), 2 green, 4 red,
 * >= 8 white. */
#define CLI_DE_SCALE_MAX 8.0
#define CLI_DE_SCALE_TEXT "dE00 0 black, 1 blue (about the threshold of visibility), 2 green, 4 red, >= 8 white"

void cli_de_color(double de, unsigned char rgb[3]);

/* Height in pixels of the legend drawn by cli_de_legend. */
#define CLI_DE_LEGEND_HEIGHT 40

/* A labelled colour bar (title, then the bar from 0 to >= 8) in the box at (x, y), width w >= 260. */
void cli_de_legend(cairo_t *cr, double x, double y, double w, const char *title);

/* Writes MAP (w x h, 8-bit RGB on this scale) as a PNG with the legend strip below it, titled
 * TITLE; errors as "biref CMD: error: ..." and CLI_EXIT_FAIL, else 0. */
int cli_de_map_write(const char *cmd, const char *path, int w, int h, const unsigned char *map, const char *title);

#endif
