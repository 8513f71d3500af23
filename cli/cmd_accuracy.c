/* biref accuracy: CIEDE2000 of the analytic approximation (paper eq. 26) and of cheap numeric
 * integrations against the ground truth (numeric, 16384 samples, paper §6), as a function of
 * the angle of incidence, for the paper's fig. 9 materials and a fig. 7-like sweep over Δε.
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
#include <unistd.h>

#include "cli_common.h"
#include "cli_light.h"
#include "commands.h"
#include "json_out.h"

static const char *const CMD = "accuracy";

#define SPLIT_DEG 70.0 /* the paper: eq. 26 is accurate "except at grazing angles, θ > 70°" */
/* Most (θ, φ) of a mm slab are nearly white (or, between crossed polarisers, nearly black), where
 * every method agrees; a second set of statistics keeps only the directions whose reference colour
 * is visibly chromatic (CIELAB chroma against white E at least this), the iridescent ones. */
#define CHROMA_MIN 5.0
#define MAX_BASE 32
#define MAX_SWEEP 16
#define MAX_SAMPLES (1 << 24)
#define MAX_FILE_BYTES (1 << 20)

/* ------------------------------------------------------------------------------------------ */
/* Methods compared                                                                            */
/* ------------------------------------------------------------------------------------------ */

enum { M_ANALYTIC, M_N8, M_N32, M_N128, M_REF_CHECK, M_AN_CHECK, NM };
/* ref-vs-check: the reference against a denser integration; analytic-vs-check: the analytic
 * method against that denser integration (tells reference error from method error). */
static const char *const METHOD_KEY[NM] = {"analytic",    "numeric-8",    "numeric-32",
                                           "numeric-128", "ref-vs-check", "analytic-vs-check"};
static const int NUMERIC_N[3] = {8, 32, 128};
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

typedef struct {
    acc_stat (*theta)[NM][2]; /* [ntheta]: over azimuths */
    double (*phi0)[NM][2];    /* [ntheta]: the unrotated axis (NaN where not computed) */
    acc_stat bin[2][NM][2];      /* [θ <= 70°, θ > 70°]: over (θ, φ) */
    acc_stat col[2][NM][2];      /* the same, chromatic reference colours only (CHROMA_MIN) */
    acc_stat axis[2][NM][2];     /* the near-axis sample sets (axis_sample), [down, up legs] */
    acc_stat axis_col[2][NM][2]; /* and their chromatic parts */
    double axis_psi_max_deg;
    long axis_valid[2];          /* near-axis samples reachable within theta_max */
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
    const biref_numeric_plan *ref, *num[3], *check;
} acc_plans;

/* The denser check integration costs 4x the reference: only base materials, every kcheck-th θ. */
static inline int computed(const acc_run *run, const acc_material *m, int it, int method)
{
    if (method == M_REF_CHECK || method == M_AN_CHECK)
        return run->samples_check > 0 && m->base < 0 && it % run->kcheck == 0;
    return 1;
}

static void stat_add(acc_stat *s, double v)
{
    s->sum += v;
    if (v > s->max) s->max = v;
    s->n++;
    s->over1 += v > 1.0;
}

static double stat_mean(const acc_stat *s) { return s->n ? s->sum / (double)s->n : NAN; }

