/* The accuracy study's JSON report (--json). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli_light.h"
#include "json_out.h"
#include "study.h"

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
        snprintf(name, sizeof name, "%s", ACC_METHOD_KEY[k]);
        cJSON_AddItemToArray(order, cJSON_CreateString(name));
        snprintf(name, sizeof name, "%s+prepare", ACC_METHOD_KEY[k]);
        cJSON_AddItemToArray(order, cJSON_CreateString(name));
        cJSON *o = cJSON_CreateObject();
        cJSON_AddItemToArray(ms, o);
        cJSON_AddStringToObject(o, "method", ACC_METHOD_KEY[k]);
        cJSON_AddItemToObject(o, "with_prepare", json_cost_time(&r->with_prepare));
        cJSON_AddItemToObject(o, "alone", json_cost_time(&r->alone));
        cJSON_AddNumberToObject(o, "ratio_to_analytic",
                                r->with_prepare.ns_median / run->cost[M_ANALYTIC].with_prepare.ns_median);
    }
    cJSON *bands = cJSON_AddArrayToObject(c, "by_theta");
    for (int b = 0; b < 2; b++) {
        if (!run->cost_band_n[b]) continue;
        double r[2];
        acc_band_range(run, b, r);
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

static void json_expansion_verdict(cJSON *root, const acc_run *run)
{
    acc_expansion_verdict e;
    acc_expansion_verdict_eval(run, &e);
    cJSON *o = cJSON_AddObjectToObject(root, "expansion_criteria");
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
            cJSON *x = cJSON_AddObjectToObject(m, ACC_TR[w]);
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
    if (e.lo >= 0) cJSON_AddStringToObject(b, "cheaper_numeric", ACC_METHOD_KEY[e.lo]);
    if (e.hi < 0) return;
    cJSON_AddStringToObject(b, "numeric", ACC_METHOD_KEY[e.hi]);
    cJSON_AddNumberToObject(b, "numeric_ns", run->cost[e.hi].with_prepare.ns_median);
    cJSON_AddNumberToObject(b, "expansion_ns", e.ns_ex);
    for (int w = 0; w < 2; w++) {
        cJSON *x = cJSON_AddObjectToObject(b, ACC_TR[w]);
        cJSON_AddItemToObject(x, "expansion", json_stat(&e.pooled[M_EXPANSION][w]));
        cJSON_AddItemToObject(x, "numeric", json_stat(&e.pooled[e.hi][w]));
        json_num_or_null(x, "gain_mean", e.gain_mean[w]);
        json_num_or_null(x, "gain_max", e.gain_max[w]);
    }
    cJSON_AddBoolToObject(b, "pass", e.pass_b);
}

/* One material's summary statistics per method, angle range and sample set. */
static void json_material_summary(cJSON *o, const acc_run *run, int i)
{
    const acc_material *m = &run->mat[i];
    const acc_result *r = &run->res[i];
    static const char *const BIN_KEY[NBIN] = {"low", "high", "grazing"};
    cJSON *sum = cJSON_AddObjectToObject(o, "summary");
    for (int k = 0; k < NM; k++) {
        if (k >= M_REF_CHECK && (m->base >= 0 || run->samples_check <= 0)) continue;
        cJSON *mk = cJSON_AddObjectToObject(sum, ACC_METHOD_KEY[k]);
        for (int w = 0; w < 2; w++) {
            cJSON *mw = cJSON_AddObjectToObject(mk, ACC_TR[w]);
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
}

/* One material's per-angle statistics; -1 when out of memory. */
static int json_material_per_theta(cJSON *o, const acc_run *run, int i)
{
    const acc_material *m = &run->mat[i];
    const acc_result *r = &run->res[i];
    cJSON *pt = cJSON_AddObjectToObject(o, "per_theta");
    double *th = malloc((size_t)run->ntheta * sizeof *th);
    double *col = malloc((size_t)run->ntheta * 3 * sizeof *col);
    if (!th || !col) {
        free(th);
        free(col);
        return -1;
    }
    for (int it = 0; it < run->ntheta; it++) th[it] = it * run->theta_step_deg;
    cJSON_AddItemToObject(pt, "theta_deg", cJSON_CreateDoubleArray(th, run->ntheta));
    for (int k = 0; k < NM; k++) {
        if (k >= M_REF_CHECK && (m->base >= 0 || run->samples_check <= 0)) continue;
        cJSON *mk = cJSON_AddObjectToObject(pt, ACC_METHOD_KEY[k]);
        for (int w = 0; w < 2; w++) {
            for (int it = 0; it < run->ntheta; it++) {
                const acc_stat *s = &r->theta[it][k][w];
                col[3 * it] = stat_mean(s);
                col[3 * it + 1] = stat_max(s);
                col[3 * it + 2] = s->n ? r->phi0[it][k][w] : NAN;
            }
            cJSON *mw = cJSON_AddObjectToObject(mk, ACC_TR[w]);
            cJSON_AddItemToObject(mw, "mean", json_array_or_nulls(col, run->ntheta, 3));
            cJSON_AddItemToObject(mw, "max", json_array_or_nulls(col + 1, run->ntheta, 3));
            cJSON_AddItemToObject(mw, "phi0", json_array_or_nulls(col + 2, run->ntheta, 3));
        }
    }
    free(th);
    free(col);
    return 0;
}

/* One material: its slab and light, then its statistics; -1 when out of memory. */
static int json_material(cJSON *mats, const acc_run *run, int i)
{
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
    json_material_summary(o, run, i);
    return json_material_per_theta(o, run, i);
}

/* The paper's envelope for method k (acc_envelope_pass) as root.key. */
static void json_acceptance(cJSON *root, const char *key, const acc_run *run, int k)
{
    cJSON *acc = cJSON_AddObjectToObject(root, key);
    char crit[256];
    snprintf(crit, sizeof crit,
             "%s vs reference, theta 0-70 deg over all azimuths: mean dE00 <= 1 and max dE00 <= 4 (evaluated on T, "
             "the quantity of fig. 9; R reported)",
             ACC_METHOD_KEY[k]);
    cJSON_AddStringToObject(acc, "criterion", crit);
    int all_pass = 1;
    cJSON *am = cJSON_AddArrayToObject(acc, "materials");
    for (int i = 0; i < run->nbase; i++) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddItemToArray(am, o);
        cJSON_AddStringToObject(o, "name", run->mat[i].name);
        for (int w = 0; w < 2; w++) {
            cJSON *x = json_stat(&run->res[i].bin[0][k][w]);
            cJSON_AddBoolToObject(x, "pass", acc_envelope_pass(&run->res[i], k, w));
            cJSON_AddItemToObject(o, ACC_TR[w], x);
        }
        all_pass &= acc_envelope_pass(&run->res[i], k, 0);
    }
    cJSON_AddBoolToObject(acc, "pass", all_pass);
}

cJSON *acc_build_json(const acc_run *run)
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
    for (int i = 0; i < run->nmat; i++)
        if (json_material(mats, run, i)) {
            cJSON_Delete(root);
            return NULL;
        }

    json_acceptance(root, "acceptance", run, M_ANALYTIC);
    json_acceptance(root, "acceptance_analytic_pairs", run, M_PAIRS);
    json_expansion_verdict(root, run);
    return root;
}
