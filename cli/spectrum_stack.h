/* biref spectrum --stack: the colours of a stack file (cli/spectrum_stack.c). */
#ifndef BIREF_CLI_SPECTRUM_STACK_H
#define BIREF_CLI_SPECTRUM_STACK_H

#include "biref/biref.h"

typedef struct {
    const char *file;
    double theta_deg;
    biref_spectral_config cfg;
    biref_stack_spectrum_opts opts;
    biref_light light;
    double stokes[4];
    const char *pol_name, *an_name;
    int json;
} spectrum_stack_args;

/* Loads, integrates and prints; returns the exit code (one error line printed unless OK). */
int spectrum_stack_run(const spectrum_stack_args *a);

#endif
