/* General polarisation options (beyond the paper's s/p model): incident light as a Stokes vector
 * or a fully polarised state, analyzer linear at any angle or circular. Angles are measured in
 * the s/p plane from s towards p, in degrees. */
#ifndef BIREF_CLI_POLARIZER_H
#define BIREF_CLI_POLARIZER_H

#include <complex.h>

#include "biref/biref.h"
#include "cli_opts.h"

/* "linear:DEG", "circular:+1" / "circular:-1" (or "circular:left"/"circular:right" are not
 * accepted: handedness is the sign of S3, see docs/PHYSICS.md §5) -> Stokes vector. */
int cli_parse_polarizer_state(const char *cmd, const char *opt, const char *text, double stokes[4]);
/* "S0,S1,S2,S3", physical (S0 >= 0, |S| <= S0). */
int cli_parse_stokes(const char *cmd, const char *opt, const char *text, double stokes[4]);
/* "linear:DEG" or "circular:+1|-1" -> analyzer projector P[in][out]. Returns 1 if text is one of
 * these general forms, 0 if it is not (the caller tries its simple forms), -1 on error. */
int cli_parse_general_analyzer(const char *cmd, const char *opt, const char *text, double complex P[2][2]);

/* --order N (0 .. BIREF_EXPANSION_MAX_ORDER) and --tolerance E (0 < E < 1) of the path-group
 * expansion, shared by biref spectrum and biref render. Return 0 or print one error. */
int cli_parse_expansion_order(const char *cmd, const char *text, biref_expansion_opts *o);
int cli_parse_expansion_tolerance(const char *cmd, const char *text, biref_expansion_opts *o);
/* The two as entries of an option table (cli_opts.h), handled by the command with these codes. */
#define CLI_EXPANSION_OPTIONS(ORDER_CODE, TOLERANCE_CODE)                                     \
    CLI_CUSTOM("order", "N", ORDER_CODE,                                                      \
               "expansion: every pair of path groups up to order N interferes,\n"             \
               "the rest adds incoherently, 0-8 (default adaptive)"),                         \
        CLI_CUSTOM("tolerance", "E", TOLERANCE_CODE,                                          \
                   "expansion: adaptive orders' target relative error (default 1e-3;\n"       \
                   "docs/PHYSICS.md section 5)")

#endif
