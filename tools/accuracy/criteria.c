/* The acceptance criteria the accuracy study reports (study.h): the analytic method's, and the
 * expansion's accuracy, cost and gain over numeric integration at equal cost. */
#include <math.h>
#include <string.h>

#include "study.h"

int acc_envelope_pass(const acc_result *r, int k, int w)
{
    const acc_stat *s = &r->bin[0][k][w];
    return s->n > 0 && stat_mean(s) <= 1.0 && s->max <= 4.0;
}

void acc_expansion_verdict_eval(const acc_run *run, acc_expansion_verdict *e)
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
            if (!(e->grid_max[i][w] <= EXPANSION_DE_MAX) || e->axis_max[i][w] > EXPANSION_DE_MAX) e->pass_de[w] = 0;
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
    e->pass_cost = e->ratio <= EXPANSION_COST_RATIO;
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
        if (!(e->gain_mean[w] >= EXPANSION_GAIN && e->gain_max[w] >= EXPANSION_GAIN)) e->pass_b = 0;
    }
}
