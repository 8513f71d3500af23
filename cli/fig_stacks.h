/* Figures of stacks of layers (cli/fig_stacks.c, cli/fig_thickness.c); each returns an exit code. */
#ifndef BIREF_CLI_FIG_STACKS_H
#define BIREF_CLI_FIG_STACKS_H

#include "fig_common.h"

/* Lyot and folded Šolc transmission spectra (examples/stacks/ under `examples`). */
int fig_filters(const fig_ctx *c, const char *examples);
/* Its inputs, checked before any figure is computed: 0, or -1 after one error line. */
int fig_filters_check(const char *examples);
/* Cellophane patches between crossed polarizers: a stained-glass picture. */
int fig_tape_art(const fig_ctx *c);
/* A disk whose stress varies through its thickness in a dark-field polariscope. */
int fig_stress_thickness(const fig_ctx *c);

#endif
