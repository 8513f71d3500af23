/* biref accuracy: CIEDE2000 of the spectral integration methods against an alias-free reference,
 * as a function of the angle of incidence, for the paper's fig. 9 materials (and optionally a fig.
 * 7-like sweep over Δε); optionally their cost per shading sample and two figures.
 *
 * Methods compared: the paper's analytic approximation (eq. 26), the exact integral of the
 * path-group expansion (docs/PHYSICS.md §5, default options), numeric integration with 3 to 128
 * samples, and the paper's ground truth (numeric, 16384 samples). The reference is numeric
 * integration with --reference-samples (default 262144) samples, not the ground truth: the 3.5 mm
 * slab of fig. 9b has a Fabry–Pérot ripple with a period of ~0.029 nm, which 16384 samples over
 * 380–700 nm (0.0195 nm apart) alias. Whether the reference itself is converged is measured on a
 * subset of the directions against 4x as many samples (ref-vs-check).
 *
 * Why azimuths: a millimetre slab at one fixed optic axis has a retardance of tens of µm, so
 * its colour integrates to almost white and any method looks accurate. The colours of fig. 9
 * come from the pixels whose rays, seen in the slab's own frame, travel close to the optic
 * axis. In the paper's frame the plane of incidence is always YZ, so a ray arriving with
 * azimuth φ about the slab normal sees the slab's axis rotated about y by that azimuth:
 * A' = (cos φ A_x + sin φ A_z, A_y, −sin φ A_x + cos φ A_z). Sampling φ over a full turn
 * (where its sign does not matter) covers the directions a rendered slab shows; statistics are
 * taken over (θ, φ). */
#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "accuracy_cost.h"
#include "accuracy_plot.h"
#include "cli_common.h"
#include "cli_light.h"
#include "commands.h"
#include "fig_plot.h"
#include "json_out.h"

static const char *const CMD = "accuracy";

/* Angle ranges of the statistics: the paper says eq. 26 is accurate "except at grazing angles,
 * θ > 70°"; issue #5 asks the expansion to stay within ΔE00 <= 1 for every θ up to 85°. */
#define SPLIT_DEG 70.0
#define CRIT_DEG 85.0
#define NBIN 3 /* [0, 70], (70, 85], (85, max] */
/* Most (θ, φ) of a mm slab are nearly white (or, between crossed polarisers, nearly black), where
 * every method agrees; a second set of statistics keeps only the directions whose reference colour
 * is visibly chromatic (CIELAB chroma against white E at least this), the iridescent ones. */
#define CHROMA_MIN 5.0
#define MAX_BASE 32
#define MAX_SWEEP 16
#define MAX_SAMPLES (1 << 24)
#define MAX_FILE_BYTES (1 << 20)
/* The reference must resolve the Fabry–Pérot ripple of the thickest slab: for fig. 9b (3.5 mm,
 * η 1.5) its period λ²/(2ηd) is 0.014 nm at 380 nm and 0.029 nm at 550 nm; 16384 samples over
 * 380-700 nm are 0.0195 nm apart (aliased), 262144 are 0.0012 nm apart (11 per period or more). */
#define DEFAULT_REFERENCE_SAMPLES 262144
/* The check integration costs 4x the reference; on the near-axis sets it runs on every
 * AXIS_CHECK_STRIDE-th sample (every ψ ring, a quarter of the directions around the axis). */
#define AXIS_CHECK_STRIDE 4

/* ------------------------------------------------------------------------------------------ */
/* Methods compared                                                                            */
/* ------------------------------------------------------------------------------------------ */

/* The compared methods (each against the reference), then the comparisons with the denser check
 * integration: ref-vs-check tests the reference itself; analytic-vs-check and expansion-vs-check
 * tell a method's error from the reference's. */
enum {
    M_ANALYTIC,
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
static const char *const METHOD_KEY[NM] = {"analytic",   "expansion",  "numeric-3",    "numeric-8",
                                           "numeric-16", "numeric-32", "numeric-64",   "numeric-128",
                                           "ground-truth", "ref-vs-check", "analytic-vs-check",
                                           "expansion-vs-check"};
static const int NUMERIC_N[NNUM] = {3, 8, 16, 32, 64, 128};
static const char *const TR[2] = {"T", "R"};

/* ------------------------------------------------------------------------------------------ */
/* Materials                                                                                   */
/* ------------------------------------------------------------------------------------------ */

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

static void set_material(acc_material *m, const char *name, double eta_o, double eta_e, double ax, double ay,
                         double az, double d_mm, double ws, double wp, const char *analyzer)
{
    memset(m, 0, sizeof *m);
    snprintf(m->name, sizeof m->name, "%s", name);
    m->base = -1;
    m->slab = (biref_slab){eta_o, eta_e, {ax, ay, az}, d_mm * 1e6, 1.0};
    m->light.w_in[0] = ws;
    m->light.w_in[1] = wp;
    m->light.mask[0] = strcmp(analyzer, "p") != 0; /* "none" passes both */
    m->light.mask[1] = strcmp(analyzer, "s") != 0;
}

/* The paper's fig. 9 (a, b, c), constants and light exactly as in its captions. */
static int builtin_fig9(acc_material *m)
{
    set_material(&m[0], "a", 1.40, 1.38, -0.54, 0.80, 0.27, 1.25, 0.75, 0.25, "none");
    set_material(&m[1], "b", 1.50, 1.51, 0.25, 0.97, 0.00, 3.50, 0.50, 0.50, "none");
    set_material(&m[2], "c", 1.775, 1.231, 0.084, 0.979, -0.187, 1.15, 0.02, 0.98, "s");
    return 3;
}

static int json_number(const cJSON *o, const char *key, double *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!v) return 0;
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble)) return -1;
    *out = v->valuedouble;
    return 1;
}

/* One material from a JSON object; errors name the file and the material's position. */
static int parse_material(const char *path, int idx, const cJSON *o, acc_material *m)
{
    char where[600];
    snprintf(where, sizeof where, "%s: material %d", path, idx + 1);
    if (!cJSON_IsObject(o)) return cli_error(CMD, "%s: expected an object", where), -1;
    memset(m, 0, sizeof *m);
    m->base = -1;
    m->slab.eta_i = 1.0;
    cli_light_default(&m->light);
    const cJSON *name = cJSON_GetObjectItemCaseSensitive(o, "name");
    if (!cJSON_IsString(name) || !name->valuestring[0] || strlen(name->valuestring) > 40)
        return cli_error(CMD, "%s: \"name\" must be a string of 1-40 characters", where), -1;
    snprintf(m->name, sizeof m->name, "%s", name->valuestring);
    static const char *const req[2] = {"eta_o", "eta_e"};
    double *dst[2] = {&m->slab.eta_o, &m->slab.eta_e};
    for (int k = 0; k < 2; k++) {
        int r = json_number(o, req[k], dst[k]);
        if (r <= 0) return cli_error(CMD, "%s: \"%s\" must be a finite number", where, req[k]), -1;
    }
    if (json_number(o, "eta_i", &m->slab.eta_i) < 0)
        return cli_error(CMD, "%s: \"eta_i\" must be a finite number", where), -1;
    const cJSON *axis = cJSON_GetObjectItemCaseSensitive(o, "axis");
    if (!cJSON_IsArray(axis) || cJSON_GetArraySize(axis) != 3)
        return cli_error(CMD, "%s: \"axis\" must be an array of 3 numbers", where), -1;
    for (int k = 0; k < 3; k++) {
        const cJSON *v = cJSON_GetArrayItem(axis, k);
        if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble))
            return cli_error(CMD, "%s: \"axis\" must be an array of 3 numbers", where), -1;
        m->slab.axis[k] = v->valuedouble;
    }
    static const char *const thick[3] = {"thickness_nm", "thickness_um", "thickness_mm"};
    static const double scale[3] = {1.0, 1e3, 1e6};
    int have = 0;
    for (int k = 0; k < 3; k++) {
        double v;
        int r = json_number(o, thick[k], &v);
        if (r < 0) return cli_error(CMD, "%s: \"%s\" must be a finite number", where, thick[k]), -1;
        if (r > 0) {
            have++;
            m->slab.thickness_nm = v * scale[k];
        }
    }
    if (have != 1)
        return cli_error(CMD, "%s: give exactly one of thickness_nm, thickness_um, thickness_mm", where), -1;
    const cJSON *pol = cJSON_GetObjectItemCaseSensitive(o, "polarization");
    char opt[700];
    if (pol) {
        snprintf(opt, sizeof opt, "%s: \"polarization\"", where);
        if (!cJSON_IsString(pol)) return cli_error(CMD, "%s: must be a string such as \"0.75,0.25\"", opt), -1;
        if (cli_parse_polarization(CMD, opt, pol->valuestring, m->light.w_in)) return -1;
    }
    const cJSON *an = cJSON_GetObjectItemCaseSensitive(o, "analyzer");
    if (an) {
        snprintf(opt, sizeof opt, "%s: \"analyzer\"", where);
        if (!cJSON_IsString(an)) return cli_error(CMD, "%s: must be \"none\", \"s\" or \"p\"", opt), -1;
        if (cli_parse_analyzer(CMD, opt, an->valuestring, m->light.mask)) return -1;
    }
    char msg[200];
    if (biref_slab_check(&m->slab, msg, sizeof msg) != BIREF_OK) return cli_error(CMD, "%s: %s", where, msg), -1;
    return 0;
}

/* --materials FILE: {"materials": [...]} or a bare array of material objects. */
static int load_materials(const char *path, acc_material *m, int cap, int *n)
{
    FILE *f = fopen(path, "rb");
    if (!f) return cli_error(CMD, "--materials: cannot open '%s': %s", path, strerror(errno)), -1;
    char *text = malloc(MAX_FILE_BYTES + 1);
    if (!text) {
        fclose(f);
        return cli_error(CMD, "out of memory"), -1;
    }
    size_t len = fread(text, 1, MAX_FILE_BYTES + 1, f);
    int rd_err = ferror(f);
    fclose(f);
    if (rd_err || len > MAX_FILE_BYTES) {
        free(text);
        return cli_error(CMD, "--materials: '%s': %s", path, rd_err ? "read error" : "larger than 1 MiB"), -1;
    }
    text[len] = '\0';
    cJSON *root = cJSON_Parse(text);
    free(text);
    if (!root) return cli_error(CMD, "--materials: '%s' is not valid JSON", path), -1;
    const cJSON *list = cJSON_IsArray(root) ? root : cJSON_GetObjectItemCaseSensitive(root, "materials");
    int rc = 0;
    if (!cJSON_IsArray(list) || cJSON_GetArraySize(list) < 1 || cJSON_GetArraySize(list) > cap) {
        cli_error(CMD, "--materials: '%s': expected a list of 1 to %d materials", path, cap);
        rc = -1;
    } else {
        *n = cJSON_GetArraySize(list);
        for (int i = 0; i < *n && rc == 0; i++) rc = parse_material(path, i, cJSON_GetArrayItem(list, i), &m[i]);
    }
    cJSON_Delete(root);
    return rc;
}

/* "v1,v2,..." (1..MAX_SWEEP finite numbers) or "none". */
static int parse_sweep(const char *text, double *out, int *n)
{
    *n = 0;
    if (!strcmp(text, "none")) return 0;
    const char *p = text;
    for (;;) {
        if (*n == MAX_SWEEP) return cli_error(CMD, "--sweep-delta-eps: at most %d values", MAX_SWEEP), -1;
        char *end = NULL;
        errno = 0;
        double v = strtod(p, &end);
        if (end == p || errno == ERANGE || !isfinite(v) || (*end != ',' && *end != '\0'))
            return cli_error(CMD, "--sweep-delta-eps: expected comma-separated finite numbers or none, got '%s'",
                             text),
                   -1;
        out[(*n)++] = v;
        if (*end == '\0') return 0;
        p = end + 1;
    }
}

/* ------------------------------------------------------------------------------------------ */
/* The computation                                                                             */
/* ------------------------------------------------------------------------------------------ */

