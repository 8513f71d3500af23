/* The accuracy study's figures (--plot-dir): ΔE00 against cost and against the angle. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "fig_plot.h"
#include "plot.h"
#include "study.h"

int acc_write_plots(const acc_run *run, const char *dir)
{
    char path[4096];
    acc_expansion_verdict e;
    acc_expansion_verdict_eval(run, &e);
    if (run->have_cost) {
        acc_plot_cost_point p[NCMP];
        for (int k = 0; k < NCMP; k++) {
            /* The numeric family is labelled by its sample count; the other methods by the legend. */
            p[k].label = k == M_GT ? "16384 = ground truth" : k >= M_N3 ? ACC_METHOD_KEY[k] + strlen("numeric-") : NULL;
            p[k].style = k == M_ANALYTIC    ? ACC_STYLE_ANALYTIC
                         : k == M_PAIRS     ? ACC_STYLE_PAIRS
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
    /* ΔE00 against θ for the methods compared in docs/ACCURACY.md (and the paper's ground truth, whose
     * aliasing on the 3.5 mm slab shows here). */
    static const int METH[] = {M_ANALYTIC, M_PAIRS, M_EXPANSION, M_N32, M_N128, M_GT};
    enum { NMETH = sizeof METH / sizeof METH[0] };
    static const int COLOR[NMETH] = {FIG_RED, FIG_ORANGE, FIG_BLUE, FIG_GREEN, FIG_BROWN, FIG_PURPLE};
    const char *names[NMETH];
    for (int q = 0; q < NMETH; q++) names[q] = ACC_METHOD_KEY[METH[q]];
    const int nm = run->nbase;
    const size_t n = (size_t)nm * NMETH * 2 * (size_t)run->ntheta;
    double *mean = malloc(n * sizeof *mean), *max = malloc(n * sizeof *max),
           *th = malloc((size_t)run->ntheta * sizeof *th);
    char(*titles)[160] = malloc((size_t)nm * sizeof *titles);
    const char **tp = malloc((size_t)nm * sizeof *tp);
    if (!mean || !max || !th || !titles || !tp) {
        free(mean), free(max), free(th), free(titles), free(tp);
        return cli_error(ACC_CMD, "out of memory"), -1;
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
