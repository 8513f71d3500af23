/* The accuracy study's Markdown tables (stdout or --markdown) and per-angle CSV (--csv). */
#include <math.h>
#include <stdio.h>

#include "cli_light.h"
#include "study.h"

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
void acc_band_range(const acc_run *run, int b, double r[2])
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
        fprintf(f, "| %s | %.0f | %.0f | %.2f | %.2f | %.2f | %ld |\n", ACC_METHOD_KEY[k], c->with_prepare.ns_median,
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
        acc_band_range(run, b, r);
        fprintf(f, "| %g-%g° | %d | %.0f | %.0f | %.2f | %.0f | %.0f | %.2f |\n", r[0], r[1], run->cost_band_n[b],
                a->with_prepare.ns_median, x->with_prepare.ns_median, x->with_prepare.ns_median / a->with_prepare.ns_median,
                a->alone.ns_median, x->alone.ns_median, x->alone.ns_median / a->alone.ns_median);
    }
}

static void write_expansion_md(FILE *f, const acc_run *run, const acc_expansion_verdict *e)
{
    fprintf(f, "\n### Expansion criterion (a): expansion within ΔE00 ≤ %g of the reference for every θ in 0-%g°\n\n"
               "Maximum over all azimuths of the grid (θ ≤ %g°) and over the near-axis samples refracted from\n"
               "θ ≤ %g°; \"θ of grid max\" is where the grid maximum occurs.\n\n"
               "| material | T max, grid | T max, near axis | θ of T grid max | R max, grid | R max, near axis | "
               "θ of R grid max |\n|---|---|---|---|---|---|---|\n",
            EXPANSION_DE_MAX, CRIT_DEG, CRIT_DEG, CRIT_DEG);
    for (int i = 0; i < run->nbase; i++) {
        fprintf(f, "| %s |", run->mat[i].name);
        for (int w = 0; w < 2; w++) {
            md_num_fine(f, e->grid_max[i][w]);
            md_num_fine(f, e->axis_max[i][w]);
            fprintf(f, " %g |", e->theta_of_max[i][w]);
        }
        fprintf(f, "\n");
    }
    fprintf(f, "\nΔE00 ≤ %g: transmission %s, reflection %s.\n", EXPANSION_DE_MAX, pass_word(e->pass_de[0]),
            pass_word(e->pass_de[1]));
    if (!run->have_cost) {
        fprintf(f, "Cost: not measured (run with --cost).\n");
        return;
    }
    fprintf(f, "Cost per shading sample in this run (prepare included): analytic %.0f ns, expansion %.0f ns, ratio "
               "%.2f (≤ %g: %s); integration alone %.0f vs %.0f ns, ratio %.2f.\n**(a): %s.**\n",
            e->ns_an, e->ns_ex, e->ratio, EXPANSION_COST_RATIO, pass_word(e->pass_cost), e->ns_an_alone, e->ns_ex_alone,
            e->ratio_alone, e->pass_a ? "met" : "not met");

    fprintf(f, "\n### Expansion criterion (b): at equal cost, expansion ΔE00 at least %g× below numeric integration\n\n"
               "ΔE00 over the grid θ 0-%g°, all azimuths, the %d base materials together. Cost with prepare, this "
               "run.\n\n| method | ns per sample | cost / expansion | T mean | T max | R mean | R max |\n"
               "|---|---|---|---|---|---|---|\n",
            EXPANSION_GAIN, CRIT_DEG, run->nbase);
    const int rows[3] = {M_EXPANSION, e->lo, e->hi};
    for (int q = 0; q < 3; q++) {
        const int k = rows[q];
        if (k < 0) continue;
        const double ns = run->cost[k].with_prepare.ns_median;
        fprintf(f, "| %s | %.0f | %.2f |", ACC_METHOD_KEY[k], ns, ns / e->ns_ex);
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
            ACC_METHOD_KEY[e->hi], e->gain_mean[0], e->gain_max[0], e->gain_mean[1], e->gain_max[1],
            e->pass_b ? "met" : "not met");
}

