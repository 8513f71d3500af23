/* The accuracy study of the spectral integration methods (`biref accuracy`): CIEDE2000 of every
 * method against an alias-free reference over angles of incidence and azimuths of the optic axis,
 * optionally the cost per shading sample and two figures; reports in Markdown, CSV and JSON.
 * A research tool kept out of the library and the CLI: the CLI parses the options into an
 * acc_options and calls acc_study. Method and results: docs/ACCURACY.md. */
#ifndef BIREF_TOOLS_ACCURACY_H
#define BIREF_TOOLS_ACCURACY_H

#include "biref/biref.h"
#include "cost.h"

#define MAX_SWEEP 16
#define MAX_SAMPLES (1 << 24)
/* The reference must resolve the Fabry–Pérot ripple of the thickest slab: for fig. 9b (3.5 mm,
 * η 1.5) its period λ²/(2ηd) is 0.014 nm at 380 nm and 0.029 nm at 550 nm; 16384 samples over
 * 380-700 nm are 0.0195 nm apart (aliased), 262144 are 0.0012 nm apart (11 per period or more). */
#define DEFAULT_REFERENCE_SAMPLES 262144
/* The check integration costs 4x the reference; on the near-axis sets it runs on every
 * AXIS_CHECK_STRIDE-th sample (every ψ ring, a quarter of the directions around the axis). */
#define AXIS_CHECK_STRIDE 4

typedef struct {
    const char *materials;   /* "fig9" or a JSON file */
    double sweep[MAX_SWEEP]; /* Δε values applied to every material */
    int nsweep;
    double theta_max_deg, theta_step_deg, check_step_deg;
    int nphi;                      /* azimuths */
    int samples_ref, samples_check; /* samples_check < 0: 4x the reference */
    biref_spectral_config scfg;
    int cost, cost_only;
    acc_cost_opts cost_opts;
    long threads; /* 0: OpenMP's default */
    int progress; /* unused: --progress and --quiet are taken for every command (cli_progress.h) */
    const char *csv_path, *md_path, *plot_dir;
    int json;
    /* --material: the dispersive study (dispersion.c) of one plate of a catalogue material */
    const char *material;
    double thickness_um; /* 0: the study's plate of that material */
    int theta_max_given, theta_step_given;
    /* derived by acc_options_finish */
    int ntheta, kcheck;
} acc_options;

void acc_options_default(acc_options *o);
/* Checks the options against each other and derives the rest; one error line and -1 if they do
 * not fit together. */
int acc_options_finish(acc_options *o);
/* Runs the study and writes its reports. Returns a CLI exit code (0 ok, 1 failure, 2 bad input),
 * after one error line on stderr unless 0. */
int acc_study(const acc_options *o);
/* The closed-form methods with dispersion against the dispersive ground truth, one plate
 * (o->material, o->thickness_um); a CLI exit code. docs/ACCURACY-DISPERSION.md. */
int acc_dispersion_study(const acc_options *o);
/* The thickness of the study's plate of a material (µm), 0 when it has none. */
double acc_dispersion_default_thickness_um(const char *material);

#endif