typedef struct {
    const biref_spectral *sp;
    const biref_numeric_plan *ref, *num[NNUM], *gt, *check;
    biref_expansion_opts xopts; /* the defaults: adaptive order, tolerance 1e-3 */
} acc_plans;

static void stat_add(acc_stat *s, double v)
{
    s->sum += v;
    if (v > s->max) s->max = v;
    s->n++;
    s->over1 += v > 1.0;
}

static void stat_merge(acc_stat *a, const acc_stat *b)
{
    a->sum += b->sum;
    if (b->n && b->max > a->max) a->max = b->max;
    a->n += b->n;
    a->over1 += b->over1;
}

static double stat_mean(const acc_stat *s) { return s->n ? s->sum / (double)s->n : NAN; }
static double stat_max(const acc_stat *s) { return s->n ? s->max : NAN; }

static int bin_of(double theta_deg) { return theta_deg <= SPLIT_DEG + 1e-9 ? 0 : theta_deg <= CRIT_DEG + 1e-9 ? 1 : 2; }

/* Progress: on a terminal, one line rewritten in place; with --progress and no terminal (a log
 * file), a new line every 10 s. Otherwise stderr stays for the one-line error. */
typedef struct {
    int on, tty;
    long done, total;
    double t0, last;
} acc_progress;

static void progress_tick(acc_progress *pg, const char *name)
{
    long d;
#pragma omp atomic capture
    d = ++pg->done;
    if (!pg->on || omp_get_thread_num() != 0) return;
    double now = omp_get_wtime();
    if (now - pg->last < (pg->tty ? 0.5 : 10.0) && d != pg->total) return;
    pg->last = now;
    fprintf(stderr, "%sbiref accuracy: %3.0f%%  material %-16s %6.1f s%s", pg->tty ? "\r" : "",
            100.0 * (double)d / (double)pg->total, name, now - pg->t0, pg->tty ? "" : "\n");
    fflush(stderr);
}


/* The near-axis sample sets. A (θ, φ) grid only grazes the narrow cone of directions near the
 * optic axis where a mm slab shows colour (for fig. 9c the cone is ~5° wide), so these samples
 * aim there directly: internal (ordinary) wave directions u at angle ψ from the axis and angle β
 * around it (--azimuths values), uniform in sin²ψ because the retardance grows like sin²ψ, up to
 * the ψ where the retardance d |Δη| sin²ψ reaches AXIS_RETARDANCE_NM (beyond a few µm the colours
 * wash out). Set 0 puts the downward legs near the axis: the main rings, from the interference of
 * the two order-0 paths (eq. 24). Set 1 puts the internally reflected, upward legs near the axis
 * (u mirrored in the surface plane): fainter rings from paths that differ only in the mode of an
 * upward leg, pairs that eq. 26 leaves out (they are neither the order-0 pair nor descendants). */
#define AXIS_NPSI 12 /* values of ψ; the number of β is --azimuths */
#define AXIS_RETARDANCE_NM 4000.0
#define AXIS_PSI_CAP_DEG 30.0

static double axis_psi_max(const acc_material *m)
{
    const double cap = sin(AXIS_PSI_CAP_DEG * M_PI / 180.0);
    double dn = fabs(m->slab.eta_e - m->slab.eta_o), s2 = dn > 0 ? AXIS_RETARDANCE_NM / (m->slab.thickness_nm * dn) : 1;
    return asin(fmin(cap, sqrt(s2)));
}

/* Incidence (θ, φ) that refracts the ordinary wave into sample j of near-axis set `set`; 0 if
 * that direction cannot be reached from outside within --theta-max-deg. */
static int axis_sample(const acc_run *run, const acc_material *m, int set, int j, double *theta, double *phi)
{
    const double *A = m->slab.axis;
    /* The axis' sign is irrelevant: set 0 aims at a = ±A with a_y <= 0. Set 1 aims at the mirror
     * image in the surface plane of the upward-pointing axis -a, i.e. (-a_x, a_y, -a_z): an
     * ordinary wave u reflected at a surface becomes (u_x, -u_y, u_z), which is then near -a. */
    const double h = (A[1] > 0 ? -1.0 : 1.0) * (set ? -1.0 : 1.0);
    const double a[3] = {h * A[0], -fabs(A[1]), h * A[2]};
    double e1[3] = {-a[2], 0.0, a[0]}; /* a x y: horizontal, perpendicular to a */
    double n1 = hypot(e1[0], e1[2]);
    if (n1 < 1e-12) e1[0] = 1.0, e1[2] = 0.0, n1 = 1.0;
    e1[0] /= n1, e1[2] /= n1;
    const double e2[3] = {a[1] * e1[2] - a[2] * e1[1], a[2] * e1[0] - a[0] * e1[2], a[0] * e1[1] - a[1] * e1[0]};
    const double smax = sin(axis_psi_max(m));
    const double spsi = smax * sqrt((j / run->nphi + 0.5) / AXIS_NPSI), cpsi = sqrt(1.0 - spsi * spsi);
    const double beta = 2.0 * M_PI * (j % run->nphi) / run->nphi;
    double u[3];
    for (int k = 0; k < 3; k++) u[k] = cpsi * a[k] + spsi * (cos(beta) * e1[k] + sin(beta) * e2[k]);
    if (!(u[1] < 0.0)) return 0;
    const double st = hypot(u[0], u[2]), sth = m->slab.eta_o * st / m->slab.eta_i;
    if (sth > sin(run->theta_max_deg * M_PI / 180.0)) return 0;
    *theta = asin(sth);
    /* The axis rotation of evaluate_point, applied to u, must bring it to (0, u_y, -st), the
     * paper's refracted direction in the YZ plane: that is φ = atan2(u_z, u_x) + π/2. */
    *phi = atan2(u[2], u[0]) + 0.5 * M_PI;
    return 1;
}

/* The slab seen by a ray whose plane of incidence makes azimuth φ with the slab's own frame. */
static biref_slab rotated_slab(const acc_material *m, double phi)
{
    biref_slab s = m->slab;
    const double *A = m->slab.axis, c = cos(phi), sn = sin(phi);
    s.axis[0] = c * A[0] + sn * A[2];
    s.axis[1] = A[1];
    s.axis[2] = -sn * A[0] + c * A[2];
    return s;
}

/* One compared method's spectrum (all four polarisation pairs, T and R). */
static int method_spectrum(const acc_plans *pl, int k, const biref_slab_state *st, biref_spectrum *x)
{
    switch (k) {
    case M_ANALYTIC: biref_spectrum_analytic(pl->sp, st, x); return 0;
    case M_EXPANSION: return biref_spectrum_expansion(pl->sp, st, &pl->xopts, x) == BIREF_OK ? 0 : -1;
    case M_GT: biref_spectrum_numeric(pl->gt, st, x); return 0;
    default: biref_spectrum_numeric(pl->num[k - M_N3], st, x); return 0;
    }
}

static void mix(const acc_material *m, const biref_spectrum *x, double out[2][3])
{
    biref_spectrum_mix(x->T, m->light.w_in, m->light.mask, out[0]);
    biref_spectrum_mix(x->R, m->light.w_in, m->light.mask, out[1]);
}

/* ΔE00 of every method for incidence θ with the axis rotated by φ about y: de[method][T/R], NaN
 * where not computed, and the chroma of the reference colours. Returns 0, or -1 if a spectrum
 * came out non-finite. */
static int evaluate_point(const acc_plans *pl, const acc_material *m, double theta, double phi, int with_check,
                          double de[NM][2], double chroma[2])
{
    for (int k = 0; k < NM; k++) de[k][0] = de[k][1] = NAN;
    biref_slab s = rotated_slab(m, phi);
    biref_slab_state st;
    if (biref_slab_prepare(&s, theta, &st) != BIREF_OK) return -1;

    biref_spectrum x;
    double ref_mix[2][3], x_mix[2][3], an_mix[2][3], ex_mix[2][3];
    biref_spectrum_numeric(pl->ref, &st, &x);
    mix(m, &x, ref_mix);
    for (int w = 0; w < 2; w++) {
        double lab[3];
        biref_xyz_to_lab(ref_mix[w], NULL, lab);
        chroma[w] = hypot(lab[1], lab[2]);
    }
    for (int k = 0; k < NCMP; k++) {
        if (method_spectrum(pl, k, &st, &x)) return -1;
        mix(m, &x, x_mix);
        for (int w = 0; w < 2; w++) de[k][w] = biref_delta_e00_xyz(ref_mix[w], x_mix[w]);
        if (k == M_ANALYTIC) memcpy(an_mix, x_mix, sizeof x_mix);
        if (k == M_EXPANSION) memcpy(ex_mix, x_mix, sizeof x_mix);
    }
    if (with_check) {
        /* Is the reference itself converged? Compare it, and the two fast methods, with a denser
         * integration (aliasing of the Fabry–Pérot terms in mm slabs, docs/ACCURACY.md). */
        biref_spectrum_numeric(pl->check, &st, &x);
        mix(m, &x, x_mix);
        for (int w = 0; w < 2; w++) {
            de[M_REF_CHECK][w] = biref_delta_e00_xyz(x_mix[w], ref_mix[w]);
            de[M_AN_CHECK][w] = biref_delta_e00_xyz(x_mix[w], an_mix[w]);
            de[M_EX_CHECK][w] = biref_delta_e00_xyz(x_mix[w], ex_mix[w]);
        }
    }
    for (int k = 0; k < (with_check ? NM : NCMP); k++)
        for (int w = 0; w < 2; w++)
            if (!isfinite(de[k][w])) return -1;
    return 0;
}

static int run_material(acc_run *run, const acc_plans *pl, int mi, acc_progress *pg)
{
    const acc_material *m = &run->mat[mi];
    acc_result *r = &run->res[mi];
    /* Jobs: the (θ, φ) grid, then the near-axis sets, in one loop so that threads stay busy. */
    const long ngrid = (long)run->ntheta * run->nphi, naxis = (long)AXIS_NPSI * run->nphi,
               njobs = ngrid + AXIS_SETS * naxis;
    double(*de)[NM][2] = malloc((size_t)njobs * sizeof *de);
    double(*chroma)[2] = malloc((size_t)njobs * sizeof *chroma);
    double *theta_j = malloc((size_t)njobs * sizeof *theta_j);
    char *valid = malloc((size_t)njobs);
    r->theta = calloc((size_t)run->ntheta, sizeof *r->theta);
    r->phi0 = malloc((size_t)run->ntheta * sizeof *r->phi0);
    if (!de || !chroma || !theta_j || !valid || !r->theta || !r->phi0) {
        free(de);
        free(chroma);
        free(theta_j);
        free(valid);
        return cli_error(CMD, "out of memory"), -1;
    }
    /* The check integration: base materials only, on a subset (see AXIS_CHECK_STRIDE). */
    const int check_on = run->samples_check > 0 && m->base < 0;
    const double t0 = omp_get_wtime();
    long bad = -1;
    double bad_theta = 0, bad_phi = 0;
#pragma omp parallel for schedule(dynamic, 2)
    for (long j = 0; j < njobs; j++) {
        double theta = 0.0, phi = 0.0;
        int check;
        if (j < ngrid) {
            const int it = (int)(j / run->nphi);
            theta = it * run->theta_step_deg * M_PI / 180.0;
            phi = 2.0 * M_PI * (double)(j % run->nphi) / run->nphi;
            /* every kcheck-th angle, and the last one (the most grazing, where errors peak) */
            check = check_on && (it % run->kcheck == 0 || it == run->ntheta - 1);
            valid[j] = 1;
        } else {
            const long ja = (j - ngrid) % naxis;
            valid[j] = (char)axis_sample(run, m, (int)((j - ngrid) / naxis), (int)ja, &theta, &phi);
            check = check_on && ja % AXIS_CHECK_STRIDE == 0;
        }
        theta_j[j] = valid[j] ? theta * 180.0 / M_PI : NAN;
        if (valid[j] && evaluate_point(pl, m, theta, phi, check, de[j], chroma[j])) {
#pragma omp critical(acc_bad)
            {
                bad = j;
                bad_theta = theta;
                bad_phi = phi;
            }
        }
        progress_tick(pg, m->name);
    }
    r->elapsed_s = omp_get_wtime() - t0;
    if (bad >= 0) {
        free(de);
        free(chroma);
        free(theta_j);
        free(valid);
        return cli_error(CMD, "material %s: non-finite result at theta %g deg, axis azimuth %g deg", m->name,
                         bad_theta * 180.0 / M_PI, bad_phi * 180.0 / M_PI),
               -1;
    }
    /* Serial aggregation keeps the sums independent of the thread count. NaN = not computed. */
    for (int it = 0; it < run->ntheta; it++) {
        const int b = bin_of(it * run->theta_step_deg);
        for (int k = 0; k < NM; k++)
            for (int w = 0; w < 2; w++) {
                r->phi0[it][k][w] = de[(long)it * run->nphi][k][w];
                for (int ip = 0; ip < run->nphi; ip++) {
                    const long j = (long)it * run->nphi + ip;
                    const double v = de[j][k][w];
                    if (v != v) continue;
                    stat_add(&r->theta[it][k][w], v);
                    stat_add(&r->bin[b][k][w], v);
                    if (chroma[j][w] >= CHROMA_MIN) stat_add(&r->col[b][k][w], v);
                }
            }
    }
    r->axis_psi_max_deg = axis_psi_max(m) * 180.0 / M_PI;
    for (long j = ngrid; j < njobs; j++) {
        if (!valid[j]) continue;
        const int set = (int)((j - ngrid) / naxis);
        r->axis_valid[set]++;
        for (int k = 0; k < NM; k++)
            for (int w = 0; w < 2; w++) {
                const double v = de[j][k][w];
                if (v != v) continue;
                stat_add(&r->axis[set][k][w], v);
                if (chroma[j][w] >= CHROMA_MIN) stat_add(&r->axis_col[set][k][w], v);
                if (theta_j[j] <= CRIT_DEG + 1e-9) stat_add(&r->axis_crit[set][k][w], v);
            }
    }
    free(de);
    free(chroma);
    free(theta_j);
    free(valid);
    return 0;
}