/* Is the reference converged? (the check integration) */
static void write_check_md(FILE *f, const acc_run *run, char bl[NBIN][32])
{
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
                    fprintf(f, "| %s | %s | %s |", run->mat[i].name, ACC_TR[w], ACC_METHOD_KEY[k]);
                    for (int b = 0; b < NBIN; b++) md_stat_pair(f, &r->bin[b][k][w]);
                    acc_stat ax = r->axis[0][k][w];
                    stat_merge(&ax, &r->axis[1][k][w]);
                    md_stat_pair(f, &ax);
                    fprintf(f, "\n");
                }
    }
}

/* ΔE00 of every method over each angle range, and on the chromatic directions only. */
static void write_de_md(FILE *f, const acc_run *run, char bl[NBIN][32])
{
    fprintf(f, "\n### ΔE00 against the reference\n\n"
               "Mean, max and share (%%) of samples with ΔE00 > 1, over all (θ, φ) of each range.\n\n"
               "| material | | method | mean %s | max %s | %% >1 %s | mean %s | max %s | %% >1 %s | mean %s | max %s | "
               "%% >1 %s |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
            bl[0], bl[0], bl[0], bl[1], bl[1], bl[1], bl[2], bl[2], bl[2]);
    for (int i = 0; i < run->nbase; i++)
        for (int w = 0; w < 2; w++)
            for (int k = 0; k < NCMP; k++) {
                const acc_result *r = &run->res[i];
                fprintf(f, "| %s | %s | %s |", run->mat[i].name, ACC_TR[w], ACC_METHOD_KEY[k]);
                for (int b = 0; b < NBIN; b++) {
                    md_stat_pair(f, &r->bin[b][k][w]);
                    md_pct(f, r->bin[b][k][w].over1, r->bin[b][k][w].n);
                }
                fprintf(f, "\n");
            }

    fprintf(f, "\n### Iridescent directions only (reference chroma C*ab ≥ %g)\n\n"
               "Share (%%) of the (θ, φ) samples whose reference colour is chromatic, and the ΔE00 of the analytic\n"
               "method, analytic-pairs and the expansion on those samples.\n\n"
               "| material | | method | share %s | mean %s | max %s | share %s | mean %s | max %s | share %s | mean %s | "
               "max %s |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
            CHROMA_MIN, bl[0], bl[0], bl[0], bl[1], bl[1], bl[1], bl[2], bl[2], bl[2]);
    for (int i = 0; i < run->nbase; i++)
        for (int w = 0; w < 2; w++)
            for (int k = M_ANALYTIC; k <= M_EXPANSION; k++) {
                const acc_result *r = &run->res[i];
                fprintf(f, "| %s | %s | %s |", run->mat[i].name, ACC_TR[w], ACC_METHOD_KEY[k]);
                for (int b = 0; b < NBIN; b++) {
                    md_pct(f, r->col[b][k][w].n, r->bin[b][k][w].n);
                    md_stat_pair(f, &r->col[b][k][w]);
                }
                fprintf(f, "\n");
            }
}

/* The near-axis sample sets. */
static void write_axis_md(FILE *f, const acc_run *run, char bl[NBIN][32])
{
    /* The near-axis table keeps the methods that matter for the discussion; the JSON has all. */
    static const int AXIS_METHODS[] = {M_ANALYTIC, M_PAIRS, M_EXPANSION, M_N32, M_N128, M_GT, M_REF_CHECK};
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
                            SET_NAME[set], r->axis_valid[set], ACC_TR[w], ACC_METHOD_KEY[k]);
                    md_pct(f, r->axis_col[set][k][w].n, r->axis[set][k][w].n);
                    md_stat_pair(f, &r->axis[set][k][w]);
                    md_pct(f, r->axis[set][k][w].over1, r->axis[set][k][w].n);
                    md_stat_pair(f, &r->axis_col[set][k][w]);
                    fprintf(f, "\n");
                }
}

