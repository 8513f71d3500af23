/* The dispersive-material options of the slab commands (--material, user formulas, a CSV table)
 * and the per-wavelength slab they describe. Part of cli_common.h's slab options. */
#ifndef BIREF_CLI_DISPERSION_H
#define BIREF_CLI_DISPERSION_H

#include "biref/biref.h"
#include "biref/material.h"

#define CLI_DISPERSION_OPTIONS                                                                                \
    CLI_CUSTOM("material", "NAME", OPT_SLAB_MATERIAL,                                                              \
               "a named dispersive material instead of --eta-o/--eta-e\n"                                     \
               "(biref material list); indices evaluated at each wavelength"),                                \
        CLI_CUSTOM("sellmeier-o", "B1,C1,...", OPT_SELLMEIER_O,                                              \
                   "n_o from n^2 = 1 + sum B_i L^2/(L^2 - C_i), L in um, C_i in um^2\n"                      \
                   "(1 to 4 pairs)"),                                                                        \
        CLI_CUSTOM("sellmeier-e", "B1,C1,...", OPT_SELLMEIER_E, "n_e from a Sellmeier formula (as --sellmeier-o)"), \
        CLI_CUSTOM("cauchy-o", "A,B,...", OPT_CAUCHY_O, "n_o from n = A + B/L^2 + C/L^4 + ..., L in um (2 to 5 terms)"), \
        CLI_CUSTOM("cauchy-e", "A,B,...", OPT_CAUCHY_E, "n_e from a Cauchy formula (as --cauchy-o)"),       \
        CLI_CUSTOM("dispersion-csv", "FILE", OPT_DISPERSION_CSV,                                             \
                   "n_o, n_e tabulated: rows lambda_nm,n_o,n_e (monotone cubic\n"                            \
                   "interpolation; docs/MATERIALS.md)")


#endif