/* --cost: the slab states of the accuracy grid itself (every angle of the grid in the range, every
 * azimuth, the base materials), so that the cost is measured on exactly the directions whose ΔE00
 * the statistics report. The expansion's cost is heavy-tailed (its order grows near grazing
 * incidence), so a small random subset would not give a stable mean. The states are stored in a
 * golden-ratio permutation of the grid: a timed run that covers only a prefix of the pool (the
 * slow methods) still samples all angles evenly, and whole passes are exact pool means. Returns
 * the number of states (0 if none or out of memory). */
static int cost_pool(const acc_run *run, int band, biref_slab **slab, double **theta)
{
    /* band 0: θ <= 70°, band 1: 70° < θ <= 85°, band 2: both */
    int n = 0;
    for (int it = 0; it < run->ntheta; it++) {
        const int b = bin_of(it * run->theta_step_deg);
        if (b < 2 && (band == 2 || band == b)) n += run->nphi * run->nbase;
    }
    if (n == 0) return 0;
    *slab = malloc((size_t)n * sizeof **slab);
    *theta = malloc((size_t)n * sizeof **theta);
    if (!*slab || !*theta) {
        free(*slab), free(*theta);
        *slab = NULL, *theta = NULL;
        return 0;
    }
    long stride = lround(0.6180339887 * n);
    for (;; stride++) {
        long x = stride, y = n; /* gcd(stride, n) == 1 makes k -> k * stride mod n a permutation */
        while (y) {
            long t = x % y;
            x = y, y = t;
        }
        if (x == 1) break;
    }
    int k = 0;
    for (int it = 0; it < run->ntheta; it++) {
        const int b = bin_of(it * run->theta_step_deg);
        if (b >= 2 || (band != 2 && band != b)) continue;
        for (int ip = 0; ip < run->nphi; ip++)
            for (int i = 0; i < run->nbase; i++, k++) {
                const long j = (long)k * stride % n;
                (*slab)[j] = rotated_slab(&run->mat[i], 2.0 * M_PI * (double)ip / run->nphi);
                (*theta)[j] = it * run->theta_step_deg * M_PI / 180.0;
            }
    }
    return n;
}

static int measure_cost(acc_run *run, const acc_plans *pl)
{
    for (int k = 0; k < NCMP; k++) {
        run->cost[k].name = METHOD_KEY[k];
        run->cost[k].kind = k == M_ANALYTIC ? ACC_COST_ANALYTIC : k == M_EXPANSION ? ACC_COST_EXPANSION : ACC_COST_NUMERIC;
        run->cost[k].plan = k == M_GT ? pl->gt : (k >= M_N3 && k <= M_N128) ? pl->num[k - M_N3] : NULL;
    }
    const double t0 = omp_get_wtime();
    biref_slab *slab = NULL;
    double *theta = NULL;
    acc_cost_pool pool = {NULL, NULL, cost_pool(run, 2, &slab, &theta)};
    if (pool.n == 0) return cli_error(CMD, "--cost: out of memory"), -1;
    pool.slab = slab, pool.theta = theta;
    run->cost_pool_n = pool.n;
    int rc = acc_cost_measure(pl->sp, &pool, &run->cost_opts, &run->cost_prepare, run->cost, NCMP);
    free(slab), free(theta);
    if (rc) return -1;
    /* The expansion's order, hence its cost, grows towards grazing incidence; the analytic
     * method's does not. Both again on the two angle ranges, for the breakdown. */
    for (int b = 0; b < 2; b++) {
        run->cost_band[b][0] = run->cost[M_ANALYTIC];
        run->cost_band[b][1] = run->cost[M_EXPANSION];
        run->cost_band_n[b] = cost_pool(run, b, &slab, &theta);
        if (run->cost_band_n[b] == 0) continue;
        pool = (acc_cost_pool){slab, theta, run->cost_band_n[b]};
        rc = acc_cost_measure(pl->sp, &pool, &run->cost_opts, NULL, run->cost_band[b], 2);
        free(slab), free(theta);
        if (rc) return -1;
    }
    run->cost_s = omp_get_wtime() - t0;
    run->have_cost = 1;
    return 0;
}

/* ------------------------------------------------------------------------------------------ */
/* Evaluation of the acceptance criteria                                                       */
/* ------------------------------------------------------------------------------------------ */

/* Issue #3: analytic vs reference, θ 0–70° over all azimuths, mean <= 1 and max <= 4. */
static int acceptance_pass(const acc_result *r, int w)
{
    const acc_stat *s = &r->bin[0][M_ANALYTIC][w];
    return s->n > 0 && stat_mean(s) <= 1.0 && s->max <= 4.0;
}

/* Issue #5. (a) for each fig. 9 material and every θ in 0–85°, the expansion within ΔE00 <= 1 of
 * the reference (grid and near-axis samples), at no more than 3x the analytic method's cost per
 * shading sample; (b) at equal cost, the expansion's ΔE00 at least 5x below numeric integration's. */
#define ISSUE5_DE_MAX 1.0
#define ISSUE5_COST_RATIO 3.0
#define ISSUE5_GAIN 5.0

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
} acc_issue5;

static void issue5_eval(const acc_run *run, acc_issue5 *e)
{
    memset(e, 0, sizeof *e);
    e->pass_de[0] = e->pass_de[1] = 1;
    for (int i = 0; i < run->nbase; i++) {
        const acc_result *r = &run->res[i];
        for (int w = 0; w < 2; w++) {
            e->grid_max[i][w] = fmax(stat_max(&r->bin[0][M_EXPANSION][w]), stat_max(&r->bin[1][M_EXPANSION][w]));
            e->axis_max[i][w] =
                fmax(stat_max(&r->axis_crit[0][M_EXPANSION][w]), stat_max(&r->axis_crit[1][M_EXPANSION][w]));
            e->theta_of_max[i][w] = NAN;
            double best = -1.0;
            for (int it = 0; it < run->ntheta; it++) {
                const acc_stat *s = &r->theta[it][M_EXPANSION][w];
                if (it * run->theta_step_deg <= CRIT_DEG + 1e-9 && s->n && s->max > best)
                    best = s->max, e->theta_of_max[i][w] = it * run->theta_step_deg;
            }
            /* fmax ignores a NaN (no near-axis sample reached), but not a missing grid */
            if (!(e->grid_max[i][w] <= ISSUE5_DE_MAX) || e->axis_max[i][w] > ISSUE5_DE_MAX) e->pass_de[w] = 0;
        }
        for (int k = 0; k < NCMP; k++)
            for (int w = 0; w < 2; w++) {
                stat_merge(&e->pooled[k][w], &r->bin[0][k][w]);
                stat_merge(&e->pooled[k][w], &r->bin[1][k][w]);
            }
    }
    e->lo = e->hi = -1;
    if (!run->have_cost) return;
    e->ns_an = run->cost[M_ANALYTIC].with_prepare.ns_median;
    e->ns_ex = run->cost[M_EXPANSION].with_prepare.ns_median;
    e->ratio = e->ns_ex / e->ns_an;
    e->ns_an_alone = run->cost[M_ANALYTIC].alone.ns_median;
    e->ns_ex_alone = run->cost[M_EXPANSION].alone.ns_median;
    e->ratio_alone = e->ns_ex_alone / e->ns_an_alone;
    e->pass_cost = e->ratio <= ISSUE5_COST_RATIO;
    e->pass_a = e->pass_cost && e->pass_de[0] && e->pass_de[1];
    /* Numeric error falls as N grows, so the cheapest numeric method that costs at least as much
     * as the expansion is at least as accurate as numeric integration at exactly equal cost: the
     * comparison with it is the conservative one. */
    for (int k = M_N3; k <= M_N128; k++) {
        if (run->cost[k].with_prepare.ns_median < e->ns_ex)
            e->lo = k;
        else if (e->hi < 0)
            e->hi = k;
    }
    if (e->hi < 0) return;
    e->pass_b = 1;
    for (int w = 0; w < 2; w++) {
        e->gain_mean[w] = stat_mean(&e->pooled[e->hi][w]) / stat_mean(&e->pooled[M_EXPANSION][w]);
        e->gain_max[w] = stat_max(&e->pooled[e->hi][w]) / stat_max(&e->pooled[M_EXPANSION][w]);
        if (!(e->gain_mean[w] >= ISSUE5_GAIN && e->gain_max[w] >= ISSUE5_GAIN)) e->pass_b = 0;
    }
}

/* ------------------------------------------------------------------------------------------ */
/* Output                                                                                      */
/* ------------------------------------------------------------------------------------------ */

static void bin_label(const acc_run *run, int b, char *buf, size_t len)
{
    static const double lo[NBIN] = {0.0, SPLIT_DEG, CRIT_DEG}, hi[NBIN] = {SPLIT_DEG, CRIT_DEG, 90.0};
    const double top = (run->ntheta - 1) * run->theta_step_deg;
    if (top <= lo[b] && b > 0)
        snprintf(buf, len, ">%g°", lo[b]);
    else
        snprintf(buf, len, "%g-%g°", lo[b], fmin(top, hi[b]));
}

static void md_num(FILE *f, double v)
{
    if (v == v)
        fprintf(f, " %.2f |", v);
    else
        fprintf(f, " – |");
}

/* Small differences matter for the expansion and the reference check: three significant digits
 * below 0.1 instead of rounding them to 0.00. */
static void md_num_fine(FILE *f, double v)
{
    if (v != v)
        fprintf(f, " – |");
    else if (v != 0.0 && fabs(v) < 0.1)
        fprintf(f, " %.3g |", v);
    else
        fprintf(f, " %.2f |", v);
}

static void md_stat_pair(FILE *f, const acc_stat *s)
{
    md_num_fine(f, stat_mean(s));
    md_num_fine(f, stat_max(s));
}