/* The paper's acceptance envelope (acc_envelope_pass) for the analytic method and analytic-pairs. */
static void write_analytic_acceptance_md(FILE *f, const acc_run *run, char bl[NBIN][32])
{
    fprintf(f, "\n### Acceptance of the analytic method: analytic, %s, mean ΔE00 ≤ 1 and max ≤ 4\n\n"
               "The paper's envelope for eq. 26, and the same for analytic-pairs (beyond the paper).\n\n"
               "| material | method | T mean | T max | T | R mean | R max | R |\n|---|---|---|---|---|---|---|---|\n",
            bl[0]);
    static const int METHODS[2] = {M_ANALYTIC, M_PAIRS};
    for (int i = 0; i < run->nbase; i++)
        for (int q = 0; q < 2; q++) {
            const acc_result *r = &run->res[i];
            fprintf(f, "| %s | %s |", run->mat[i].name, ACC_METHOD_KEY[METHODS[q]]);
            for (int w = 0; w < 2; w++) {
                md_stat_pair(f, &r->bin[0][METHODS[q]][w]);
                fprintf(f, " %s |", pass_word(acc_envelope_pass(r, METHODS[q], w)));
            }
            fprintf(f, "\n");
        }
}

/* The Δε sweep variants. */
static void write_sweep_md(FILE *f, const acc_run *run, char bl[NBIN][32])
{
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
            static const int NEAR_AXIS[2] = {M_ANALYTIC, M_EXPANSION};
            for (int q = 0; q < 2; q++)
                fprintf(f, " %.2f / %.2f |", stat_max(&r->axis[0][NEAR_AXIS[q]][0]), stat_max(&r->axis[1][NEAR_AXIS[q]][0]));
            md_num(f, stat_max(&r->bin[0][M_N128][0]));
            fprintf(f, "\n");
        }
    }
}

/* A coarse per-angle view of the fast methods (M_ANALYTIC .. M_EXPANSION). */
static void write_per_angle_md(FILE *f, const acc_run *run, char bl[NBIN][32])
{
    /* Every 5° or so; the CSV has every angle. */
    int every = (int)lround(fmin(5.0 / run->theta_step_deg, run->ntheta));
    if (every < 1) every = 1;
    for (int w = 0; w < 2; w++) {
        fprintf(f, "\n### Per angle, %s: max / mean ΔE00 over azimuths, analytic, analytic-pairs and expansion\n\n| θ |",
                w ? "reflection" : "transmission");
        for (int i = 0; i < run->nbase; i++)
            for (int k = M_ANALYTIC; k <= M_EXPANSION; k++) fprintf(f, " %s %s |", run->mat[i].name, ACC_METHOD_KEY[k]);
        fprintf(f, "\n|---|");
        for (int i = 0; i < run->nbase; i++)
            for (int k = M_ANALYTIC; k <= M_EXPANSION; k++) fprintf(f, "---|");
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
}

void acc_write_markdown(FILE *f, const acc_run *run)
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

    write_check_md(f, run, bl);
    write_de_md(f, run, bl);
    write_axis_md(f, run, bl);
    write_analytic_acceptance_md(f, run, bl);
    acc_expansion_verdict e;
    acc_expansion_verdict_eval(run, &e);
    write_expansion_md(f, run, &e);
    if (run->have_cost) write_cost_md(f, run);
    write_sweep_md(f, run, bl);
    write_per_angle_md(f, run, bl);
    fprintf(f, "\nWall time %.1f s on %d threads", run->total_s, run->threads);
    if (run->have_cost) fprintf(f, " (of which %.1f s single-threaded cost measurement)", run->cost_s);
    fprintf(f, ".\n");
}

void acc_write_csv(FILE *f, const acc_run *run)
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
                            m->slab.eta_e * m->slab.eta_e - m->slab.eta_o * m->slab.eta_o, ACC_TR[w], ACC_METHOD_KEY[k],
                            it * run->theta_step_deg, stat_mean(s), s->max, r->phi0[it][k][w], s->n);
                }
    }
}
