/* The renderer with the path-group expansion (beyond the paper): a world-fixed polarizer and an
 * analyzer at 45 degrees on fig. 9c's slab, against the 16384-sample ground truth, by ΔE00
 * statistics of the linear images (never by bytes). */
#include <math.h>
#include <stdlib.h>

#include "biref/biref.h"
#include "test_util.h"

static float *render(const biref_scene *sc, biref_method m, int *n)
{
    biref_render_options opt;
    biref_render_options_default(&opt);
    opt.method = m;
    biref_renderer *r = NULL;
    char msg[256];
    if (biref_renderer_create(sc, &opt, &r, msg, sizeof msg) != BIREF_OK) {
        fprintf(stderr, "renderer: %s\n", msg);
        return NULL;
    }
    *n = biref_renderer_width(r) * biref_renderer_height(r);
    float *xyz = malloc((size_t)*n * 3 * sizeof *xyz);
    if (xyz && biref_render_image(r, xyz, NULL, NULL, NULL) != BIREF_OK) {
        free(xyz);
        xyz = NULL;
    }
    biref_renderer_destroy(r);
    return xyz;
}

int main(void)
{
    biref_scene sc;
    char msg[256];
    CHECK(biref_scene_load("examples/fig9c_analyzer45.json", &sc, msg, sizeof msg) == BIREF_OK);
    int quick = getenv("BIREF_TEST_QUICK") != NULL;
    sc.camera.width = quick ? 16 : 40;
    sc.camera.height = quick ? 9 : 24;
    int n1 = 0, n2 = 0;
    float *e = render(&sc, BIREF_METHOD_EXPANSION, &n1);
    float *g = render(&sc, BIREF_METHOD_GROUND_TRUTH, &n2);
    CHECK(e && g && n1 == n2);
    if (e && g) {
        double sum = 0, worst = 0, ymin = INFINITY, ymax = 0;
        for (int i = 0; i < n1; i++) {
            double a[3] = {e[3 * i], e[3 * i + 1], e[3 * i + 2]}, b[3] = {g[3 * i], g[3 * i + 1], g[3 * i + 2]};
            double d = biref_delta_e00_xyz(a, b);
            sum += d;
            worst = fmax(worst, d);
            ymin = fmin(ymin, a[1]);
            ymax = fmax(ymax, a[1]);
        }
        printf("expansion vs ground truth, world-fixed polarizer + analyzer at 45 deg: mean dE00 %.3f, max %.3f\n",
               sum / n1, worst);
        CHECK(sum / n1 < 0.1);
        CHECK(worst < 1.0);
        CHECK(ymax > 2 * ymin + 0.01); /* not a uniform picture */
    }
    free(e);
    free(g);
    /* The paper's method refuses world-fixed polarizers with a clear message. */
    biref_render_options opt;
    biref_render_options_default(&opt);
    biref_renderer *r = NULL;
    CHECK(biref_renderer_create(&sc, &opt, &r, msg, sizeof msg) == BIREF_ERR_INVALID && r == NULL);
    return test_report("test_render_expansion");
}
