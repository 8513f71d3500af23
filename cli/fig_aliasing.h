/* biref figure aliasing: plain, prefiltered and super-sampled renders of scenes made to alias,
 * against a 32x32 super-sampled reference (docs/ANTIALIASING.md). */
#ifndef BIREF_CLI_FIG_ALIASING_H
#define BIREF_CLI_FIG_ALIASING_H

#include "biref/biref.h"

/* Writes DIR/aliasing.png and DIR/aliasing.csv; scenes are read from SCENES (fig9c.json and
 * aliasing/thick_grazing.json). threads 0 = the OpenMP default. Returns a CLI exit status. */
int fig_aliasing(const biref_spectral *sp, const char *dir, const char *scenes, int quick, int threads);

#endif