/* Share of samples in percent, with one decimal: small shares are the interesting ones. */
static void md_pct(FILE *f, long part, long whole)
{
    if (whole > 0)
        fprintf(f, " %.1f |", 100.0 * (double)part / (double)whole);
    else
        fprintf(f, " – |");
}

static const char *light_desc(const cli_light *l, char *buf, size_t len)
{
    snprintf(buf, len, "%.0f%% s / %.0f%% p, analyzer %s", 100 * l->w_in[0], 100 * l->w_in[1],
             cli_analyzer_name(l->mask));
    return buf;
}

static const char *pass_word(int ok) { return ok ? "pass" : "**fail**"; }

/* The angle range of a cost breakdown band: 0 = [0, 70°], 1 = (70°, 85°], clipped to the grid. */
static void band_range(const acc_run *run, int b, double r[2])
{
    const double top = (run->ntheta - 1) * run->theta_step_deg;
    r[0] = b ? SPLIT_DEG : 0.0;
    r[1] = fmin(b ? CRIT_DEG : SPLIT_DEG, top);
}

static void write_cost_md(FILE *f, const acc_run *run)
{
    const int fixed = run->cost_opts.fixed_iters > 0;
    fprintf(f, "\n### Cost per shading sample (one thread)\n\n"
               "One shading sample = biref_slab_prepare for one direction and one biref_spectrum: the XYZ of all\n"
               "four s/p input/output pairs, transmission and reflection. Every method runs on the same %d slab\n"
               "states: the accuracy grid for θ 0-%g° (every %g°, %d azimuths, the %d base materials), in a\n"
               "golden-ratio permutation. ",
            run->cost_pool_n, fmin(CRIT_DEG, (run->ntheta - 1) * run->theta_step_deg), run->theta_step_deg, run->nphi,
            run->nbase);
    if (fixed)
        fprintf(f, "One run of %ld samples per method (--cost-iterations).\n", run->cost_opts.fixed_iters);
    else
        fprintf(f, "Median of %d timed runs of at least %g s (whole passes over the states\n"
                   "when a pass is shorter), CLOCK_MONOTONIC; cpu share = lowest thread CPU time / wall time over the\n"
                   "runs (below ~0.95 another process took the core).\n",
                run->cost_opts.runs, run->cost_opts.min_time);
    fprintf(f, "Measuring took %.1f s.\n\n"
               "| method | ns per sample, prepare included | integration alone (ns) | prepare + integration / analytic | "
               "integration alone / analytic | cpu share | samples per run |\n|---|---|---|---|---|---|---|\n",
            run->cost_s);
    fprintf(f, "| biref_slab_prepare only | %.0f | – | – | – | %.2f | %ld |\n", run->cost_prepare.ns_median,
            run->cost_prepare.cpu_share, run->cost_prepare.iters);
    const acc_cost_row *an = &run->cost[M_ANALYTIC];
    for (int k = 0; k < NCMP; k++) {
        const acc_cost_row *c = &run->cost[k];
        fprintf(f, "| %s | %.0f | %.0f | %.2f | %.2f | %.2f | %ld |\n", METHOD_KEY[k], c->with_prepare.ns_median,
                c->alone.ns_median, c->with_prepare.ns_median / an->with_prepare.ns_median,
                c->alone.ns_median / an->alone.ns_median, fmin(c->alone.cpu_share, c->with_prepare.cpu_share),
                c->with_prepare.iters);
    }
    fprintf(f, "\nBy angle range (the grid states of each range):\n\n"
               "| θ range | states | analytic, prepare included (ns) | expansion, prepare included (ns) | ratio | "
               "analytic alone | expansion alone | ratio |\n|---|---|---|---|---|---|---|---|\n");
    for (int b = 0; b < 2; b++) {
        if (!run->cost_band_n[b]) continue;
        const acc_cost_row *a = &run->cost_band[b][0], *x = &run->cost_band[b][1];
        double r[2];
        band_range(run, b, r);
        fprintf(f, "| %g-%g° | %d | %.0f | %.0f | %.2f | %.0f | %.0f | %.2f |\n", r[0], r[1], run->cost_band_n[b],
                a->with_prepare.ns_median, x->with_prepare.ns_median, x->with_prepare.ns_median / a->with_prepare.ns_median,
                a->alone.ns_median, x->alone.ns_median, x->alone.ns_median / a->alone.ns_median);
    }
}

static void write_issue5_md(FILE *f, const acc_run *run, const acc_issue5 *e)
{
    fprintf(f, "\n### Issue #5 (a): expansion within ΔE00 ≤ %g of the reference for every θ in 0-%g°\n\n"
               "Maximum over all azimuths of the grid (θ ≤ %g°) and over the near-axis samples refracted from\n"
               "θ ≤ %g°; \"θ of grid max\" is where the grid maximum occurs.\n\n"
               "| material | T max, grid | T max, near axis | θ of T grid max | R max, grid | R max, near axis | "
               "θ of R grid max |\n|---|---|---|---|---|---|---|\n",
            ISSUE5_DE_MAX, CRIT_DEG, CRIT_DEG, CRIT_DEG);
    for (int i = 0; i < run->nbase; i++) {
        fprintf(f, "| %s |", run->mat[i].name);
        for (int w = 0; w < 2; w++) {
            md_num_fine(f, e->grid_max[i][w]);
            md_num_fine(f, e->axis_max[i][w]);
            fprintf(f, " %g |", e->theta_of_max[i][w]);
        }
        fprintf(f, "\n");
    }
    fprintf(f, "\nΔE00 ≤ %g: transmission %s, reflection %s.\n", ISSUE5_DE_MAX, pass_word(e->pass_de[0]),
            pass_word(e->pass_de[1]));
    if (!run->have_cost) {
        fprintf(f, "Cost: not measured (run with --cost).\n");
        return;
    }
    fprintf(f, "Cost per shading sample in this run (prepare included): analytic %.0f ns, expansion %.0f ns, ratio "
               "%.2f (≤ %g: %s); integration alone %.0f vs %.0f ns, ratio %.2f.\n**(a): %s.**\n",
            e->ns_an, e->ns_ex, e->ratio, ISSUE5_COST_RATIO, pass_word(e->pass_cost), e->ns_an_alone, e->ns_ex_alone,
            e->ratio_alone, e->pass_a ? "met" : "not met");

    fprintf(f, "\n### Issue #5 (b): at equal cost, expansion ΔE00 at least %g× below numeric integration\n\n"
               "ΔE00 over the grid θ 0-%g°, all azimuths, the %d base materials together. Cost with prepare, this "
               "run.\n\n| method | ns per sample | cost / expansion | T mean | T max | R mean | R max |\n"
               "|---|---|---|---|---|---|---|\n",
            ISSUE5_GAIN, CRIT_DEG, run->nbase);
    const int rows[3] = {M_EXPANSION, e->lo, e->hi};
    for (int q = 0; q < 3; q++) {
        const int k = rows[q];
        if (k < 0) continue;
        const double ns = run->cost[k].with_prepare.ns_median;
        fprintf(f, "| %s | %.0f | %.2f |", METHOD_KEY[k], ns, ns / e->ns_ex);
        for (int w = 0; w < 2; w++) md_stat_pair(f, &e->pooled[k][w]);
        fprintf(f, "\n");
    }
    if (e->hi < 0) {
        fprintf(f, "\nEvery numeric method compared here is cheaper than the expansion; (b) not evaluated.\n");
        return;
    }
    fprintf(f, "\nCompared with %s, the cheapest numeric integration that costs at least as much as the expansion\n"
               "(numeric error falls with N, so numeric integration at exactly equal cost is no better): ΔE00 ratio\n"
               "numeric / expansion, T mean %.0f×, T max %.0f×, R mean %.0f×, R max %.0f×.\n**(b): %s.**\n",
            METHOD_KEY[e->hi], e->gain_mean[0], e->gain_max[0], e->gain_mean[1], e->gain_max[1],
            e->pass_b ? "met" : "not met");
}

