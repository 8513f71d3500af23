/* biref photoelastic: stress from finite-element nodes, full-field maps, float pictures, phase-
 * stepped image sets, colour key and scale bar (docs/PHOTOELASTICITY.md). photoelastic_args.c
 * parses the options and hands these to pe_ext_option. */
#ifndef BIREF_CLI_PHOTOELASTIC_EXT_H
#define BIREF_CLI_PHOTOELASTIC_EXT_H

#include <cjson/cJSON.h>
#include "cli_common.h"

enum {
    OPT_PE_NODES = 3100,
    OPT_PE_COLUMNS,
    OPT_PE_LENGTH_UNIT,
    OPT_PE_STRESS_UNIT,
    OPT_PE_BOUNDARY,
    OPT_PE_MAP,
    OPT_PE_PFM,
    OPT_PE_PHASE_STEPS,
    OPT_PE_KEY,
    OPT_PE_SCALE_BAR,
    OPT_PE_FORMAT,
    OPT_PE_FEA,
    OPT_PE_FEA_FORMAT,
    OPT_PE_FEA_STRESS
};

typedef struct {
    const char *nodes_path, *boundary_path;
    const char *fea_path, *fea_tensor; /* --fea FILE, --fea-stress NAME */
    int fea_format;                    /* PE_FEA_*: from --fea-format or the extension */
    char fea_used[96];                 /* the stress arrays or components read */
    biref_pe_node_format fmt;
    char names[5][64];
    int have_columns, have_units;
    int map;         /* biref_pe_map_kind, or -1 */
    int pfm;         /* pictures as float PFM */
    int phase_steps; /* 0, 4 or 6 */
    int key, scale_bar;
    biref_pe_mesh *mesh;
} pe_ext;

enum { PE_FEA_AUTO, PE_FEA_FRD, PE_FEA_VTU, PE_FEA_VTK };

/* Everything the extra outputs need from the command. */
typedef struct {
    const biref_pe_setup *setup;
    const biref_spectral *sp;
    const biref_pe_field *field;
    const biref_pe_image_opts *io; /* width, height set */
    const char *out;
    double exposure;
    double lambda_N;   /* wavelength of the fringe orders */
    const double *tint; /* mono tint (XYZ), 3 */
    cJSON *root;       /* JSON report or NULL */
    double polarizer;  /* rad, for the key's colours in a plane polariscope */
} pe_ext_ctx;

void pe_ext_init(pe_ext *e);
void pe_ext_free(pe_ext *e);
/* Parses the extension option with this code (OPT_PE_*): 1 handled, 0 not an extension
 * option, -1 error printed. */
int pe_ext_option(pe_ext *e, int code, const char *arg);
/* Consistency of the extension options with the command's (light, output); -1 error printed. */
int pe_ext_check(const pe_ext *e, int have_kind, int mono, int have_out, int have_tilt);
/* Loads the nodes (and boundary) into a field; returns a CLI exit code. */
int pe_ext_nodes_field(pe_ext *e, biref_pe_field *f, double h);
/* 1 if -o is a map, a phase-stepped set or a PFM picture rather than a PNG. */
int pe_ext_owns_output(const pe_ext *e);
/* Writes map / phase steps / PFM picture; returns a CLI exit code. */
int pe_ext_write(const pe_ext *e, const pe_ext_ctx *c);
/* The PNG picture, with --key and --scale-bar drawn by cairo if asked; returns a CLI exit code. */
int pe_ext_write_png(const pe_ext *e, const pe_ext_ctx *c, const unsigned char *rgb);

/* Adds the node counts (rows, distinct nodes, triangles, boundary polygons) to a JSON report. */
void pe_ext_json(const pe_ext *e, cJSON *root);

int cmd_photoelastic_demodulate(int argc, char **argv);
/* biref photoelastic calibrate; biref photoelastic demodulate --tfp (photoelastic_tfp.c). */
int cmd_photoelastic_calibrate(int argc, char **argv);
int cmd_photoelastic_tfp(int argc, char **argv);

#endif
