/* Cost per shading sample of the spectral integration methods, for `biref accuracy --cost`.
 *
 * A shading sample is what a renderer computes per slab hit: biref_slab_prepare for one angle
 * (modes, Fresnel coefficients) and one spectral integration giving the band-normalised XYZ of
 * all four input/output polarisation pairs in transmission and reflection (one biref_spectrum).
 * Every method runs on the same pool of slab states, in the same order, on the calling thread. */
#ifndef BIREF_TOOLS_ACCURACY_COST_H
#define BIREF_TOOLS_ACCURACY_COST_H

#include "biref/biref.h"
#include "cli_progress.h"

typedef struct {
    double ns_median, ns_min; /* per sample, over the timed runs */
    double cpu_share;         /* lowest (thread CPU time / wall time) over the runs */
    long iters;               /* samples per timed run */
} acc_cost_time;

typedef struct {
    const char *name;
    const biref_integrator *integrator; /* biref_integrate_spectrum per sample */
    acc_cost_time alone;            /* on states prepared beforehand */
    acc_cost_time with_prepare;     /* biref_slab_prepare + integration */
} acc_cost_row;

typedef struct {
    double min_time;   /* seconds per timed run after calibration */
    int runs;          /* timed runs per case; the median is reported */
    long fixed_iters;  /* > 0: one run of exactly this many samples, no calibration (callgrind) */
    biref_progress_bar *progress; /* a line per case on stderr, or NULL */
} acc_cost_opts;

/* Slab states to time: n slabs, each with its own angle of incidence (radians). */
typedef struct {
    const biref_slab *slab;
    const double *theta;
    int n;
} acc_cost_pool;

/* Times biref_slab_prepare alone (*prepare, skipped if NULL), then each row alone and with the prepare, in that
 * order (the order of the calls to the timed loop, which `--cost-iterations` runs under callgrind
 * rely on). Returns 0, or -1 if a state could not be prepared (one error line printed). */
int acc_cost_measure(const acc_cost_pool *pool, const acc_cost_opts *o, acc_cost_time *prepare,
                     acc_cost_row *rows, int nrows);

#endif