static void write_markdown(FILE *f, const acc_run *run)
{
    char lb[96], bl[NBIN][32];
    for (int b = 0; b < NBIN; b++) bin_label(run, b, bl[b], sizeof bl[b]);
    fprintf(f, "Reference: numeric integration of eq. 17 with %d midpoint samples; CMF %s, %g-%g nm.\n",
            run->samples_ref, biref_cmf_kind_name(run->scfg.cmf), run->scfg.lambda_min_nm, run->scfg.lambda_max_nm);
    if (run->sweep_done)
        fprintf(f, "Angles θ = 0-%g° in steps of %g°, %d azimuths of the optic axis about the slab normal.\n"
                   "ΔE00 of the mixed colour (each material's light) against the reference, mean and max over (θ, φ).\n",
                (run->ntheta - 1) * run->theta_step_deg, run->theta_step_deg, run->nphi);
    fprintf(f, "\n### Materials\n\n| material | η_o | η_e | Δε | axis | d (mm) | light |\n|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < run->nbase; i++) {
        const acc_material *m = &run->mat[i];
        const biref_slab *s = &m->slab;
        fprintf(f, "| %s | %.4g | %.4g | %+.4f | (%.3f, %.3f, %.3f) | %.4g | %s |\n", m->name, s->eta_o, s->eta_e,
                s->eta_e * s->eta_e - s->eta_o * s->eta_o, s->axis[0], s->axis[1], s->axis[2], s->thickness_nm / 1e6,
                light_desc(&m->light, lb, sizeof lb));
    }
    if (!run->sweep_done) {
        if (run->have_cost) write_cost_md(f, run);
        return;
    }

    if (run->samples_check > 0) {
        fprintf(f, "\n### Is the reference converged? %d vs %d samples\n\n"
                   "On the grid every %g° of θ and at the largest θ (all azimuths), and on every %dth near-axis\n"
                   "sample, base materials.\n"
                   "`ref-vs-check`: ΔE00 between the reference (%d samples) and %d samples; `analytic-vs-check`,\n"
                   "`expansion-vs-check`: those methods against %d samples.\n\n"
                   "| material | | comparison | mean %s | max %s | mean %s | max %s | mean %s | max %s | "
                   "near axis: mean | near axis: max |\n|---|---|---|---|---|---|---|---|---|---|---|\n",
                run->samples_ref, run->samples_check, run->kcheck * run->theta_step_deg, AXIS_CHECK_STRIDE,
                run->samples_ref, run->samples_check, run->samples_check, bl[0], bl[0], bl[1], bl[1], bl[2], bl[2]);
        for (int i = 0; i < run->nbase; i++)
            for (int w = 0; w < 2; w++)
                for (int k = M_REF_CHECK; k <= M_EX_CHECK; k++) {
                    const acc_result *r = &run->res[i];
                    fprintf(f, "| %s | %s | %s |", run->mat[i].name, TR[w], METHOD_KEY[k]);
                    for (int b = 0; b < NBIN; b++) md_stat_pair(f, &r->bin[b][k][w]);
                    acc_stat ax = r->axis[0][k][w];
                    stat_merge(&ax, &r->axis[1][k][w]);
                    md_stat_pair(f, &ax);
                    fprintf(f, "\n");
                }
    }

    fprintf(f, "\n### ΔE00 against the reference\n\n"
               "Mean, max and share (%%) of samples with ΔE00 > 1, over all (θ, φ) of each range.\n\n"
               "| material | | method | mean %s | max %s | %% >1 %s | mean %s | max %s | %% >1 %s | mean %s | max %s | "
               "%% >1 %s |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
            bl[0], bl[0], bl[0], bl[1], bl[1], bl[1], bl[2], bl[2], bl[2]);
    for (int i = 0; i < run->nbase; i++)
        for (int w = 0; w < 2; w++)
            for (int k = 0; k < NCMP; k++) {
                const acc_result *r = &run->res[i];
                fprintf(f, "| %s | %s | %s |", run->mat[i].name, TR[w], METHOD_KEY[k]);
                for (int b = 0; b < NBIN; b++) {
                    md_stat_pair(f, &r->bin[b][k][w]);
                    md_pct(f, r->bin[b][k][w].over1, r->bin[b][k][w].n);
                }
                fprintf(f, "\n");
            }

    fprintf(f, "\n### Iridescent directions only (reference chroma C*ab ≥ %g)\n\n"
               "Share (%%) of the (θ, φ) samples whose reference colour is chromatic, and the ΔE00 of the analytic\n"
               "method and the expansion on those samples.\n\n"
               "| material | | method | share %s | mean %s | max %s | share %s | mean %s | max %s | share %s | mean %s | "
               "max %s |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
            CHROMA_MIN, bl[0], bl[0], bl[0], bl[1], bl[1], bl[1], bl[2], bl[2], bl[2]);
    for (int i = 0; i < run->nbase; i++)
        for (int w = 0; w < 2; w++)
            for (int k = M_ANALYTIC; k <= M_EXPANSION; k++) {
                const acc_result *r = &run->res[i];
                fprintf(f, "| %s | %s | %s |", run->mat[i].name, TR[w], METHOD_KEY[k]);
                for (int b = 0; b < NBIN; b++) {
                    md_pct(f, r->col[b][k][w].n, r->bin[b][k][w].n);
                    md_stat_pair(f, &r->col[b][k][w]);
                }
                fprintf(f, "\n");
            }

    /* The near-axis table keeps the methods that matter for the discussion; the JSON has all. */
    static const int AXIS_METHODS[] = {M_ANALYTIC, M_EXPANSION, M_N32, M_N128, M_GT, M_REF_CHECK};
    fprintf(f, "\n### Near the optic axis (the iridescent directions)\n\n"
               "Internal wave directions within ψ of the optic axis (retardance up to %g nm), %d x %d samples per\n"
               "set, uniform in sin²ψ and around the axis. Set `down`: the downward legs near the axis (main\n"
               "rings); set `up`: the internally reflected, upward legs near the axis (minor rings). \"reached\" =\n"
               "refracted from θ ≤ %g°. Share = chromatic reference (C*ab ≥ %g). `ref-vs-check` on every %dth\n"
               "sample only.\n\n"
               "| material | ψ max | set | reached | | method | share %% | mean | max | %% >1 | mean (chromatic) | "
               "max (chromatic) |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
            AXIS_RETARDANCE_NM, AXIS_NPSI, run->nphi, (run->ntheta - 1) * run->theta_step_deg, CHROMA_MIN,
            AXIS_CHECK_STRIDE);
    static const char *const SET_NAME[AXIS_SETS] = {"down", "up"};
    for (int i = 0; i < run->nbase; i++)
        for (int set = 0; set < AXIS_SETS; set++)
            for (int w = 0; w < 2; w++)
                for (size_t q = 0; q < sizeof AXIS_METHODS / sizeof AXIS_METHODS[0]; q++) {
                    const int k = AXIS_METHODS[q];
                    const acc_result *r = &run->res[i];
                    if (!r->axis[set][k][w].n) continue;
                    fprintf(f, "| %s | %.1f° | %s | %ld | %s | %s |", run->mat[i].name, r->axis_psi_max_deg,
                            SET_NAME[set], r->axis_valid[set], TR[w], METHOD_KEY[k]);
                    md_pct(f, r->axis_col[set][k][w].n, r->axis[set][k][w].n);
                    md_stat_pair(f, &r->axis[set][k][w]);
                    md_pct(f, r->axis[set][k][w].over1, r->axis[set][k][w].n);
                    md_stat_pair(f, &r->axis_col[set][k][w]);
                    fprintf(f, "\n");
                }

    fprintf(f, "\n### Acceptance of issue #3: analytic, %s, mean ΔE00 ≤ 1 and max ≤ 4\n\n"
               "| material | T mean | T max | T | R mean | R max | R |\n|---|---|---|---|---|---|---|\n",
            bl[0]);
    for (int i = 0; i < run->nbase; i++) {
        const acc_result *r = &run->res[i];
        fprintf(f, "| %s |", run->mat[i].name);
        for (int w = 0; w < 2; w++) {
            md_stat_pair(f, &r->bin[0][M_ANALYTIC][w]);
            fprintf(f, " %s |", pass_word(acceptance_pass(r, w)));
        }
        fprintf(f, "\n");
    }

    acc_issue5 e;
    issue5_eval(run, &e);
    write_issue5_md(f, run, &e);
    if (run->have_cost) write_cost_md(f, run);

    if (run->nmat > run->nbase) {
        fprintf(f, "\n### Δε sweep (η_o, axis, d and light of the base material; against the reference)\n\n"
                   "| base | Δε | η_e | analytic T mean %s | analytic T max %s | analytic T max %s | analytic R max %s | "
                   "expansion T max %s | expansion T max %s | expansion R max %s | near-axis T max, analytic (down / up) | "
                   "near-axis T max, expansion (down / up) | numeric-128 T max %s |\n"
                   "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
                bl[0], bl[0], bl[1], bl[0], bl[0], bl[1], bl[0], bl[0]);
        for (int i = run->nbase; i < run->nmat; i++) {
            const acc_material *m = &run->mat[i];
            const acc_result *r = &run->res[i];
            fprintf(f, "| %s | %+.2f | %.4f |", run->mat[m->base].name, m->delta_eps, m->slab.eta_e);
            md_stat_pair(f, &r->bin[0][M_ANALYTIC][0]);
            md_num_fine(f, stat_max(&r->bin[1][M_ANALYTIC][0]));
            md_num_fine(f, stat_max(&r->bin[0][M_ANALYTIC][1]));
            md_num_fine(f, stat_max(&r->bin[0][M_EXPANSION][0]));
            md_num_fine(f, stat_max(&r->bin[1][M_EXPANSION][0]));
            md_num_fine(f, stat_max(&r->bin[0][M_EXPANSION][1]));
            for (int k = M_ANALYTIC; k <= M_EXPANSION; k++)
                fprintf(f, " %.2f / %.2f |", stat_max(&r->axis[0][k][0]), stat_max(&r->axis[1][k][0]));
            md_num(f, stat_max(&r->bin[0][M_N128][0]));
            fprintf(f, "\n");
        }
    }

    /* A coarse per-angle view of the two fast methods (every 5° or so; the CSV has every angle). */
    int every = (int)lround(5.0 / run->theta_step_deg);
    if (every < 1) every = 1;
    for (int w = 0; w < 2; w++) {
        fprintf(f, "\n### Per angle, %s: max / mean ΔE00 over azimuths, analytic and expansion\n\n| θ |",
                w ? "reflection" : "transmission");
        for (int i = 0; i < run->nbase; i++) fprintf(f, " %s analytic | %s expansion |", run->mat[i].name, run->mat[i].name);
        fprintf(f, "\n|---|");
        for (int i = 0; i < run->nbase; i++) fprintf(f, "---|---|");
        fprintf(f, "\n");
        for (int it = 0; it < run->ntheta; it++) {
            if (it % every && it != run->ntheta - 1) continue;
            fprintf(f, "| %g |", it * run->theta_step_deg);
            for (int i = 0; i < run->nbase; i++)
                for (int k = M_ANALYTIC; k <= M_EXPANSION; k++) {
                    const acc_stat *s = &run->res[i].theta[it][k][w];
                    fprintf(f, " %.3f / %.3f |", stat_max(s), stat_mean(s));
                }
            fprintf(f, "\n");
        }
    }
    fprintf(f, "\nWall time %.1f s on %d threads", run->total_s, run->threads);
    if (run->have_cost) fprintf(f, " (of which %.1f s single-threaded cost measurement)", run->cost_s);
    fprintf(f, ".\n");
}

static void write_csv(FILE *f, const acc_run *run)
{
    fprintf(f, "material,base,delta_eps,which,method,theta_deg,mean_de00,max_de00,phi0_de00,n_azimuths\n");
    for (int i = 0; i < run->nmat; i++) {
        const acc_material *m = &run->mat[i];
        const acc_result *r = &run->res[i];
        const char *base = m->base >= 0 ? run->mat[m->base].name : "";
        for (int k = 0; k < NM; k++)
            for (int w = 0; w < 2; w++)
                for (int it = 0; it < run->ntheta; it++) {
                    const acc_stat *s = &r->theta[it][k][w];
                    if (!s->n) continue;
                    fprintf(f, "%s,%s,%.6g,%s,%s,%.6g,%.6g,%.6g,%.6g,%ld\n", m->name, base,
                            m->slab.eta_e * m->slab.eta_e - m->slab.eta_o * m->slab.eta_o, TR[w], METHOD_KEY[k],
                            it * run->theta_step_deg, stat_mean(s), s->max, r->phi0[it][k][w], s->n);
                }
    }
}

static void json_num_or_null(cJSON *o, const char *key, double v)
{
    if (v == v)
        cJSON_AddNumberToObject(o, key, v);
    else
        cJSON_AddNullToObject(o, key);
}

static cJSON *json_stat(const acc_stat *s)
{
    cJSON *o = cJSON_CreateObject();
    json_num_or_null(o, "mean", stat_mean(s));
    json_num_or_null(o, "max", stat_max(s));
    cJSON_AddNumberToObject(o, "n", (double)s->n);
    json_num_or_null(o, "frac_over_1", s->n ? (double)s->over1 / (double)s->n : NAN);
    return o;
}

static cJSON *json_array_or_nulls(const double *v, int n, int stride)
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; i < n; i++) {
        double x = v[(size_t)i * stride];
        cJSON_AddItemToArray(a, x == x ? cJSON_CreateNumber(x) : cJSON_CreateNull());
    }
    return a;
}

static cJSON *json_cost_time(const acc_cost_time *t)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "ns_per_sample", t->ns_median);
    cJSON_AddNumberToObject(o, "ns_per_sample_min", t->ns_min);
    cJSON_AddNumberToObject(o, "cpu_share", t->cpu_share);
    cJSON_AddNumberToObject(o, "iterations", (double)t->iters);
    return o;
}

static void json_cost(cJSON *root, const acc_run *run)
{
    cJSON *c = cJSON_AddObjectToObject(root, "cost");
    cJSON_AddNumberToObject(c, "states", run->cost_pool_n);
    cJSON_AddNumberToObject(c, "runs", run->cost_opts.fixed_iters > 0 ? 1 : run->cost_opts.runs);
    cJSON_AddNumberToObject(c, "min_time_s", run->cost_opts.min_time);
    cJSON_AddNumberToObject(c, "fixed_iterations", (double)run->cost_opts.fixed_iters);
    cJSON_AddNumberToObject(c, "elapsed_s", run->cost_s);
    cJSON_AddItemToObject(c, "prepare", json_cost_time(&run->cost_prepare));
    /* The order of the timed loops, for matching callgrind's dumps (one per loop). */
    cJSON *order = cJSON_AddArrayToObject(c, "order");
    cJSON_AddItemToArray(order, cJSON_CreateString("prepare"));
    cJSON *ms = cJSON_AddArrayToObject(c, "methods");
    for (int k = 0; k < NCMP; k++) {
        const acc_cost_row *r = &run->cost[k];
        char name[64];
        snprintf(name, sizeof name, "%s", METHOD_KEY[k]);
        cJSON_AddItemToArray(order, cJSON_CreateString(name));
        snprintf(name, sizeof name, "%s+prepare", METHOD_KEY[k]);
        cJSON_AddItemToArray(order, cJSON_CreateString(name));
        cJSON *o = cJSON_CreateObject();
        cJSON_AddItemToArray(ms, o);
        cJSON_AddStringToObject(o, "method", METHOD_KEY[k]);
        cJSON_AddItemToObject(o, "with_prepare", json_cost_time(&r->with_prepare));
        cJSON_AddItemToObject(o, "alone", json_cost_time(&r->alone));
        cJSON_AddNumberToObject(o, "ratio_to_analytic",
                                r->with_prepare.ns_median / run->cost[M_ANALYTIC].with_prepare.ns_median);
    }
    cJSON *bands = cJSON_AddArrayToObject(c, "by_theta");
    for (int b = 0; b < 2; b++) {
        if (!run->cost_band_n[b]) continue;
        double r[2];
        band_range(run, b, r);
        for (int q = 0; q < 4; q++) {
            char name[96];
            snprintf(name, sizeof name, "%s%s@%g-%g", q < 2 ? "analytic" : "expansion", q % 2 ? "+prepare" : "", r[0],
                     r[1]);
            cJSON_AddItemToArray(order, cJSON_CreateString(name));
        }
        cJSON *o = cJSON_CreateObject();
        cJSON_AddItemToArray(bands, o);
        cJSON_AddItemToObject(o, "theta_deg", cJSON_CreateDoubleArray(r, 2));
        cJSON_AddNumberToObject(o, "states", run->cost_band_n[b]);
        for (int q = 0; q < 2; q++) {
            cJSON *m = cJSON_AddObjectToObject(o, q ? "expansion" : "analytic");
            cJSON_AddItemToObject(m, "with_prepare", json_cost_time(&run->cost_band[b][q].with_prepare));
            cJSON_AddItemToObject(m, "alone", json_cost_time(&run->cost_band[b][q].alone));
        }
    }
}

