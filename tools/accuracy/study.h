/* The accuracy study's shared data: the compared methods, the materials, the statistics and one
 * run's configuration and results. Internal to tools/accuracy (the CLI uses accuracy.h). */
#ifndef BIREF_TOOLS_ACCURACY_STUDY_H
#define BIREF_TOOLS_ACCURACY_STUDY_H

#include <math.h>
#include <stdio.h>

#include "accuracy.h"
#include "biref/biref.h"
#include "cli_light.h"
#include "cost.h"

/* Errors are printed as "biref accuracy: error: ...". */
#define ACC_CMD "accuracy"

/* Angle ranges of the statistics: the paper says eq. 26 is accurate "except at grazing angles,
 * θ > 70°"; the expansion's criterion asks for ΔE00 <= 1 for every θ up to 85°. */
#define SPLIT_DEG 70.0
#define CRIT_DEG 85.0
#define NBIN 3 /* [0, 70], (70, 85], (85, max] */
/* Most (θ, φ) of a mm slab are nearly white (or, between crossed polarisers, nearly black), where
 * every method agrees; a second set of statistics keeps only the directions whose reference colour
 * is visibly chromatic (CIELAB chroma against white E at least this), the iridescent ones. */
#define CHROMA_MIN 5.0
#define MAX_BASE 32
#define MAX_FILE_BYTES (1 << 20)
/* The near-axis sample sets (study.c, axis_sample): AXIS_NPSI values of ψ, each with --azimuths
 * values of β, up to the ψ where the retardance reaches AXIS_RETARDANCE_NM. */
#define AXIS_NPSI 12
#define AXIS_RETARDANCE_NM 4000.0
#define AXIS_PSI_CAP_DEG 30.0

/* ------------------------------------------------------------------------------------------ */
/* Methods compared                                                                            */
/* ------------------------------------------------------------------------------------------ */

/* The compared methods (each against the reference), then the comparisons with the denser check
 * integration: ref-vs-check tests the reference itself; analytic-vs-check and expansion-vs-check
 * tell a method's error from the reference's. M_PAIRS: the analytic-pairs method (eq. 26 plus
 * transmission's sibling and entry pairs, beyond the paper; docs/PHYSICS.md §4). */
enum {
    M_ANALYTIC,
    M_PAIRS,
    M_EXPANSION,
    M_N3,
    M_N8,
    M_N16,
    M_N32,
    M_N64,
    M_N128,
    M_GT,
    NCMP,
    M_REF_CHECK = NCMP,
    M_AN_CHECK,
    M_EX_CHECK,
    NM
};
#define NNUM (M_N128 - M_N3 + 1)
extern const char *const ACC_METHOD_KEY[NM];
extern const int ACC_NUMERIC_N[NNUM];
extern const char *const ACC_TR[2]; /* "T", "R" */

typedef struct {
    char name[64];
    int base;         /* index of the base material for a sweep variant, -1 for a base */
    double delta_eps; /* eps_e - eps_o */
    biref_slab slab;  /* axis normalised */
    cli_light light;
} acc_material;

typedef struct {
    double sum, max;
    long n, over1; /* over1: samples with ΔE00 > 1, "perceptible" */
} acc_stat;

#define AXIS_SETS 2

typedef struct {
    acc_stat (*theta)[NM][2]; /* [ntheta]: over azimuths */
    double (*phi0)[NM][2];    /* [ntheta]: the unrotated axis (NaN where not computed) */
    acc_stat bin[NBIN][NM][2];          /* over (θ, φ) of each angle range */
    acc_stat col[NBIN][NM][2];          /* the same, chromatic reference colours only (CHROMA_MIN) */
    acc_stat axis[AXIS_SETS][NM][2];     /* the near-axis sample sets (axis_sample), [down, up legs] */
    acc_stat axis_col[AXIS_SETS][NM][2]; /* and their chromatic parts */
    acc_stat axis_crit[AXIS_SETS][NM][2]; /* near-axis samples with θ <= CRIT_DEG */
    double axis_psi_max_deg;
    long axis_valid[AXIS_SETS];          /* near-axis samples reachable within theta_max */
    double elapsed_s;
} acc_result;

typedef struct {
    double theta_max_deg, theta_step_deg, check_step_deg;
    int ntheta, nphi, kcheck;
    int samples_ref, samples_check;
    biref_spectral_config scfg;
    int threads;
    const char *materials_arg;
    int nmat, nbase;
    acc_material *mat;
    acc_result *res;
    double total_s;
    int sweep_done; /* 0 with --cost-only */
    /* --cost: rows in the order of the compared methods (M_ANALYTIC .. M_GT) */
    int have_cost;
    acc_cost_opts cost_opts;
    acc_cost_time cost_prepare;
    acc_cost_row cost[NCMP];
    acc_cost_row cost_band[2][2]; /* [θ 0–70°, 70–85°][analytic, expansion] */
    int cost_pool_n, cost_band_n[2]; /* states timed (0: range empty) */
    double cost_s;
} acc_run;

