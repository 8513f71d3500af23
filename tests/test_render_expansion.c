/* The renderer with the path-group expansion (beyond the paper): a world-fixed polarizer and an
 * analyzer at 45 degrees on fig. 9c's slab, against the 16384-sample ground truth, and the
 * analytic method's general terms against the expansion, by ΔE00 statistics of the linear images
 * (never by bytes). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "biref/biref.h"
#include "test_cases.h"
#include "test_render_util.h"

static int load_scene(biref_scene *sc)
{
    return test_load_scene("examples/fig9c_analyzer45.json", sc, test_quick() ? 16 : 40, test_quick() ? 9 : 24);
}

static float *render(const biref_scene *sc, biref_method m, int *pixels)
{
    biref_render_options opt;
    biref_render_options_default(&opt);
    opt.method = m;
    return test_render_xyz(sc, &opt, pixels);
}

static void expansion_matches_ground_truth_with_world_fixed_polarizer(void)
{
    biref_scene sc;
    if (load_scene(&sc)) return;
    int n = 0, n_ground_truth = 0;
    float *e = render(&sc, BIREF_METHOD_EXPANSION, &n);
    float *g = render(&sc, BIREF_METHOD_GROUND_TRUTH, &n_ground_truth);
    CHECK(e && g && n == n_ground_truth);
    if (e && g) {
        double sum = 0, worst = 0, ymin = INFINITY, ymax = 0;
        for (int i = 0; i < n; i++) {
            double a[3] = {e[3 * i], e[3 * i + 1], e[3 * i + 2]}, b[3] = {g[3 * i], g[3 * i + 1], g[3 * i + 2]};
            double d = biref_delta_e00_xyz(a, b);
            sum += d;
            worst = fmax(worst, d);
            ymin = fmin(ymin, a[1]);
            ymax = fmax(ymax, a[1]);
        }
        printf("expansion vs ground truth, world-fixed polarizer + analyzer at 45 deg: mean dE00 %.3f, max %.3f\n",
               sum / n, worst);
        CHECK(sum / n < 0.1);
        CHECK(worst < 1.0);
        CHECK(ymax > 2 * ymin + 0.01); /* not a uniform picture */
    }
    free(e);
    free(g);
}

/* The analytic method renders world-fixed polarizers with its general terms (the GPU shader's),
 * close to the exact expansion. */
static void analytic_close_to_expansion_with_world_fixed_polarizer(void)
{
    biref_scene sc;
    if (load_scene(&sc)) return;
    int n = 0, n_expansion = 0;
    float *a = render(&sc, BIREF_METHOD_ANALYTIC, &n);
    float *e = render(&sc, BIREF_METHOD_EXPANSION, &n_expansion);
    CHECK(a && e && n == n_expansion);
    if (a && e) {
        double sum = 0, worst = 0;
        for (int i = 0; i < n; i++) {
            double x[3] = {a[3 * i], a[3 * i + 1], a[3 * i + 2]}, y[3] = {e[3 * i], e[3 * i + 1], e[3 * i + 2]};
            double d = biref_delta_e00_xyz(x, y);
            sum += d;
            worst = fmax(worst, d);
        }
        printf("analytic vs expansion, world-fixed polarizer + analyzer at 45 deg: mean dE00 %.3f, max %.3f\n",
               sum / n, worst);
        CHECK(sum / n < 0.1 && worst < 2);
    }
    free(a);
    free(e);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"expansion_matches_ground_truth_with_world_fixed_polarizer", expansion_matches_ground_truth_with_world_fixed_polarizer},
        {"analytic_close_to_expansion_with_world_fixed_polarizer", analytic_close_to_expansion_with_world_fixed_polarizer},
    };
    return test_run_cases("test_render_expansion", cases, TEST_COUNT(cases), argc, argv);
}