static void json_issue5(cJSON *root, const acc_run *run)
{
    acc_issue5 e;
    issue5_eval(run, &e);
    cJSON *o = cJSON_AddObjectToObject(root, "issue5");
    cJSON_AddNumberToObject(o, "theta_max_deg", CRIT_DEG);
    cJSON *a = cJSON_AddObjectToObject(o, "a");
    cJSON_AddStringToObject(a, "criterion", "expansion vs reference, every theta 0-85 deg (grid and near-axis): max dE00 "
                                            "<= 1, at <= 3x the analytic cost per shading sample (prepare included)");
    cJSON *am = cJSON_AddArrayToObject(a, "materials");
    for (int i = 0; i < run->nbase; i++) {
        cJSON *m = cJSON_CreateObject();
        cJSON_AddItemToArray(am, m);
        cJSON_AddStringToObject(m, "name", run->mat[i].name);
        for (int w = 0; w < 2; w++) {
            cJSON *x = cJSON_AddObjectToObject(m, TR[w]);
            json_num_or_null(x, "grid_max", e.grid_max[i][w]);
            json_num_or_null(x, "near_axis_max", e.axis_max[i][w]);
            json_num_or_null(x, "theta_of_grid_max", e.theta_of_max[i][w]);
        }
    }
    cJSON_AddBoolToObject(a, "pass_T", e.pass_de[0]);
    cJSON_AddBoolToObject(a, "pass_R", e.pass_de[1]);
    if (!run->have_cost) return;
    cJSON_AddNumberToObject(a, "analytic_ns", e.ns_an);
    cJSON_AddNumberToObject(a, "expansion_ns", e.ns_ex);
    cJSON_AddNumberToObject(a, "cost_ratio", e.ratio);
    cJSON_AddNumberToObject(a, "cost_ratio_alone", e.ratio_alone);
    cJSON_AddBoolToObject(a, "pass_cost", e.pass_cost);
    cJSON_AddBoolToObject(a, "pass", e.pass_a);
    cJSON *b = cJSON_AddObjectToObject(o, "b");
    cJSON_AddStringToObject(b, "criterion", "at equal cost per sample, expansion dE00 (mean and max over the grid "
                                            "theta 0-85 deg, base materials together) >= 5x smaller than numeric");
    if (e.lo >= 0) cJSON_AddStringToObject(b, "cheaper_numeric", METHOD_KEY[e.lo]);
    if (e.hi < 0) return;
    cJSON_AddStringToObject(b, "numeric", METHOD_KEY[e.hi]);
    cJSON_AddNumberToObject(b, "numeric_ns", run->cost[e.hi].with_prepare.ns_median);
    cJSON_AddNumberToObject(b, "expansion_ns", e.ns_ex);
    for (int w = 0; w < 2; w++) {
        cJSON *x = cJSON_AddObjectToObject(b, TR[w]);
        cJSON_AddItemToObject(x, "expansion", json_stat(&e.pooled[M_EXPANSION][w]));
        cJSON_AddItemToObject(x, "numeric", json_stat(&e.pooled[e.hi][w]));
        json_num_or_null(x, "gain_mean", e.gain_mean[w]);
        json_num_or_null(x, "gain_max", e.gain_max[w]);
    }
    cJSON_AddBoolToObject(b, "pass", e.pass_b);
}

static cJSON *build_json(const acc_run *run)
{
    cJSON *root = cJSON_CreateObject();
    cJSON *cfg = cJSON_AddObjectToObject(root, "config");
    cJSON_AddNumberToObject(cfg, "theta_max_deg", (run->ntheta - 1) * run->theta_step_deg);
    cJSON_AddNumberToObject(cfg, "theta_step_deg", run->theta_step_deg);
    cJSON_AddNumberToObject(cfg, "azimuths", run->nphi);
    cJSON_AddNumberToObject(cfg, "samples_ref", run->samples_ref);
    cJSON_AddNumberToObject(cfg, "samples_check", run->samples_check);
    cJSON_AddNumberToObject(cfg, "check_step_deg", run->kcheck * run->theta_step_deg);
    cJSON_AddNumberToObject(cfg, "check_near_axis_stride", AXIS_CHECK_STRIDE);
    cJSON_AddStringToObject(cfg, "cmf", biref_cmf_kind_name(run->scfg.cmf));
    double range[2] = {run->scfg.lambda_min_nm, run->scfg.lambda_max_nm};
    cJSON_AddItemToObject(cfg, "range_nm", cJSON_CreateDoubleArray(range, 2));
    cJSON_AddStringToObject(cfg, "materials", run->materials_arg);
    double split[2] = {SPLIT_DEG, CRIT_DEG};
    cJSON_AddItemToObject(cfg, "split_deg", cJSON_CreateDoubleArray(split, 2));
    cJSON_AddNumberToObject(cfg, "chroma_min", CHROMA_MIN);
    cJSON_AddNumberToObject(cfg, "threads", run->threads);
    cJSON_AddNumberToObject(root, "elapsed_s", run->total_s);
    if (run->have_cost) json_cost(root, run);
    if (!run->sweep_done) return root;

    cJSON *mats = cJSON_AddArrayToObject(root, "materials");
    for (int i = 0; i < run->nmat; i++) {
        const acc_material *m = &run->mat[i];
        const acc_result *r = &run->res[i];
        cJSON *o = cJSON_CreateObject();
        cJSON_AddItemToArray(mats, o);
        cJSON_AddStringToObject(o, "name", m->name);
        if (m->base >= 0)
            cJSON_AddStringToObject(o, "base", run->mat[m->base].name);
        else
            cJSON_AddNullToObject(o, "base");
        cJSON_AddNumberToObject(o, "eta_o", m->slab.eta_o);
        cJSON_AddNumberToObject(o, "eta_e", m->slab.eta_e);
        cJSON_AddNumberToObject(o, "delta_eps", m->slab.eta_e * m->slab.eta_e - m->slab.eta_o * m->slab.eta_o);
        cJSON_AddItemToObject(o, "axis", json_vec3(m->slab.axis));
        cJSON_AddNumberToObject(o, "thickness_nm", m->slab.thickness_nm);
        cJSON_AddNumberToObject(o, "eta_i", m->slab.eta_i);
        cJSON *pol = cJSON_AddObjectToObject(o, "polarization");
        cJSON_AddNumberToObject(pol, "s", m->light.w_in[0]);
        cJSON_AddNumberToObject(pol, "p", m->light.w_in[1]);
        cJSON_AddStringToObject(o, "analyzer", cli_analyzer_name(m->light.mask));
        cJSON_AddNumberToObject(o, "elapsed_s", r->elapsed_s);
        cJSON *na = cJSON_AddObjectToObject(o, "near_axis");
        cJSON_AddNumberToObject(na, "psi_max_deg", r->axis_psi_max_deg);
        cJSON_AddNumberToObject(na, "samples", AXIS_NPSI * run->nphi);
        cJSON_AddNumberToObject(na, "reached", (double)r->axis_valid[0]);
        cJSON_AddNumberToObject(na, "reached_up", (double)r->axis_valid[1]);
        static const char *const BIN_KEY[NBIN] = {"low", "high", "grazing"};
        cJSON *sum = cJSON_AddObjectToObject(o, "summary");
        for (int k = 0; k < NM; k++) {
            if (k >= M_REF_CHECK && (m->base >= 0 || run->samples_check <= 0)) continue;
            cJSON *mk = cJSON_AddObjectToObject(sum, METHOD_KEY[k]);
            for (int w = 0; w < 2; w++) {
                cJSON *mw = cJSON_AddObjectToObject(mk, TR[w]);
                char key[40];
                for (int b = 0; b < NBIN; b++) {
                    cJSON_AddItemToObject(mw, BIN_KEY[b], json_stat(&r->bin[b][k][w]));
                    snprintf(key, sizeof key, "%s_chromatic", BIN_KEY[b]);
                    cJSON_AddItemToObject(mw, key, json_stat(&r->col[b][k][w]));
                }
                cJSON_AddItemToObject(mw, "near_axis", json_stat(&r->axis[0][k][w]));
                cJSON_AddItemToObject(mw, "near_axis_chromatic", json_stat(&r->axis_col[0][k][w]));
                cJSON_AddItemToObject(mw, "near_axis_up", json_stat(&r->axis[1][k][w]));
                cJSON_AddItemToObject(mw, "near_axis_up_chromatic", json_stat(&r->axis_col[1][k][w]));
            }
        }
        cJSON *pt = cJSON_AddObjectToObject(o, "per_theta");
        double *th = malloc((size_t)run->ntheta * sizeof *th);
        double *col = malloc((size_t)run->ntheta * 3 * sizeof *col);
        if (!th || !col) {
            free(th);
            free(col);
            cJSON_Delete(root);
            return NULL;
        }
        for (int it = 0; it < run->ntheta; it++) th[it] = it * run->theta_step_deg;
        cJSON_AddItemToObject(pt, "theta_deg", cJSON_CreateDoubleArray(th, run->ntheta));
        for (int k = 0; k < NM; k++) {
            if (k >= M_REF_CHECK && (m->base >= 0 || run->samples_check <= 0)) continue;
            cJSON *mk = cJSON_AddObjectToObject(pt, METHOD_KEY[k]);
            for (int w = 0; w < 2; w++) {
                for (int it = 0; it < run->ntheta; it++) {
                    const acc_stat *s = &r->theta[it][k][w];
                    col[3 * it] = stat_mean(s);
                    col[3 * it + 1] = stat_max(s);
                    col[3 * it + 2] = s->n ? r->phi0[it][k][w] : NAN;
                }
                cJSON *mw = cJSON_AddObjectToObject(mk, TR[w]);
                cJSON_AddItemToObject(mw, "mean", json_array_or_nulls(col, run->ntheta, 3));
                cJSON_AddItemToObject(mw, "max", json_array_or_nulls(col + 1, run->ntheta, 3));
                cJSON_AddItemToObject(mw, "phi0", json_array_or_nulls(col + 2, run->ntheta, 3));
            }
        }
        free(th);
        free(col);
    }

    cJSON *acc = cJSON_AddObjectToObject(root, "acceptance");
    cJSON_AddStringToObject(acc, "criterion", "analytic vs reference, theta 0-70 deg over all azimuths: mean dE00 <= 1 "
                                              "and max dE00 <= 4 (evaluated on T, the quantity of fig. 9; R reported)");
    int all_pass = 1;
    cJSON *am = cJSON_AddArrayToObject(acc, "materials");
    for (int i = 0; i < run->nbase; i++) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddItemToArray(am, o);
        cJSON_AddStringToObject(o, "name", run->mat[i].name);
        for (int w = 0; w < 2; w++) {
            cJSON *x = json_stat(&run->res[i].bin[0][M_ANALYTIC][w]);
            cJSON_AddBoolToObject(x, "pass", acceptance_pass(&run->res[i], w));
            cJSON_AddItemToObject(o, TR[w], x);
        }
        all_pass &= acceptance_pass(&run->res[i], 0);
    }
    cJSON_AddBoolToObject(acc, "pass", all_pass);
    json_issue5(root, run);
    return root;
}

