/* Shared command-line plumbing: strict number parsing, one-line errors, slab options. */
#ifndef BIREF_CLI_COMMON_H
#define BIREF_CLI_COMMON_H

#include <getopt.h>
#include <stdio.h>

#include "biref/biref.h"
#include "cli_dispersion.h"
#include "cli_opts.h"
#include "cli_progress.h"

/* Exit codes: 0 success, 1 runtime failure (I/O, numerics), 2 bad usage or bad input. */
enum { CLI_EXIT_OK = 0, CLI_EXIT_FAIL = 1, CLI_EXIT_USAGE = 2 };

/* Prints "biref CMD: error: ..." as one line on stderr. */
void cli_error(const char *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* 1 if TEXT is a whole decimal number: [+-]digits[.digits][e[+-]digits] (integer: [+-]digits),
 * no blanks, no hexadecimal, no inf or nan. */
int cli_number_syntax_ok(const char *text, int integer);
/* Strict parsers: the whole string must be a finite decimal number. Return 0 on success. */
int cli_parse_double(const char *cmd, const char *opt, const char *text, double *out);
int cli_parse_int(const char *cmd, const char *opt, const char *text, long lo, long hi, long *out);
/* Parses n comma-separated finite numbers ("a,b,c"). */
int cli_parse_list(const char *cmd, const char *opt, const char *text, double *out, int n);

/* qsort's comparison for doubles, ascending. */
int cli_cmp_double(const void *a, const void *b);

/* A Jones matrix and its power fractions as a table on stdout (rows: input s/p, columns: output). */
void cli_print_jones_table(const char *title, const biref_jones *J, double P[2][2]);

/* Options shared by every command that describes one slab at one angle. The indices are either
 * constants (--eta-o, --eta-e: material NULL after cli_slab_opts_finish) or a dispersive material
 * (--material, --dispersion-csv, or a Sellmeier/Cauchy formula per index; cli_dispersion.h). */
typedef struct {
    biref_slab slab;
    double theta_deg;
    int have_eta_o, have_eta_e, have_axis, have_thickness, have_theta;
    const char *index_source[2]; /* the option that gave n_o / n_e (repeats are errors) */
    const char *material_name, *dispersion_csv;
    biref_index_formula formula[2];
    int have_formula[2];
    const biref_material *material; /* after finish: NULL for constant indices */
    biref_material *owned_material;
} cli_slab_opts;

enum {
    OPT_ETA_O = 1000,
    OPT_ETA_E,
    OPT_AXIS,
    OPT_THICKNESS_UM,
    OPT_THICKNESS_MM,
    OPT_THICKNESS_NM,
    OPT_THETA_DEG,
    OPT_ETA_I,
    OPT_SLAB_MATERIAL,
    OPT_SELLMEIER_O,
    OPT_SELLMEIER_E,
    OPT_CAUCHY_O,
    OPT_CAUCHY_E,
    OPT_DISPERSION_CSV,
    OPT_SLAB_LAST
};

/* The slab options as entries of an option table (cli_opts.h); the command's handler passes
 * their codes to cli_slab_opts_handle. */
#define CLI_SLAB_OPTIONS                                                                                      \
    CLI_CUSTOM("eta-o", "N", OPT_ETA_O, "ordinary refractive index (required unless a material is given)"),                             \
        CLI_CUSTOM("eta-e", "N", OPT_ETA_E, "extraordinary refractive index (likewise)"),                    \
        CLI_CUSTOM("axis", "a,b,c", OPT_AXIS,                                                                \
                   "optic axis in the slab frame, normalised by biref (required);\n"                         \
                   "frame: surface y = 0, slab below, light in the YZ plane"),                               \
        CLI_CUSTOM("thickness-um", "D", OPT_THICKNESS_UM, "slab thickness in micrometres (required, or one of:)"), \
        CLI_CUSTOM("thickness-mm", "D", OPT_THICKNESS_MM, "slab thickness in millimetres"),                 \
        CLI_CUSTOM("thickness-nm", "D", OPT_THICKNESS_NM, "slab thickness in nanometres"),                  \
        CLI_CUSTOM("theta-deg", "A", OPT_THETA_DEG, "angle of incidence in degrees, 0 <= A < 90 (default 0)"), \
        CLI_CUSTOM("eta-i", "N", OPT_ETA_I, "index of the surrounding medium, both sides (default 1)"),       \
        CLI_DISPERSION_OPTIONS


/* The slab options that exclude each other, for a command's cli_command_spec.exclusive. */
#define CLI_SLAB_EXCLUSIVE "thickness-um thickness-mm thickness-nm"

void cli_slab_opts_init(cli_slab_opts *o);
/* Frees the material a finished option set may own. */
void cli_slab_opts_free(cli_slab_opts *o);
/* Handles one slab option; returns 1 if handled, 0 if the code is not a slab option, -1 on error. */
int cli_slab_opts_handle(const char *cmd, cli_slab_opts *o, int code, const char *arg);
/* Checks presence and physical validity; prints one error line and returns -1 on failure. */
int cli_slab_opts_finish(const char *cmd, cli_slab_opts *o);

/* The dispersive part of the slab options (cli_dispersion.c), used by the three above. */
int cli_dispersion_handle(const char *cmd, cli_slab_opts *o, int code, const char *arg);
int cli_dispersion_finish(const char *cmd, cli_slab_opts *o);
/* The option that made the slab dispersive (before or after finish), NULL for constant indices. */
const char *cli_slab_dispersion_option(const cli_slab_opts *o);
/* The slab at one wavelength: the constant indices, or the material's there (one error line and
 * -1 where it is unphysical; a warning line when the wavelength is extrapolated). */
int cli_slab_at(const char *cmd, const cli_slab_opts *o, double lambda_nm, biref_slab *out);
/* A dispersive material over a band: one error line and -1 where it is unphysical (a pole,
 * n^2 <= 1), a warning line for the extrapolated part; 0 for constant indices. */
int cli_slab_check_band(const char *cmd, const cli_slab_opts *o, double lo_nm, double hi_nm);

/* Reports an unknown option or a missing argument detected by getopt_long (opterr = 0). */
void cli_getopt_error(const char *cmd, int code, char *const argv[]);

#endif