/* Progress on a terminal only: stderr is for the one-line error otherwise. */
typedef struct {
    int on;
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
    if (now - pg->last < 0.5 && d != pg->total) return;
    pg->last = now;
    fprintf(stderr, "\rbiref accuracy: %3.0f%%  material %-16s %6.1f s", 100.0 * (double)d / (double)pg->total, name,
            now - pg->t0);
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
#define AXIS_SETS 2
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

/* ΔE00 of every method for incidence θ with the axis rotated by φ about y: de[method][T/R], NaN
 * where not computed, and the chroma of the reference colours. Returns 0, or -1 if a spectrum
 * came out non-finite. */
static int evaluate_point(const acc_plans *pl, const acc_material *m, double theta, double phi, int with_check,
                          double de[NM][2], double chroma[2])
{
    for (int k = 0; k < NM; k++) de[k][0] = de[k][1] = NAN;
    biref_slab s = m->slab;
    const double *A = m->slab.axis, c = cos(phi), sn = sin(phi);
    s.axis[0] = c * A[0] + sn * A[2];
    s.axis[1] = A[1];
    s.axis[2] = -sn * A[0] + c * A[2];
    biref_slab_state st;
    if (biref_slab_prepare(&s, theta, &st) != BIREF_OK) return -1;

    biref_spectrum ref, x;
    double ref_mix[2][3], x_mix[2][3];
    biref_spectrum_numeric(pl->ref, &st, &ref);
    biref_spectrum_mix(ref.T, m->light.w_in, m->light.mask, ref_mix[0]);
    biref_spectrum_mix(ref.R, m->light.w_in, m->light.mask, ref_mix[1]);
    for (int w = 0; w < 2; w++) {
        double lab[3];
        biref_xyz_to_lab(ref_mix[w], NULL, lab);
        chroma[w] = hypot(lab[1], lab[2]);
    }

    double an_mix[2][3];
    biref_spectrum_analytic(pl->sp, &st, &x);
    biref_spectrum_mix(x.T, m->light.w_in, m->light.mask, an_mix[0]);
    biref_spectrum_mix(x.R, m->light.w_in, m->light.mask, an_mix[1]);
    for (int w = 0; w < 2; w++) de[M_ANALYTIC][w] = biref_delta_e00_xyz(ref_mix[w], an_mix[w]);

    for (int k = 0; k < 3; k++) {
        biref_spectrum_numeric(pl->num[k], &st, &x);
        biref_spectrum_mix(x.T, m->light.w_in, m->light.mask, x_mix[0]);
        biref_spectrum_mix(x.R, m->light.w_in, m->light.mask, x_mix[1]);
        for (int w = 0; w < 2; w++) de[M_N8 + k][w] = biref_delta_e00_xyz(ref_mix[w], x_mix[w]);
    }
    if (with_check) {
        /* Is the reference itself converged? Compare it, and the analytic result, with a
         * denser integration (aliasing of the Fabry–Pérot terms in mm slabs, docs/ACCURACY.md). */
        biref_spectrum_numeric(pl->check, &st, &x);
        biref_spectrum_mix(x.T, m->light.w_in, m->light.mask, x_mix[0]);
        biref_spectrum_mix(x.R, m->light.w_in, m->light.mask, x_mix[1]);
        for (int w = 0; w < 2; w++) {
            de[M_REF_CHECK][w] = biref_delta_e00_xyz(x_mix[w], ref_mix[w]);
            de[M_AN_CHECK][w] = biref_delta_e00_xyz(x_mix[w], an_mix[w]);
        }
    }
    for (int k = 0; k < (with_check ? NM : M_REF_CHECK); k++)
        for (int w = 0; w < 2; w++)
            if (!isfinite(de[k][w])) return -1;
    return 0;
}

static int run_material(acc_run *run, const acc_plans *pl, int mi, acc_progress *pg)
{
    const acc_material *m = &run->mat[mi];
    acc_result *r = &run->res[mi];
    /* Jobs: the (θ, φ) grid, then the near-axis set, in one loop so that threads stay busy. */
    const long ngrid = (long)run->ntheta * run->nphi, naxis = (long)AXIS_NPSI * run->nphi,
               njobs = ngrid + AXIS_SETS * naxis;
    double(*de)[NM][2] = malloc((size_t)njobs * sizeof *de);
    double(*chroma)[2] = malloc((size_t)njobs * sizeof *chroma);
    char *valid = malloc((size_t)njobs);
    r->theta = calloc((size_t)run->ntheta, sizeof *r->theta);
    r->phi0 = malloc((size_t)run->ntheta * sizeof *r->phi0);
    if (!de || !chroma || !valid || !r->theta || !r->phi0) {
        free(de);
        free(chroma);
        free(valid);
        return cli_error(CMD, "out of memory"), -1;
    }
    const double t0 = omp_get_wtime();
    long bad = -1;
    double bad_theta = 0, bad_phi = 0;
#pragma omp parallel for schedule(dynamic, 4)
    for (long j = 0; j < njobs; j++) {
        double theta, phi;
        int check;
        if (j < ngrid) {
            const int it = (int)(j / run->nphi);
            theta = it * run->theta_step_deg * M_PI / 180.0;
            phi = 2.0 * M_PI * (double)(j % run->nphi) / run->nphi;
            check = computed(run, m, it, M_REF_CHECK);
            valid[j] = 1;
        } else {
            valid[j] = (char)axis_sample(run, m, (int)((j - ngrid) / naxis), (int)((j - ngrid) % naxis), &theta, &phi);
            check = run->samples_check > 0 && m->base < 0;
        }
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
        free(valid);
        return cli_error(CMD, "material %s: non-finite result at theta %g deg, axis azimuth %g deg", m->name,
                         bad_theta * 180.0 / M_PI, bad_phi * 180.0 / M_PI),
               -1;
    }
    /* Serial aggregation keeps the sums independent of the thread count. */
    for (int it = 0; it < run->ntheta; it++) {
        const int hi = it * run->theta_step_deg > SPLIT_DEG + 1e-9;
        for (int k = 0; k < NM; k++)
            for (int w = 0; w < 2; w++) {
                r->phi0[it][k][w] = de[(long)it * run->nphi][k][w];
                if (!computed(run, m, it, k)) continue;
                for (int ip = 0; ip < run->nphi; ip++) {
                    const long j = (long)it * run->nphi + ip;
                    stat_add(&r->theta[it][k][w], de[j][k][w]);
                    stat_add(&r->bin[hi][k][w], de[j][k][w]);
                    if (chroma[j][w] >= CHROMA_MIN) stat_add(&r->col[hi][k][w], de[j][k][w]);
                }
            }
    }
    r->axis_psi_max_deg = axis_psi_max(m) * 180.0 / M_PI;
    for (long j = ngrid; j < njobs; j++) {
        if (!valid[j]) continue;
        const int set = (int)((j - ngrid) / naxis);
        r->axis_valid[set]++;
        for (int k = 0; k < NM; k++)
            for (int w = 0; w < 2; w++)
                if (k < M_REF_CHECK || (run->samples_check > 0 && m->base < 0)) {
                    stat_add(&r->axis[set][k][w], de[j][k][w]);
                    if (chroma[j][w] >= CHROMA_MIN) stat_add(&r->axis_col[set][k][w], de[j][k][w]);
                }
    }
    free(de);
    free(chroma);
    free(valid);
    return 0;
}

/* ------------------------------------------------------------------------------------------ */
/* Output                                                                                      */
/* ------------------------------------------------------------------------------------------ */

static void bin_label(const acc_run *run, int hi, char *buf, size_t len)
{
    double lo_end = run->theta_max_deg < SPLIT_DEG ? (run->ntheta - 1) * run->theta_step_deg : SPLIT_DEG;
    if (!hi)
        snprintf(buf, len, "0-%g°", lo_end);
    else
        snprintf(buf, len, "%g-%g°", SPLIT_DEG, (run->ntheta - 1) * run->theta_step_deg);
}

static void md_num(FILE *f, double v)
{
    if (v == v)
        fprintf(f, " %.2f |", v);
    else
        fprintf(f, " – |");
}

static void md_stat_pair(FILE *f, const acc_stat *s)
{
    md_num(f, stat_mean(s));
    md_num(f, s->n ? s->max : NAN);
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

static int acceptance_pass(const acc_result *r, int w)
{
    const acc_stat *s = &r->bin[0][M_ANALYTIC][w];
    return s->n > 0 && stat_mean(s) <= 1.0 && s->max <= 4.0;
}

static void write_markdown(FILE *f, const acc_run *run)
{
    char lo[32], hi[32], lb[96];
    bin_label(run, 0, lo, sizeof lo);
    bin_label(run, 1, hi, sizeof hi);
    fprintf(f, "Reference: numeric integration of eq. 17 with %d samples (ground truth); CMF %s, %g-%g nm.\n",
            run->samples_ref, biref_cmf_kind_name(run->scfg.cmf), run->scfg.lambda_min_nm, run->scfg.lambda_max_nm);
    fprintf(f, "Angles θ = 0-%g° in steps of %g°, %d azimuths of the optic axis about the slab normal.\n",
            (run->ntheta - 1) * run->theta_step_deg, run->theta_step_deg, run->nphi);
    fprintf(f, "ΔE00 of the mixed colour (each material's light) against the reference, mean and max over (θ, φ).\n\n");

    fprintf(f, "### Materials\n\n| material | η_o | η_e | Δε | axis | d (mm) | light |\n|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < run->nbase; i++) {
        const acc_material *m = &run->mat[i];
        const biref_slab *s = &m->slab;
        fprintf(f, "| %s | %.4g | %.4g | %+.4f | (%.3f, %.3f, %.3f) | %.4g | %s |\n", m->name, s->eta_o, s->eta_e,
                s->eta_e * s->eta_e - s->eta_o * s->eta_o, s->axis[0], s->axis[1], s->axis[2], s->thickness_nm / 1e6,
                light_desc(&m->light, lb, sizeof lb));
    }
    fprintf(f, "\n### ΔE00 against the reference\n\n"
               "Mean, max and share (%%) of samples with ΔE00 > 1, over all (θ, φ) of each range.\n\n"
               "| material | | method | mean %s | max %s | %% >1 %s | mean %s | max %s | %% >1 %s |\n"
               "|---|---|---|---|---|---|---|---|---|\n",
            lo, lo, lo, hi, hi, hi);
    for (int i = 0; i < run->nbase; i++)
        for (int w = 0; w < 2; w++)
            for (int k = 0; k <= M_N128; k++) {
                const acc_result *r = &run->res[i];
                fprintf(f, "| %s | %s | %s |", run->mat[i].name, TR[w], METHOD_KEY[k]);
                for (int b = 0; b < 2; b++) {
                    md_stat_pair(f, &r->bin[b][k][w]);
                    md_pct(f, r->bin[b][k][w].over1, r->bin[b][k][w].n);
                }
                fprintf(f, "\n");
            }

    fprintf(f, "\n### Iridescent directions only (reference chroma C*ab ≥ %g)\n\n"
               "Share (%%) of the (θ, φ) samples whose reference colour is chromatic, and the analytic method's\n"
               "ΔE00 on those samples.\n\n"
               "| material | | share %s | mean %s | max %s | share %s | mean %s | max %s |\n"
               "|---|---|---|---|---|---|---|---|\n",
            CHROMA_MIN, lo, lo, lo, hi, hi, hi);
    for (int i = 0; i < run->nbase; i++)
        for (int w = 0; w < 2; w++) {
            const acc_result *r = &run->res[i];
            fprintf(f, "| %s | %s |", run->mat[i].name, TR[w]);
            for (int b = 0; b < 2; b++) {
                md_pct(f, r->col[b][M_ANALYTIC][w].n, r->bin[b][M_ANALYTIC][w].n);
                md_stat_pair(f, &r->col[b][M_ANALYTIC][w]);
            }
            fprintf(f, "\n");
        }

    fprintf(f, "\n### Near the optic axis (the iridescent directions)\n\n"
               "Internal wave directions within ψ of the optic axis (retardance up to %g nm), %d x %d samples per\n"
               "set, uniform in sin²ψ and around the axis. Set `down`: the downward legs near the axis (main\n"
               "rings); set `up`: the internally reflected, upward legs near the axis (minor rings). \"reached\" =\n"
               "refracted from θ ≤ %g°. Share = chromatic reference (C*ab ≥ %g).\n\n"
               "| material | ψ max | set | reached | | method | share %% | mean | max | %% >1 | mean (chromatic) | "
               "max (chromatic) |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
            AXIS_RETARDANCE_NM, AXIS_NPSI, run->nphi, (run->ntheta - 1) * run->theta_step_deg, CHROMA_MIN);
    static const char *const SET_NAME[AXIS_SETS] = {"down", "up"};
    for (int i = 0; i < run->nbase; i++)
        for (int set = 0; set < AXIS_SETS; set++)
            for (int w = 0; w < 2; w++)
                for (int k = 0; k < NM; k++) {
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

    fprintf(f, "\n### Acceptance: analytic, %s, mean ΔE00 ≤ 1 and max ≤ 4\n\n"
               "| material | T mean | T max | T | R mean | R max | R |\n|---|---|---|---|---|---|---|\n",
            lo);
    for (int i = 0; i < run->nbase; i++) {
        const acc_result *r = &run->res[i];
        fprintf(f, "| %s |", run->mat[i].name);
        for (int w = 0; w < 2; w++) {
            md_stat_pair(f, &r->bin[0][M_ANALYTIC][w]);
            fprintf(f, " %s |", acceptance_pass(r, w) ? "pass" : "**fail**");
        }
        fprintf(f, "\n");
    }

    if (run->samples_check > 0) {
        fprintf(f, "\n### Is the reference converged? %d vs %d samples (every %g°)\n\n"
                   "`ref-vs-check`: ΔE00 between the reference (%d) and %d samples; `analytic-vs-check`: the analytic\n"
                   "method against %d samples.\n\n"
                   "| material | | comparison | mean %s | max %s | mean %s | max %s |\n|---|---|---|---|---|---|---|\n",
                run->samples_ref, run->samples_check, run->kcheck * run->theta_step_deg, run->samples_ref,
                run->samples_check, run->samples_check, lo, lo, hi, hi);
        for (int i = 0; i < run->nbase; i++)
            for (int w = 0; w < 2; w++)
                for (int k = M_REF_CHECK; k <= M_AN_CHECK; k++) {
                    const acc_result *r = &run->res[i];
                    fprintf(f, "| %s | %s | %s |", run->mat[i].name, TR[w], METHOD_KEY[k]);
                    md_stat_pair(f, &r->bin[0][k][w]);
                    md_stat_pair(f, &r->bin[1][k][w]);
                    fprintf(f, "\n");
                }
    }

    if (run->nmat > run->nbase) {
        fprintf(f, "\n### Δε sweep (η_o, axis, d and light of the base material; analytic vs reference)\n\n"
                   "| base | Δε | η_e | T mean %s | T max %s | T mean %s | T max %s | R mean %s | R max %s | "
                   "R mean %s | R max %s | near-axis T max (down) | near-axis T max (up) | "
                   "near-axis R max (down) | near-axis R max (up) | numeric-128 T max %s |\n"
                   "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
                lo, lo, hi, hi, lo, lo, hi, hi, lo);
        for (int i = run->nbase; i < run->nmat; i++) {
            const acc_material *m = &run->mat[i];
            const acc_result *r = &run->res[i];
            fprintf(f, "| %s | %+.2f | %.4f |", run->mat[m->base].name, m->delta_eps, m->slab.eta_e);
            for (int w = 0; w < 2; w++) {
                md_stat_pair(f, &r->bin[0][M_ANALYTIC][w]);
                md_stat_pair(f, &r->bin[1][M_ANALYTIC][w]);
            }
            for (int w = 0; w < 2; w++)
                for (int set = 0; set < AXIS_SETS; set++)
                    md_num(f, r->axis[set][M_ANALYTIC][w].n ? r->axis[set][M_ANALYTIC][w].max : NAN);
            md_num(f, r->bin[0][M_N128][0].n ? r->bin[0][M_N128][0].max : NAN);
            fprintf(f, "\n");
        }
    }

    /* A coarse per-angle view of the analytic method (every 5° or so). */
    int every = (int)lround(5.0 / run->theta_step_deg);
    if (every < 1) every = 1;
    for (int w = 0; w < 2; w++) {
        fprintf(f, "\n### Per angle, analytic, %s: mean / max ΔE00 over azimuths (φ = 0 in brackets)\n\n| θ |",
                w ? "reflection" : "transmission");
        for (int i = 0; i < run->nbase; i++) fprintf(f, " %s |", run->mat[i].name);
        fprintf(f, "\n|---|");
        for (int i = 0; i < run->nbase; i++) fprintf(f, "---|");
        fprintf(f, "\n");
        for (int it = 0; it < run->ntheta; it++) {
            if (it % every && it != run->ntheta - 1) continue;
            fprintf(f, "| %g |", it * run->theta_step_deg);
            for (int i = 0; i < run->nbase; i++) {
                const acc_stat *s = &run->res[i].theta[it][M_ANALYTIC][w];
                fprintf(f, " %.2f / %.2f (%.2f) |", stat_mean(s), s->max, run->res[i].phi0[it][M_ANALYTIC][w]);
            }
            fprintf(f, "\n");
        }
    }
    fprintf(f, "\nWall time %.1f s on %d threads.\n", run->total_s, run->threads);
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
    json_num_or_null(o, "max", s->n ? s->max : NAN);
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
    cJSON_AddStringToObject(cfg, "cmf", biref_cmf_kind_name(run->scfg.cmf));
    double range[2] = {run->scfg.lambda_min_nm, run->scfg.lambda_max_nm};
    cJSON_AddItemToObject(cfg, "range_nm", cJSON_CreateDoubleArray(range, 2));
    cJSON_AddStringToObject(cfg, "materials", run->materials_arg);
    cJSON_AddNumberToObject(cfg, "split_deg", SPLIT_DEG);
    cJSON_AddNumberToObject(cfg, "chroma_min", CHROMA_MIN);
    cJSON_AddNumberToObject(cfg, "threads", run->threads);
    cJSON_AddNumberToObject(root, "elapsed_s", run->total_s);

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
        cJSON *sum = cJSON_AddObjectToObject(o, "summary");
        for (int k = 0; k < NM; k++) {
            if (k >= M_REF_CHECK && (m->base >= 0 || run->samples_check <= 0)) continue;
            cJSON *mk = cJSON_AddObjectToObject(sum, METHOD_KEY[k]);
            for (int w = 0; w < 2; w++) {
                cJSON *mw = cJSON_AddObjectToObject(mk, TR[w]);
                cJSON_AddItemToObject(mw, "low", json_stat(&r->bin[0][k][w]));
                cJSON_AddItemToObject(mw, "high", json_stat(&r->bin[1][k][w]));
                cJSON_AddItemToObject(mw, "low_chromatic", json_stat(&r->col[0][k][w]));
                cJSON_AddItemToObject(mw, "high_chromatic", json_stat(&r->col[1][k][w]));
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
                    col[3 * it + 1] = s->n ? s->max : NAN;
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
    return root;
}

/* ------------------------------------------------------------------------------------------ */
/* Command                                                                                     */
/* ------------------------------------------------------------------------------------------ */

static void help(void)
{
    printf("usage: biref accuracy [OPTIONS]\n\n"
           "CIEDE2000 difference between the analytic approximation (paper eq. 26), numeric\n"
           "integration with 8, 32 and 128 samples, and the ground truth (numeric, 16384 samples) as a\n"
           "function of the angle of incidence, for the paper's fig. 9 materials and a sweep over\n"
           "delta-epsilon (fig. 7). Each angle is evaluated at several azimuths: the optic axis is\n"
           "rotated about the slab normal, as it is for the pixels of a rendered slab. Tables on\n"
           "stdout (markdown) unless --json. A second sample set aims at the directions close to the\n"
           "optic axis, where mm-thick slabs show their colours. Method and results: docs/ACCURACY.md.\n\n"
           "Options:\n"
           "  --materials M          fig9 (default: the three materials of fig. 9 with their light)\n"
           "                         or a JSON file: [{\"name\", \"eta_o\", \"eta_e\", \"axis\": [a,b,c],\n"
           "                         \"thickness_mm\" (or _um, _nm), \"eta_i\", \"polarization\": \"0.75,0.25\",\n"
           "                         \"analyzer\": \"none\"|\"s\"|\"p\"}, ...]\n"
           "  --sweep-delta-eps L    comma-separated eps_e - eps_o values applied to every material\n"
           "                         (eta_o kept, eta_e varied), or none (default -0.6,-0.2,0.2,0.6)\n"
           "  --theta-max-deg A      largest angle of incidence, 0 <= A < 90 (default 85)\n"
           "  --theta-step-deg S     angle step, > 0 (default 1)\n"
           "  --azimuths N           azimuths of the optic axis per angle, and directions around the\n"
           "                         axis per ring of the near-axis set (default 24)\n"
           "  --samples-ref N        samples of the reference integration (default 16384)\n"
           "  --samples-check N      denser integration to test the reference, 0 = off (default 65536;\n"
           "                         base materials only)\n"
           "  --check-step-deg S     angle step of that test (default 5)\n"
           "  --cmf C                cie1931 (default) or wyman2013\n"
           "  --range-nm MIN,MAX     integration band (default 380,700)\n"
           "  --threads T            OpenMP threads (default: all cores)\n"
           "  --csv FILE             per-angle statistics of every method and material\n"
           "  --markdown FILE        write the tables to FILE\n"
           "  --json                 machine-readable output on stdout\n"
           "  -h, --help             this help\n");
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
    OPT_CMF,
    OPT_RANGE,
    OPT_THREADS,
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
    run.theta_max_deg = 85.0;
    run.theta_step_deg = 1.0;
    run.check_step_deg = 5.0;
    run.nphi = 24;
    run.samples_ref = BIREF_GROUND_TRUTH_SAMPLES;
    run.samples_check = 4 * BIREF_GROUND_TRUTH_SAMPLES;
    run.materials_arg = "fig9";
    biref_spectral_config_default(&run.scfg);
    double sweep[MAX_SWEEP] = {-0.6, -0.2, 0.2, 0.6};
    int nsweep = 4;
    long threads = 0;
    const char *csv_path = NULL, *md_path = NULL;
    int json = 0;
    static const struct option longopts[] = {{"materials", required_argument, 0, OPT_MATERIALS},
                                             {"sweep-delta-eps", required_argument, 0, OPT_SWEEP},
                                             {"theta-max-deg", required_argument, 0, OPT_THETA_MAX},
                                             {"theta-step-deg", required_argument, 0, OPT_THETA_STEP},
                                             {"azimuths", required_argument, 0, OPT_AZIMUTHS},
                                             {"samples-ref", required_argument, 0, OPT_SAMPLES_REF},
                                             {"samples-check", required_argument, 0, OPT_SAMPLES_CHECK},
                                             {"check-step-deg", required_argument, 0, OPT_CHECK_STEP},
                                             {"cmf", required_argument, 0, OPT_CMF},
                                             {"range-nm", required_argument, 0, OPT_RANGE},
                                             {"threads", required_argument, 0, OPT_THREADS},
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
            if (cli_parse_int(CMD, "--samples-ref", optarg, 1, MAX_SAMPLES, &v)) return CLI_EXIT_USAGE;
            run.samples_ref = (int)v;
            break;
        case OPT_SAMPLES_CHECK:
            if (cli_parse_int(CMD, "--samples-check", optarg, 0, MAX_SAMPLES, &v)) return CLI_EXIT_USAGE;
            run.samples_check = (int)v;
            break;
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
        case OPT_CSV: csv_path = optarg; break;
        case OPT_MARKDOWN: md_path = optarg; break;
        case OPT_JSON: json = 1; break;
        default: cli_getopt_error(CMD, c, argv); return CLI_EXIT_USAGE;
        }
    }
    if (optind < argc) return cli_error(CMD, "unexpected argument '%s'", argv[optind]), CLI_EXIT_USAGE;
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
    biref_numeric_plan *plans[5] = {NULL, NULL, NULL, NULL, NULL};
    FILE *csv = NULL, *md = NULL;
    for (int i = 0; i < run.nbase; i++) {
        run.mat[i] = base[i];
        double n2 = sqrt(base[i].slab.axis[0] * base[i].slab.axis[0] + base[i].slab.axis[1] * base[i].slab.axis[1] +
                         base[i].slab.axis[2] * base[i].slab.axis[2]);
        for (int k = 0; k < 3; k++) run.mat[i].slab.axis[k] /= n2;
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
    const int plan_n[5] = {run.samples_ref, NUMERIC_N[0], NUMERIC_N[1], NUMERIC_N[2], run.samples_check};
    for (int k = 0; k < 5; k++) {
        if (plan_n[k] <= 0) continue;
        s = biref_numeric_plan_create(sp, plan_n[k], &plans[k]);
        if (s != BIREF_OK) {
            cli_error(CMD, "numeric plan (%d samples): %s", plan_n[k], biref_status_string(s));
            goto done;
        }
    }
    acc_plans pl = {sp, plans[0], {plans[1], plans[2], plans[3]}, plans[4]};

    if (threads > 0) omp_set_num_threads((int)threads);
    run.threads = omp_get_max_threads();
    acc_progress pg = {isatty(STDERR_FILENO), 0, (long)run.nmat * ((long)run.ntheta + AXIS_SETS * AXIS_NPSI) * run.nphi, omp_get_wtime(), 0.0};
    for (int i = 0; i < run.nmat; i++)
        if (run_material(&run, &pl, i, &pg)) goto done;
    run.total_s = omp_get_wtime() - pg.t0;
    if (pg.on) fprintf(stderr, "\rbiref accuracy: done in %.1f s on %d threads%30s\n", run.total_s, run.threads, "");

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
    for (int k = 0; k < 5; k++) biref_numeric_plan_destroy(plans[k]);
    biref_spectral_destroy(sp);
    for (int i = 0; i < run.nmat; i++) {
        free(run.res[i].theta);
        free(run.res[i].phi0);
    }
    free(run.mat);
    free(run.res);
    return rc;
}