/* ------------------------------------------------------------------------------------------ */
/* Figures                                                                                     */
/* ------------------------------------------------------------------------------------------ */

static int write_plots(const acc_run *run, const char *dir)
{
    char path[4096];
    acc_issue5 e;
    issue5_eval(run, &e);
    if (run->have_cost) {
        acc_plot_cost_point p[NCMP];
        for (int k = 0; k < NCMP; k++) {
            /* The numeric family is labelled by its sample count; the other methods by the legend. */
            p[k].label = k == M_GT ? "16384 = ground truth" : k >= M_N3 ? METHOD_KEY[k] + strlen("numeric-") : NULL;
            p[k].style = k == M_ANALYTIC    ? ACC_STYLE_ANALYTIC
                         : k == M_EXPANSION ? ACC_STYLE_EXPANSION
                         : k == M_GT        ? ACC_STYLE_GROUND_TRUTH
                                            : ACC_STYLE_NUMERIC;
            p[k].ns = run->cost[k].with_prepare.ns_median;
            for (int w = 0; w < 2; w++) {
                p[k].mean[w] = stat_mean(&e.pooled[k][w]);
                p[k].max[w] = stat_max(&e.pooled[k][w]);
            }
        }
        char note[256];
        snprintf(note, sizeof note,
                 "materials %s%s%s together, θ 0-%g°, %d azimuths; reference: numeric, %d samples", run->mat[0].name,
                 run->nbase > 1 ? "…" : "", run->nbase > 1 ? run->mat[run->nbase - 1].name : "",
                 fmin(CRIT_DEG, (run->ntheta - 1) * run->theta_step_deg), run->nphi, run->samples_ref);
        snprintf(path, sizeof path, "%s/accuracy_vs_cost.png", dir);
        if (acc_plot_vs_cost(path, p, NCMP, note)) return -1;
    }
    /* ΔE00 against θ for the methods the issue discusses (and the paper's ground truth, whose
     * aliasing on the 3.5 mm slab shows here). */
    static const int METH[] = {M_ANALYTIC, M_EXPANSION, M_N32, M_N128, M_GT};
    enum { NMETH = sizeof METH / sizeof METH[0] };
    static const int COLOR[NMETH] = {FIG_RED, FIG_BLUE, FIG_GREEN, FIG_ORANGE, FIG_PURPLE};
    const char *names[NMETH];
    for (int q = 0; q < NMETH; q++) names[q] = METHOD_KEY[METH[q]];
    const int nm = run->nbase;
    const size_t n = (size_t)nm * NMETH * 2 * (size_t)run->ntheta;
    double *mean = malloc(n * sizeof *mean), *max = malloc(n * sizeof *max),
           *th = malloc((size_t)run->ntheta * sizeof *th);
    char(*titles)[160] = malloc((size_t)nm * sizeof *titles);
    const char **tp = malloc((size_t)nm * sizeof *tp);
    if (!mean || !max || !th || !titles || !tp) {
        free(mean), free(max), free(th), free(titles), free(tp);
        return cli_error(CMD, "out of memory"), -1;
    }
    for (int it = 0; it < run->ntheta; it++) th[it] = it * run->theta_step_deg;
    for (int i = 0; i < nm; i++) {
        const biref_slab *s = &run->mat[i].slab;
        snprintf(titles[i], sizeof titles[i], "%s (%.4g mm)", run->mat[i].name, s->thickness_nm / 1e6);
        tp[i] = titles[i];
        for (int q = 0; q < NMETH; q++)
            for (int w = 0; w < 2; w++)
                for (int it = 0; it < run->ntheta; it++) {
                    const acc_stat *s2 = &run->res[i].theta[it][METH[q]][w];
                    const size_t idx = ((size_t)(i * NMETH + q) * 2 + (size_t)w) * (size_t)run->ntheta + (size_t)it;
                    mean[idx] = stat_mean(s2);
                    max[idx] = stat_max(s2);
                }
    }
    acc_plot_theta_data d = {nm, NMETH, run->ntheta, tp, names, COLOR, th, mean, max, CRIT_DEG};
    snprintf(path, sizeof path, "%s/accuracy_vs_theta.png", dir);
    int rc = acc_plot_vs_theta(path, &d);
    free(mean), free(max), free(th), free(titles), free(tp);
    return rc;
}

/* ------------------------------------------------------------------------------------------ */
/* Command                                                                                     */
/* ------------------------------------------------------------------------------------------ */

static void help(void)
{
    printf("usage: biref accuracy [OPTIONS]\n\n"
           "CIEDE2000 difference between spectral integration methods and a reference, as a function of\n"
           "the angle of incidence, for the paper's fig. 9 materials with their light. Methods: the\n"
           "paper's analytic approximation (eq. 26), the exact integral of the path-group expansion\n"
           "(default options), numeric integration with 3, 8, 16, 32, 64 and 128 samples, and the\n"
           "paper's ground truth (numeric, 16384 samples). Reference: numeric integration with\n"
           "--reference-samples samples, itself tested against 4x as many on a subset. Each angle is\n"
           "evaluated at several azimuths of the optic axis about the slab normal, as for the pixels of a\n"
           "rendered slab; two more sample sets aim at the directions close to the optic axis, where\n"
           "mm-thick slabs show their colours. Tables on stdout (markdown) unless --json. Method and\n"
           "results: docs/ACCURACY.md.\n\n"
           "Options:\n"
           "  --materials M          fig9 (default: the three materials of fig. 9 with their light)\n"
           "                         or a JSON file: [{\"name\", \"eta_o\", \"eta_e\", \"axis\": [a,b,c],\n"
           "                         \"thickness_mm\" (or _um, _nm), \"eta_i\", \"polarization\": \"0.75,0.25\",\n"
           "                         \"analyzer\": \"none\"|\"s\"|\"p\"}, ...]\n"
           "  --sweep-delta-eps L    comma-separated eps_e - eps_o values applied to every material\n"
           "                         (eta_o kept, eta_e varied), or none (default none)\n"
           "  --theta-max-deg A      largest angle of incidence, 0 <= A < 90 (default 89)\n"
           "  --theta-step-deg S     angle step, > 0 (default 1)\n"
           "  --azimuths N           azimuths of the optic axis per angle, and directions around the\n"
           "                         axis per ring of the near-axis sets (default 16)\n"
           "  --reference-samples N  samples of the reference integration (default %d)\n"
           "  --samples-ref N        the same (older name)\n"
           "  --samples-check N      denser integration to test the reference, 0 = off (default 4x the\n"
           "                         reference; base materials, every --check-step-deg of the grid, the\n"
           "                         largest angle, and every %dth near-axis sample)\n"
           "  --check-step-deg S     angle step of that test (default 5)\n"
           "  --cost                 also measure the cost per shading sample of every method, on one\n"
           "                         thread, before the sweep, on the grid's states up to 85 deg (adds\n"
           "                         about a minute); needed for the issue #5 verdicts\n"
           "  --cost-only            only that measurement, no accuracy sweep\n"
           "  --cost-min-time S      seconds per timed run (default 0.3)\n"
           "  --cost-runs N          timed runs per method, median reported (default 5)\n"
           "  --cost-iterations N    one run of exactly N samples per method, no calibration: for\n"
           "                         valgrind --tool=callgrind --toggle-collect=acc_cost_loop\n"
           "                         --dump-after=acc_cost_loop (one dump per loop, order in --json;\n"
           "                         scripts/accuracy_callgrind.sh does this)\n"
           "  --plot-dir DIR         write DIR/accuracy_vs_theta.png and, with --cost,\n"
           "                         DIR/accuracy_vs_cost.png\n"
           "  --cmf C                cie1931 (default) or wyman2013\n"
           "  --range-nm MIN,MAX     integration band (default 380,700)\n"
           "  --threads T            OpenMP threads (default: all cores)\n"
           "  --progress             progress on stderr also when it is not a terminal\n"
           "  --csv FILE             per-angle statistics of every method and material\n"
           "  --markdown FILE        write the tables to FILE\n"
           "  --json                 machine-readable output on stdout\n"
           "  -h, --help             this help\n",
           DEFAULT_REFERENCE_SAMPLES, AXIS_CHECK_STRIDE);
}

enum {
    OPT_MATERIALS = 2000,
    OPT_SWEEP,
    OPT_THETA_MAX,
    OPT_THETA_STEP,
    OPT_AZIMUTHS,
    OPT_SAMPLES_REF,
    OPT_SAMPLES_CHECK,
    OPT_CHECK_STEP,
    OPT_COST,
    OPT_COST_ONLY,
    OPT_COST_MIN_TIME,
    OPT_COST_RUNS,
    OPT_COST_ITERS,
    OPT_PLOT_DIR,
    OPT_CMF,
    OPT_RANGE,
    OPT_THREADS,
    OPT_PROGRESS,
    OPT_CSV,
    OPT_MARKDOWN,
    OPT_JSON
};

static FILE *open_out(const char *opt, const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f) cli_error(CMD, "%s: cannot write '%s': %s", opt, path, strerror(errno));
    return f;
}

static int close_out(const char *opt, const char *path, FILE *f)
{
    int bad = ferror(f);
    if (fclose(f) != 0 || bad) return cli_error(CMD, "%s: error writing '%s'", opt, path), -1;
    return 0;
}

