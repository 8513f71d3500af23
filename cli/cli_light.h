/* Light model options shared by `biref spectrum` and `biref accuracy`: incident polarisation
 * fractions, analyzer, spectral band and colour-matching functions, and a terminal swatch. */
#ifndef BIREF_CLI_LIGHT_H
#define BIREF_CLI_LIGHT_H

#include <stdio.h>

#include "biref/biref.h"

/* Incoherent incident light (fractions of s and p, summing to 1) seen through an analyzer
 * that passes mask[s], mask[p] (each 0 or 1) — the paper's light model (fig. 9). */
typedef struct {
    double w_in[2];
    double mask[2];
} cli_light;

/* Unpolarized input, no analyzer. */
void cli_light_default(cli_light *l);

/* "s", "p", "unpolarized" or "S,P" (two non-negative weights, not both zero; normalised to
 * sum 1 so that "3,1" and "0.75,0.25" mean the same light). Returns 0 or prints one error. */
int cli_parse_polarization(const char *cmd, const char *opt, const char *text, double w_in[2]);
/* "none", "s" or "p". */
int cli_parse_analyzer(const char *cmd, const char *opt, const char *text, double mask[2]);

/* Inverse names: "s", "p", "unpolarized" or "S,P" with %.6g (buf needs >= 40 bytes); and
 * "none", "s", "p". */
const char *cli_polarization_name(const double w_in[2], char *buf, size_t len);
const char *cli_analyzer_name(const double mask[2]);

/* "MIN,MAX" in nm: finite, 0 < MIN < MAX. */
int cli_parse_range_nm(const char *cmd, const char *opt, const char *text, double range[2]);

/* A two-character-cell block in 24-bit ANSI colour, encoded sRGB clamped to [0, 1] (the
 * terminal cannot show out-of-gamut colours). Callers only use it when stdout is a tty. */
void cli_print_swatch(FILE *f, const double srgb[3]);

#endif
