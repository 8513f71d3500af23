/* The renderer with the path-group expansion (beyond the paper): a world-fixed polarizer and an
 * analyzer at 45 degrees on fig. 9c's slab, against the 16384-sample ground truth, by ΔE00
 * statistics of the linear images (never by bytes). */
#include <math.h>
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

/* The paper's method refuses world-fixed polarizers with a clear message. */
static void analytic_method_refuses_world_fixed_polarizer(void)
{
    biref_scene sc;
    if (load_scene(&sc)) return;
    biref_render_options opt;
    biref_render_options_default(&opt);
    biref_renderer *r = NULL;
    char msg[256];
    CHECK(biref_renderer_create(test_sp(), &sc, &opt, &r, msg, sizeof msg) == BIREF_ERR_INVALID && r == NULL);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"expansion_matches_ground_truth_with_world_fixed_polarizer", expansion_matches_ground_truth_with_world_fixed_polarizer},
        {"analytic_method_refuses_world_fixed_polarizer", analytic_method_refuses_world_fixed_polarizer},
    };
    return test_run_cases("test_render_expansion", cases, TEST_COUNT(cases), argc, argv);
}
