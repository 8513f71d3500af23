/* biref photoelastic: its command line (option table, parsing and the checks between options). */
#ifndef BIREF_CLI_PHOTOELASTIC_ARGS_H
#define BIREF_CLI_PHOTOELASTIC_ARGS_H

#include "cli_opts.h"
#include "photoelastic_ext.h"

/* White light has no single wavelength; fringe orders are then quoted at 550 nm (mid-band). */
#define WHITE_FRINGE_LAMBDA_NM 550.0

/* Geometry options of the presets. */
enum { PE_RADIUS, PE_LOAD, PE_STRESS, PE_WIDTH, PE_HEIGHT, PE_LENGTH, PE_DEPTH, PE_MOMENT, PE_TENSION, PE_N_GEO };

typedef struct {
    int kind; /* biref_pe_field_kind, or -1 before parsing */
    const char *grid_path, *out, *material_name;
    int json, tint, have_profile, have_view, have_lambda, material_given;
    int prefilter; /* 1: fringes averaged over each sample's footprint (--antialias prefilter) */
    double thickness_mm, n0, c_brew; /* NAN: not given */
    double dispersion_alpha; /* --dispersion-alpha; NAN: not given (the material's, 0 for every preset) */
    double fringe_value, fringe_value_nm; /* --fringe-value F@L (N/mm per fringe at L nm); NAN: not given */
    double margin_pct; /* --margin-pct; NAN: not given (5 % for finite-element sources, else the part's frame) */
    double eta_i, polarizer_deg, lambda, exposure, tilt_deg;
    double geo[PE_N_GEO]; /* NAN: not given */
    double profile[4], view[4]; /* view: xmin, xmax, ymin, ymax */
    long size, supersample, threads, samples;
    biref_pe_polariscope_kind pk;
    biref_pe_field_type ft;
    biref_pe_light_kind light;
    pe_ext ext;
} pe_args;

extern const cli_command_spec CLI_PHOTOELASTIC;

/* The specimen's name in messages and reports ("disk", ..., "grid", "nodes"). */
const char *pe_kind_name(int kind);
/* Parses and checks the command line. Returns 0, 1 after --help, or -1 after one error line. On 0
 * the caller owns a->ext (pe_ext_free). */
int pe_args_parse(int argc, char **argv, pe_args *a);
/* The geometry option's value, or dflt when it was not given. */
double pe_geo_or(const pe_args *a, int g, double dflt);

#endif