typedef struct {
    const biref_spectral *sp;
    const biref_integrator *method[NCMP]; /* the compared methods; the expansion with its defaults */
    const biref_integrator *ref, *check;   /* numeric, --reference-samples and --samples-check */
} acc_plans;


static inline void stat_add(acc_stat *s, double v)
{
    s->sum += v;
    if (v > s->max) s->max = v;
    s->n++;
    s->over1 += v > 1.0;
}

static inline void stat_merge(acc_stat *a, const acc_stat *b)
{
    a->sum += b->sum;
    if (b->n && b->max > a->max) a->max = b->max;
    a->n += b->n;
    a->over1 += b->over1;
}

static inline double stat_mean(const acc_stat *s) { return s->n ? s->sum / (double)s->n : NAN; }
static inline double stat_max(const acc_stat *s) { return s->n ? s->max : NAN; }

/* The angle range (NBIN) of an angle of the grid. */
static inline int bin_of(double theta_deg)
{
    return theta_deg <= SPLIT_DEG + 1e-9 ? 0 : theta_deg <= CRIT_DEG + 1e-9 ? 1 : 2;
}

/* Progress of the sweep: evaluated points over all materials, shown by bar (cli_progress.h). */
typedef struct {
    biref_progress_bar *bar;
    long done, total;
} acc_progress;

/* materials.c: the paper's fig. 9 materials (returns their number, 3), or a --materials file. */
int acc_builtin_fig9(acc_material *m);
int acc_load_materials(const char *path, acc_material *m, int cap, int *n);

/* study.c */
double acc_axis_psi_max(const acc_material *m);
/* ΔE00 of every method over the (θ, φ) grid and the near-axis sets of material mi. */
int acc_run_material(acc_run *run, const acc_plans *pl, int mi, acc_progress *pg);
/* --cost: the cost per shading sample of every method on the grid's states. */
int acc_measure_cost(acc_run *run, const acc_plans *pl);

/* criteria.c: the two acceptance criteria the study reports. */

/* Method k (the analytic method, or analytic-pairs) against the reference, θ 0–70° over all
 * azimuths: mean ΔE00 <= 1 and max <= 4, the paper's envelope (transmission w = 0 or reflection
 * w = 1). */
int acc_envelope_pass(const acc_result *r, int k, int w);

/* The expansion's criteria. (a) for each base material and every θ in 0–85°, the expansion
 * within ΔE00 <= EXPANSION_DE_MAX of the reference (grid and near-axis samples), at no more than
 * EXPANSION_COST_RATIO times the analytic method's cost per shading sample; (b) at equal cost, the
 * expansion's ΔE00 at least EXPANSION_GAIN times below numeric integration's. */
#define EXPANSION_DE_MAX 1.0
#define EXPANSION_COST_RATIO 3.0
#define EXPANSION_GAIN 5.0

typedef struct {
    /* (a) per base material, [T, R] */
    double grid_max[MAX_BASE][2], axis_max[MAX_BASE][2], theta_of_max[MAX_BASE][2];
    int pass_de[2]; /* every material, grid and near-axis */
    double ns_an, ns_ex, ratio, ns_an_alone, ns_ex_alone, ratio_alone;
    int pass_cost, pass_a;
    /* (b) numeric methods bracketing the expansion's cost (with prepare): lo cheaper, hi not cheaper */
    int lo, hi;
    acc_stat pooled[NCMP][2]; /* grid θ <= 85°, all base materials */
    double gain_mean[2], gain_max[2]; /* numeric hi / expansion */
    int pass_b;
} acc_expansion_verdict;

void acc_expansion_verdict_eval(const acc_run *run, acc_expansion_verdict *e);

/* report_md.c, report_json.c, figures.c: the outputs. */
void acc_write_markdown(FILE *f, const acc_run *run);
/* The angle range of a cost breakdown band: 0 = [0, 70°], 1 = (70°, 85°], clipped to the grid. */
void acc_band_range(const acc_run *run, int b, double r[2]);
void acc_write_csv(FILE *f, const acc_run *run);
/* NULL when out of memory. */
struct cJSON *acc_build_json(const acc_run *run);
int acc_write_plots(const acc_run *run, const char *dir);

#endif