int cmd_accuracy(int argc, char **argv)
{
    acc_run run;
    memset(&run, 0, sizeof run);
    run.theta_max_deg = 89.0;
    run.theta_step_deg = 1.0;
    run.check_step_deg = 5.0;
    run.nphi = 16;
    run.samples_ref = DEFAULT_REFERENCE_SAMPLES;
    run.samples_check = -1; /* 4x the reference unless given */
    run.materials_arg = "fig9";
    run.cost_opts = (acc_cost_opts){0.3, 5, 0, 0};
    biref_spectral_config_default(&run.scfg);
    double sweep[MAX_SWEEP];
    int nsweep = 0, cost = 0, cost_only = 0, progress = 0;
    long threads = 0;
    const char *csv_path = NULL, *md_path = NULL, *plot_dir = NULL;
    int json = 0;
    static const struct option longopts[] = {{"materials", required_argument, 0, OPT_MATERIALS},
                                             {"sweep-delta-eps", required_argument, 0, OPT_SWEEP},
                                             {"theta-max-deg", required_argument, 0, OPT_THETA_MAX},
                                             {"theta-step-deg", required_argument, 0, OPT_THETA_STEP},
                                             {"azimuths", required_argument, 0, OPT_AZIMUTHS},
                                             {"reference-samples", required_argument, 0, OPT_SAMPLES_REF},
                                             {"samples-ref", required_argument, 0, OPT_SAMPLES_REF},
                                             {"samples-check", required_argument, 0, OPT_SAMPLES_CHECK},
                                             {"check-step-deg", required_argument, 0, OPT_CHECK_STEP},
                                             {"cost", no_argument, 0, OPT_COST},
                                             {"cost-only", no_argument, 0, OPT_COST_ONLY},
                                             {"cost-min-time", required_argument, 0, OPT_COST_MIN_TIME},
                                             {"cost-runs", required_argument, 0, OPT_COST_RUNS},
                                             {"cost-iterations", required_argument, 0, OPT_COST_ITERS},
                                             {"plot-dir", required_argument, 0, OPT_PLOT_DIR},
                                             {"cmf", required_argument, 0, OPT_CMF},
                                             {"range-nm", required_argument, 0, OPT_RANGE},
                                             {"threads", required_argument, 0, OPT_THREADS},
                                             {"progress", no_argument, 0, OPT_PROGRESS},
                                             {"csv", required_argument, 0, OPT_CSV},
                                             {"markdown", required_argument, 0, OPT_MARKDOWN},
                                             {"json", no_argument, 0, OPT_JSON},
                                             {"help", no_argument, 0, 'h'},
                                             {0, 0, 0, 0}};
    opterr = 0;
    optind = 1;
    int c;
    long v;
    while ((c = getopt_long(argc, argv, ":h", longopts, NULL)) != -1) {
        switch (c) {
        case 'h': help(); return CLI_EXIT_OK;
        case OPT_MATERIALS: run.materials_arg = optarg; break;
        case OPT_SWEEP:
            if (parse_sweep(optarg, sweep, &nsweep)) return CLI_EXIT_USAGE;
            break;
        case OPT_THETA_MAX:
            if (cli_parse_double(CMD, "--theta-max-deg", optarg, &run.theta_max_deg)) return CLI_EXIT_USAGE;
            if (run.theta_max_deg < 0.0 || run.theta_max_deg >= 90.0)
                return cli_error(CMD, "--theta-max-deg: need 0 <= A < 90, got %g", run.theta_max_deg), CLI_EXIT_USAGE;
            break;
        case OPT_THETA_STEP:
            if (cli_parse_double(CMD, "--theta-step-deg", optarg, &run.theta_step_deg)) return CLI_EXIT_USAGE;
            if (run.theta_step_deg <= 0.0)
                return cli_error(CMD, "--theta-step-deg: must be positive, got %g", run.theta_step_deg), CLI_EXIT_USAGE;
            break;
        case OPT_CHECK_STEP:
            if (cli_parse_double(CMD, "--check-step-deg", optarg, &run.check_step_deg)) return CLI_EXIT_USAGE;
            if (run.check_step_deg <= 0.0)
                return cli_error(CMD, "--check-step-deg: must be positive, got %g", run.check_step_deg), CLI_EXIT_USAGE;
            break;
        case OPT_AZIMUTHS:
            if (cli_parse_int(CMD, "--azimuths", optarg, 1, 3600, &v)) return CLI_EXIT_USAGE;
            run.nphi = (int)v;
            break;
        case OPT_SAMPLES_REF:
            if (cli_parse_int(CMD, "--reference-samples", optarg, 1, MAX_SAMPLES, &v)) return CLI_EXIT_USAGE;
            run.samples_ref = (int)v;
            break;
        case OPT_SAMPLES_CHECK:
            if (cli_parse_int(CMD, "--samples-check", optarg, 0, MAX_SAMPLES, &v)) return CLI_EXIT_USAGE;
            run.samples_check = (int)v;
            break;
        case OPT_COST: cost = 1; break;
        case OPT_COST_ONLY: cost = cost_only = 1; break;
        case OPT_COST_MIN_TIME:
            if (cli_parse_double(CMD, "--cost-min-time", optarg, &run.cost_opts.min_time)) return CLI_EXIT_USAGE;
            if (run.cost_opts.min_time <= 0.0 || run.cost_opts.min_time > 60.0)
                return cli_error(CMD, "--cost-min-time: need 0 < S <= 60, got %g", run.cost_opts.min_time),
                       CLI_EXIT_USAGE;
            break;
        case OPT_COST_RUNS:
            if (cli_parse_int(CMD, "--cost-runs", optarg, 1, 64, &v)) return CLI_EXIT_USAGE;
            run.cost_opts.runs = (int)v;
            break;
        case OPT_COST_ITERS:
            if (cli_parse_int(CMD, "--cost-iterations", optarg, 1, 1000000000L, &v)) return CLI_EXIT_USAGE;
            run.cost_opts.fixed_iters = v;
            break;
        case OPT_PLOT_DIR: plot_dir = optarg; break;
        case OPT_CMF:
            if (biref_cmf_kind_from_name(optarg, &run.scfg.cmf) != BIREF_OK)
                return cli_error(CMD, "--cmf: expected cie1931 or wyman2013, got '%s'", optarg), CLI_EXIT_USAGE;
            break;
        case OPT_RANGE: {
            double r2[2];
            if (cli_parse_range_nm(CMD, "--range-nm", optarg, r2)) return CLI_EXIT_USAGE;
            run.scfg.lambda_min_nm = r2[0];
            run.scfg.lambda_max_nm = r2[1];
            break;
        }
        case OPT_THREADS:
            if (cli_parse_int(CMD, "--threads", optarg, 1, 1024, &threads)) return CLI_EXIT_USAGE;
            break;
        case OPT_PROGRESS: progress = 1; break;
        case OPT_CSV: csv_path = optarg; break;
        case OPT_MARKDOWN: md_path = optarg; break;
        case OPT_JSON: json = 1; break;
        default: cli_getopt_error(CMD, c, argv); return CLI_EXIT_USAGE;
        }
    }
    if (optind < argc) return cli_error(CMD, "unexpected argument '%s'", argv[optind]), CLI_EXIT_USAGE;
    if (cost_only && (csv_path || plot_dir))
        return cli_error(CMD, "--cost-only: no accuracy sweep, so no --csv or --plot-dir"), CLI_EXIT_USAGE;
    if ((run.cost_opts.fixed_iters > 0) && !cost)
        return cli_error(CMD, "--cost-iterations: needs --cost or --cost-only"), CLI_EXIT_USAGE;
    if (plot_dir) {
        struct stat sb;
        if (stat(plot_dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
            return cli_error(CMD, "--plot-dir: '%s' is not a directory", plot_dir), CLI_EXIT_USAGE;
    }
    /* The check defaults to 4x the reference: a midpoint rule that has converged changes by far
     * less than the error it had when the samples are quadrupled. */
    if (run.samples_check < 0)
        run.samples_check = run.samples_ref <= MAX_SAMPLES / 4 ? 4 * run.samples_ref : 0;
    run.ntheta = (int)floor(run.theta_max_deg / run.theta_step_deg + 1e-9) + 1;
    if (run.ntheta > 100000)
        return cli_error(CMD, "--theta-step-deg: %g gives more than 100000 angles", run.theta_step_deg), CLI_EXIT_USAGE;
    run.kcheck = (int)lround(run.check_step_deg / run.theta_step_deg);
    if (run.kcheck < 1) run.kcheck = 1;

    /* Materials: the bases, then one variant per (base, Δε). */
    acc_material base[MAX_BASE];
    if (!strcmp(run.materials_arg, "fig9"))
        run.nbase = builtin_fig9(base);
    else if (load_materials(run.materials_arg, base, MAX_BASE, &run.nbase))
        return CLI_EXIT_USAGE;
    run.nmat = run.nbase * (1 + nsweep);
    run.mat = calloc((size_t)run.nmat, sizeof *run.mat);
    run.res = calloc((size_t)run.nmat, sizeof *run.res);
    if (!run.mat || !run.res) {
        free(run.mat);
        free(run.res);
        return cli_error(CMD, "out of memory"), CLI_EXIT_FAIL;
    }
    int rc = CLI_EXIT_USAGE;
    biref_spectral *sp = NULL;
    enum { NPLANS = NNUM + 3 }; /* reference, numeric-3..128, ground truth, check */
    biref_numeric_plan *plans[NPLANS] = {0};
    FILE *csv = NULL, *md = NULL;
    for (int i = 0; i < run.nbase; i++) {
        run.mat[i] = base[i];
        biref_axis_normalize(base[i].slab.axis, run.mat[i].slab.axis);
        run.mat[i].delta_eps = base[i].slab.eta_e * base[i].slab.eta_e - base[i].slab.eta_o * base[i].slab.eta_o;
    }
    for (int i = 0; i < run.nbase; i++)
        for (int k = 0; k < nsweep; k++) {
            acc_material *m = &run.mat[run.nbase + i * nsweep + k];
            *m = run.mat[i];
            m->base = i;
            m->delta_eps = sweep[k];
            double e2 = m->slab.eta_o * m->slab.eta_o + sweep[k];
            if (!(e2 > 0.0)) {
                cli_error(CMD, "--sweep-delta-eps: %g makes eps_e <= 0 for material %s", sweep[k], m->name);
                goto done;
            }
            m->slab.eta_e = sqrt(e2);
            snprintf(m->name, sizeof m->name, "%.40s:de%+.3g", base[i].name, sweep[k]);
        }

    /* Open the outputs first: a bad path should fail now, not after minutes of computation. */
    if (csv_path && !(csv = open_out("--csv", csv_path))) goto done;
    if (md_path && !(md = open_out("--markdown", md_path))) goto done;

    biref_status s = biref_spectral_create(&run.scfg, &sp);
    if (s == BIREF_ERR_INVALID) {
        cli_error(CMD, "--range-nm: the colour-matching functions are zero on %g-%g nm", run.scfg.lambda_min_nm,
                  run.scfg.lambda_max_nm);
        goto done;
    }
    rc = CLI_EXIT_FAIL;
    if (s != BIREF_OK) {
        cli_error(CMD, "spectral context: %s", biref_status_string(s));
        goto done;
    }
    int plan_n[NPLANS];
    plan_n[0] = cost_only ? 0 : run.samples_ref;
    for (int k = 0; k < NNUM; k++) plan_n[1 + k] = NUMERIC_N[k];
    plan_n[NNUM + 1] = BIREF_GROUND_TRUTH_SAMPLES;
    plan_n[NNUM + 2] = cost_only ? 0 : run.samples_check;
    for (int k = 0; k < NPLANS; k++) {
        if (plan_n[k] <= 0) continue;
        s = biref_numeric_plan_create(sp, plan_n[k], &plans[k]);
        if (s != BIREF_OK) {
            cli_error(CMD, "numeric plan (%d samples): %s", plan_n[k], biref_status_string(s));
            goto done;
        }
    }
    acc_plans pl;
    memset(&pl, 0, sizeof pl);
    pl.sp = sp;
    pl.ref = plans[0];
    for (int k = 0; k < NNUM; k++) pl.num[k] = plans[1 + k];
    pl.gt = plans[NNUM + 1];
    pl.check = plans[NNUM + 2];
    biref_expansion_opts_default(&pl.xopts);

    const int tty = isatty(STDERR_FILENO);
    run.cost_opts.progress = tty || progress;
    /* Cost first: on one thread, before any OpenMP team exists whose idle workers could spin on the
     * other core while it is timed. */
    if (cost && measure_cost(&run, &pl)) goto done;

    if (threads > 0) omp_set_num_threads((int)threads);
    run.threads = omp_get_max_threads();
    acc_progress pg = {tty || progress, tty, 0,
                       (long)run.nmat * ((long)run.ntheta + AXIS_SETS * AXIS_NPSI) * run.nphi, omp_get_wtime(), 0.0};
    if (!cost_only) {
        for (int i = 0; i < run.nmat; i++)
            if (run_material(&run, &pl, i, &pg)) goto done;
        run.sweep_done = 1;
    }
    run.total_s = omp_get_wtime() - pg.t0 + run.cost_s;
    if (pg.on) fprintf(stderr, "%sbiref accuracy: done in %.1f s on %d threads%30s\n", tty ? "\r" : "", run.total_s,
                       run.threads, "");

    if (plot_dir && write_plots(&run, plot_dir)) goto done;
    if (csv) {
        write_csv(csv, &run);
        int e = close_out("--csv", csv_path, csv);
        csv = NULL;
        if (e) goto done;
    }
    if (md) {
        fprintf(md, "## biref accuracy\n\n");
        write_markdown(md, &run);
        int e = close_out("--markdown", md_path, md);
        md = NULL;
        if (e) goto done;
    }
    if (json) {
        cJSON *root = build_json(&run);
        if (!root) {
            cli_error(CMD, "out of memory");
            goto done;
        }
        if (json_print_and_free(root)) goto done;
    } else {
        write_markdown(stdout, &run);
    }
    rc = CLI_EXIT_OK;

done:
    if (csv) fclose(csv), remove(csv_path);
    if (md) fclose(md), remove(md_path);
    for (int k = 0; k < NPLANS; k++) biref_numeric_plan_destroy(plans[k]);
    biref_spectral_destroy(sp);
    for (int i = 0; i < run.nmat; i++) {
        free(run.res[i].theta);
        free(run.res[i].phi0);
    }
    free(run.mat);
    free(run.res);
    return rc;
}
