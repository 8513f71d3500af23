/* The accuracy study: CIEDE2000 of the spectral integration methods against an alias-free reference,
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
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "cli_mpi.h"
#include "study.h"

const char *const ACC_METHOD_KEY[NM] = {"analytic",     "analytic-pairs", "expansion",         "numeric-3",
                                        "numeric-8",    "numeric-16",     "numeric-32",        "numeric-64",
                                        "numeric-128",  "ground-truth",   "ref-vs-check",      "analytic-vs-check",
                                        "expansion-vs-check"};
const int ACC_NUMERIC_N[NNUM] = {3, 8, 16, 32, 64, 128};
const char *const ACC_TR[2] = {"T", "R"};

/* Every thread counts; the bar is drawn by the master thread alone (it is not thread-safe). The
 * count is passed in millionths: the total can exceed an int. */
static void progress_tick(acc_progress *pg)
{
    long d;
#pragma omp atomic capture
    d = ++pg->done;
    if (omp_get_thread_num() == 0 && d < pg->total)
        biref_progress_bar_update(pg->bar, (int)(1000000.0 * (double)d / (double)pg->total), 1000000);
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

double acc_axis_psi_max(const acc_material *m)
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
    const double smax = sin(acc_axis_psi_max(m));
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
    return biref_integrate_spectrum(pl->method[k], st, x) == BIREF_OK ? 0 : -1;
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
    biref_integrate_spectrum(pl->ref, &st, &x);
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
        biref_integrate_spectrum(pl->check, &st, &x);
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

/* Job j of material m's sweep: the (θ, φ) grid first, then the near-axis sets. Its angles, whether
 * it is checked against the denser integration, and whether it is a sample at all (a near-axis
 * direction may lie beyond --theta-max-deg). */
static int job_angles(const acc_run *run, const acc_material *m, int check_on, long j, double *theta, double *phi,
                      int *check)
{
    const long ngrid = (long)run->ntheta * run->nphi, naxis = (long)AXIS_NPSI * run->nphi;
    *theta = *phi = 0.0;
    if (j < ngrid) {
        const int it = (int)(j / run->nphi);
        *theta = it * run->theta_step_deg * M_PI / 180.0;
        *phi = 2.0 * M_PI * (double)(j % run->nphi) / run->nphi;
        /* every kcheck-th angle, and the last one (the most grazing, where errors peak) */
        *check = check_on && (it % run->kcheck == 0 || it == run->ntheta - 1);
        return 1;
    }
    const long ja = (j - ngrid) % naxis;
    *check = check_on && ja % AXIS_CHECK_STRIDE == 0;
    return axis_sample(run, m, (int)((j - ngrid) / naxis), (int)ja, theta, phi);
}

/* A material's sweep: per job its ΔE00, reference chroma, angle and validity, and a job whose
 * result came out non-finite (bad >= 0). */
typedef struct {
    const acc_run *run;
    const acc_plans *pl;
    const acc_material *m;
    int check_on;
    long njobs;
    double (*de)[NM][2], (*chroma)[2], *theta_j;
    char *valid;
    long bad;
    double bad_theta, bad_phi;
    acc_progress *pg;
} acc_sweep;

/* Jobs j0 .. j1 - 1 into the arrays at offset 0 (de[j - j0] ...), in parallel. */
static void sweep_jobs(acc_sweep *w, long j0, long j1, double (*de)[NM][2], double (*chroma)[2], double *theta_j,
                       char *valid, int tick)
{
#pragma omp parallel for schedule(dynamic, 2)
    for (long j = j0; j < j1; j++) {
        double theta, phi;
        int check;
        const long k = j - j0;
        valid[k] = (char)job_angles(w->run, w->m, w->check_on, j, &theta, &phi, &check);
        theta_j[k] = valid[k] ? theta * 180.0 / M_PI : NAN;
        if (valid[k] && evaluate_point(w->pl, w->m, theta, phi, check, de[k], chroma[k])) {
#pragma omp critical(acc_bad)
            {
                w->bad = j;
                w->bad_theta = theta;
                w->bad_phi = phi;
            }
        }
        if (tick) progress_tick(w->pg);
    }
}

/* In an MPI job (cli_mpi.h), chunks of jobs are the processes' jobs; their results are exact
 * copies of what one process computes, so the statistics are the same. */
#define SWEEP_CHUNK 16
typedef struct {
    double de[SWEEP_CHUNK][NM][2], chroma[SWEEP_CHUNK][2], theta_j[SWEEP_CHUNK];
    char valid[SWEEP_CHUNK];
    long bad;
    double bad_theta, bad_phi;
} sweep_chunk;

static int sweep_compute(void *user, long chunk, void *result)
{
    acc_sweep w = *(const acc_sweep *)user;
    sweep_chunk *c = result;
    const long j0 = chunk * SWEEP_CHUNK, j1 = j0 + SWEEP_CHUNK < w.njobs ? j0 + SWEEP_CHUNK : w.njobs;
    w.bad = -1;
    sweep_jobs(&w, j0, j1, c->de, c->chroma, c->theta_j, c->valid, 0);
    c->bad = w.bad;
    c->bad_theta = w.bad_theta;
    c->bad_phi = w.bad_phi;
    return 0;
}

static void sweep_store(void *user, long chunk, const void *result)
{
    acc_sweep *w = user;
    const sweep_chunk *c = result;
    const long j0 = chunk * SWEEP_CHUNK, n = j0 + SWEEP_CHUNK < w->njobs ? SWEEP_CHUNK : w->njobs - j0;
    memcpy(w->de + j0, c->de, (size_t)n * sizeof c->de[0]);
    memcpy(w->chroma + j0, c->chroma, (size_t)n * sizeof c->chroma[0]);
    memcpy(w->theta_j + j0, c->theta_j, (size_t)n * sizeof c->theta_j[0]);
    memcpy(w->valid + j0, c->valid, (size_t)n);
    if (c->bad >= 0) {
        w->bad = c->bad;
        w->bad_theta = c->bad_theta;
        w->bad_phi = c->bad_phi;
    }
    w->pg->done += n;
    biref_progress_bar_update(w->pg->bar, (int)(1000000.0 * (double)w->pg->done / (double)w->pg->total), 1000000);
}

int acc_run_material(acc_run *run, const acc_plans *pl, int mi, acc_progress *pg)
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
        return cli_error(ACC_CMD, "out of memory"), -1;
    }
    /* The check integration: base materials only, on a subset (see AXIS_CHECK_STRIDE). */
    acc_sweep sw = {run, pl, m, run->samples_check > 0 && m->base < 0, njobs, de, chroma, theta_j, valid, -1, 0, 0, pg};
    const double t0 = omp_get_wtime();
    if (cli_mpi_active()) {
        cli_mpi_jobs((njobs + SWEEP_CHUNK - 1) / SWEEP_CHUNK, sizeof(sweep_chunk), sweep_compute, sweep_store, &sw, NULL,
                     NULL);
        if (cli_mpi_rank() > 0) { /* rank 0 alone keeps the results */
            free(de), free(chroma), free(theta_j), free(valid);
            return 0;
        }
    } else {
        sweep_jobs(&sw, 0, njobs, de, chroma, theta_j, valid, 1);
    }
    const long bad = sw.bad;
    const double bad_theta = sw.bad_theta, bad_phi = sw.bad_phi;
    r->elapsed_s = omp_get_wtime() - t0;
    if (bad >= 0) {
        free(de);
        free(chroma);
        free(theta_j);
        free(valid);
        cli_error(ACC_CMD, "material %s: non-finite result at theta %g deg, axis azimuth %g deg", m->name,
                  bad_theta * 180.0 / M_PI, bad_phi * 180.0 / M_PI);
        return cli_mpi_abort(-1); /* the other processes of an MPI job wait for the next material */
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
    r->axis_psi_max_deg = acc_axis_psi_max(m) * 180.0 / M_PI;
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

int acc_measure_cost(acc_run *run, const acc_plans *pl)
{
    for (int k = 0; k < NCMP; k++) {
        run->cost[k].name = ACC_METHOD_KEY[k];
        run->cost[k].integrator = pl->method[k];
    }
    const double t0 = omp_get_wtime();
    biref_slab *slab = NULL;
    double *theta = NULL;
    acc_cost_pool pool = {NULL, NULL, cost_pool(run, 2, &slab, &theta)};
    if (pool.n == 0) return cli_error(ACC_CMD, "--cost: out of memory"), -1;
    pool.slab = slab, pool.theta = theta;
    run->cost_pool_n = pool.n;
    int rc = acc_cost_measure(&pool, &run->cost_opts, &run->cost_prepare, run->cost, NCMP);
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
        rc = acc_cost_measure(&pool, &run->cost_opts, NULL, run->cost_band[b], 2);
        free(slab), free(theta);
        if (rc) return -1;
    }
    run->cost_s = omp_get_wtime() - t0;
    run->have_cost = 1;
    return 0;
}
