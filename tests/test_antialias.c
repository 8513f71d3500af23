/* Spatial anti-aliasing: the pre-integrated phase table against direct averages of the point
 * table, and a small aliasing scene where the prefiltered render must be much closer to a
 * super-sampled reference than the plain one. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"
#include "optics/modes_internal.h"
#include "render/render_internal.h"
#include "spectral/phase_prefilter.h"
#include "test_cases.h"
#include "test_render_util.h"

/* Box average of the point look-ups by a fine midpoint rule. */
static void box_by_quadrature(const biref_spectral *sp, double d, double w, double c[3], double s[3])
{
    const int n = 4000;
    for (int j = 0; j < 3; j++) c[j] = s[j] = 0.0;
    for (int i = 0; i < n; i++) {
        double cc[3], ss[3];
        biref_spectral_phase_integrals(sp, d - 0.5 * w + (i + 0.5) * w / n, cc, ss);
        for (int j = 0; j < 3; j++) c[j] += cc[j] / n, s[j] += ss[j] / n;
    }
}

static biref_spectral *sp;
static biref_phase_prefilter *pf;

/* Near zero, straddling it, mid-table, straddling the table's end (1e5 nm), beyond it. */
static void box_average_matches_quadrature_of_point_table(void)
{
    const double D[] = {0.0, 120.0, -700.0, 2500.0, 31000.0, 99990.0, 2.5e5};
    const double W[] = {0.5, 40.0, 300.0, 1500.0, 9000.0};
    double worst = 0.0;
    for (size_t a = 0; a < sizeof D / sizeof D[0]; a++)
        for (size_t b = 0; b < sizeof W / sizeof W[0]; b++) {
            double c[3], s[3], cq[3], sq[3];
            biref_phase_integrals_box(pf, D[a], W[b], c, s);
            box_by_quadrature(sp, D[a], W[b], cq, sq);
            for (int j = 0; j < 3; j++) worst = fmax(worst, fmax(fabs(c[j] - cq[j]), fabs(s[j] - sq[j])));
        }
    printf("box average vs quadrature of the point table: max |error| %.2e\n", worst);
    CHECK(worst < 2e-5);
}

/* A zero width is the point look-up exactly; a tiny one agrees with it. */
static void zero_width_box_is_the_point_lookup(void)
{
    double c0[3], s0[3], c1[3], s1[3];
    biref_spectral_phase_integrals(sp, 1234.5, c0, s0);
    biref_phase_integrals_box(pf, 1234.5, 0.0, c1, s1);
    for (int j = 0; j < 3; j++) CHECK(c0[j] == c1[j] && s0[j] == s1[j]);
    biref_phase_integrals_box(pf, 1234.5, 0.01, c1, s1);
    for (int j = 0; j < 3; j++) {
        CHECK_NEAR(c1[j], c0[j], 1e-5);
        CHECK_NEAR(s1[j], s0[j], 1e-5);
    }
}

/* A footprint much wider than a fringe averages the oscillation away. */
static void wide_box_averages_the_fringes_away(void)
{
    double c1[3], s1[3];
    biref_phase_integrals_box(pf, 3000.0, 20000.0, c1, s1);
    for (int j = 0; j < 3; j++) CHECK(fabs(c1[j]) < 0.02 && fabs(s1[j]) < 0.02);
}

static float *render(const biref_scene *sc, biref_method method, biref_antialias aa, int K)
{
    biref_render_options opt;
    biref_render_options_default(&opt);
    opt.method = method;
    opt.antialias = aa;
    opt.supersample = K;
    return test_render_xyz(sc, &opt, NULL);
}

/* Mean over rows y0 ... H - 1 (W pixels each). */
static double mean_de(const float *a, const float *b, int W, int H, int y0)
{
    double sum = 0.0;
    size_t n = (size_t)W * (H - y0);
    a += (size_t)3 * W * y0, b += (size_t)3 * W * y0;
    for (size_t i = 0; i < n; i++) {
        double x[3] = {a[3 * i], a[3 * i + 1], a[3 * i + 2]}, y[3] = {b[3 * i], b[3 * i + 1], b[3 * i + 2]};
        sum += biref_delta_e00_xyz(x, y);
    }
    return sum / (double)n;
}

/* The thick slab at a grazing view: fringes narrower than a pixel towards the sides. Measured
 * below the slab's far edge (the top 30 % of the frame): the prefilter removes the aliasing of the
 * phases, not that of geometric edges, which only super-sampling cures. */
static void aliasing_scene(biref_method method, int W, int H, int K_ref)
{
    biref_scene sc;
    if (test_load_scene("examples/aliasing/thick_grazing.json", &sc, W, H)) return;
    float *ref = render(&sc, method, BIREF_ANTIALIAS_NONE, K_ref);
    float *plain = render(&sc, method, BIREF_ANTIALIAS_NONE, 1);
    float *pre = render(&sc, method, BIREF_ANTIALIAS_PREFILTER, 1);
    CHECK(ref && plain && pre);
    if (ref && plain && pre) {
        int y0 = (int)(0.3 * H);
        double e_plain = mean_de(plain, ref, W, H, y0), e_pre = mean_de(pre, ref, W, H, y0);
        printf("%s %dx%d vs %dx%d supersampled: mean dE00 plain %.3f, prefiltered %.3f (%.1fx closer)\n",
               biref_method_name(method), W, H, K_ref, K_ref, e_plain, e_pre, e_plain / e_pre);
        CHECK(e_plain > 1.0); /* the scene does alias */
        CHECK(e_pre * 3.0 <= e_plain);
    }
    free(ref);
    free(plain);
    free(pre);
}

/* The prefilter needs the phase table: numeric methods refuse it; the super-sampling factor is
 * bounded. */
static void prefilter_and_supersample_options_are_checked(void)
{
    biref_scene sc;
    char msg[256];
    CHECK(biref_scene_load("examples/fig9c.json", &sc, msg, sizeof msg) == BIREF_OK);
    biref_render_options opt;
    biref_render_options_default(&opt);
    CHECK(opt.antialias == BIREF_ANTIALIAS_NONE && opt.supersample == 1);
    biref_renderer *r = NULL;
    opt.method = BIREF_METHOD_NUMERIC;
    opt.antialias = BIREF_ANTIALIAS_PREFILTER;
    CHECK(biref_renderer_create(test_sp(), &sc, &opt, &r, msg, sizeof msg) == BIREF_ERR_INVALID && !r);
    opt.method = BIREF_METHOD_ANALYTIC;
    opt.supersample = 0;
    CHECK(biref_renderer_create(test_sp(), &sc, &opt, &r, msg, sizeof msg) == BIREF_ERR_INVALID && !r);
    opt.supersample = BIREF_MAX_SUPERSAMPLE + 1;
    CHECK(biref_renderer_create(test_sp(), &sc, &opt, &r, msg, sizeof msg) == BIREF_ERR_INVALID && !r);
}

/* Re(opl) of the legs of a ray along dir through the slab's hit frame and the modes' normal
 * components (biref_shading_frames, biref_uniaxial_normal_components): the footprint's
 * frame-free dot products must give the same paths. */
static void legs_through_the_frame(const render_slab *sl, const double dir[3], double opl[4])
{
    biref_hit_frames f;
    biref_shading_frames(sl->normal, sl->tangent, sl->axis_world, &sl->base, dir, &f);
    double complex q[4];
    biref_uniaxial_normal_components(f.slab.eta_o, f.slab.eta_e, f.slab.axis, f.slab.eta_i * sin(f.theta), q);
    const double d = f.slab.thickness_nm;
    opl[BIREF_LEG_DOWN_O] = -creal(q[BIREF_MODE_O_DOWN]) * d;
    opl[BIREF_LEG_DOWN_E] = -creal(q[BIREF_MODE_E_DOWN]) * d;
    opl[BIREF_LEG_UP_O] = creal(q[BIREF_MODE_O_UP]) * d;
    opl[BIREF_LEG_UP_E] = creal(q[BIREF_MODE_E_UP]) * d;
}

/* Footprints of random rays (both faces of the slab, normal to grazing incidence, steps of a
 * pixel and of a hundred) against the frame route's differences, on the thick grazing slab and on
 * fig. 9c's: equal up to the rounding of the paths they difference (a relative 1e-13 of them). */
static void footprint_matches_the_modes(void)
{
    const char *scenes[] = {"examples/aliasing/thick_grazing.json", "examples/fig9c.json"};
    test_rng rng = {0xf007u};
    double worst = 0.0;
    int n = 0;
    for (int s = 0; s < 2; s++) {
        biref_scene sc;
        if (test_load_scene(scenes[s], &sc, 64, 36)) continue;
        biref_render_options opt;
        biref_render_options_default(&opt);
        opt.antialias = BIREF_ANTIALIAS_PREFILTER;
        biref_renderer *r = NULL;
        CHECK(biref_renderer_create(test_sp(), &sc, &opt, &r, NULL, 0) == BIREF_OK);
        if (!r) continue;
        const render_slab *sl = &r->slabs[0];
        for (int k = 0; k < 400; k++) {
            double dir[3], nb[2][3], step = k % 2 ? 1e-3 : 0.1;
            test_random_axis(&rng, dir);
            const double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
            for (int i = 0; i < 3; i++) dir[i] /= len;
            if (fabs(dir[0] * sl->normal[0] + dir[1] * sl->normal[1] + dir[2] * sl->normal[2]) < 0.02) continue;
            for (int a = 0; a < 2; a++) {
                for (int i = 0; i < 3; i++) nb[a][i] = dir[i] + step * test_uniform(&rng, -1, 1);
                double l = sqrt(nb[a][0] * nb[a][0] + nb[a][1] * nb[a][1] + nb[a][2] * nb[a][2]);
                for (int i = 0; i < 3; i++) nb[a][i] /= l;
                if (fabs(nb[a][0] * sl->normal[0] + nb[a][1] * sl->normal[1] + nb[a][2] * sl->normal[2]) < 0.02)
                    memcpy(nb[a], dir, sizeof dir);
            }
            biref_opl_footprint fp;
            biref_render_footprint_rays(r, sl, dir, nb[0], nb[1], &fp);
            CHECK(fp.pf != NULL);
            double o0[4], o1[4];
            legs_through_the_frame(sl, dir, o0);
            for (int a = 0; a < 2; a++) {
                legs_through_the_frame(sl, nb[a], o1);
                for (int l = 0; l < 4; l++) worst = fmax(worst, fabs(fp.grad[l][a] - (o1[l] - o0[l])) / fabs(o0[l]));
            }
            n++;
        }
        biref_renderer_destroy(r);
    }
    printf("%d footprints: max |grad - frame route| / |opl| = %.2g\n", n, worst);
    CHECK(n > 300);
    CHECK(worst < 1e-13);
}

/* BIREF_TEST_QUICK (the sanitizer run): smaller images and references. */
static void prefilter_reduces_aliasing_analytic(void)
{
    const int quick = test_quick();
    aliasing_scene(BIREF_METHOD_ANALYTIC, quick ? 48 : 64, quick ? 27 : 36, quick ? 8 : 12);
}

static void prefilter_reduces_aliasing_expansion(void)
{
    const int quick = test_quick();
    aliasing_scene(BIREF_METHOD_EXPANSION, quick ? 24 : 32, quick ? 14 : 18, quick ? 6 : 8);
}

int main(int argc, char **argv)
{
    if (biref_spectral_create(NULL, &sp, NULL, 0) != BIREF_OK || biref_phase_prefilter_create(sp, &pf) != BIREF_OK) return 1;
    static const test_case cases[] = {
        {"box_average_matches_quadrature_of_point_table", box_average_matches_quadrature_of_point_table},
        {"zero_width_box_is_the_point_lookup", zero_width_box_is_the_point_lookup},
        {"wide_box_averages_the_fringes_away", wide_box_averages_the_fringes_away},
        {"prefilter_and_supersample_options_are_checked", prefilter_and_supersample_options_are_checked},
        {"footprint_matches_the_modes", footprint_matches_the_modes},
        {"prefilter_reduces_aliasing_analytic", prefilter_reduces_aliasing_analytic},
        {"prefilter_reduces_aliasing_expansion", prefilter_reduces_aliasing_expansion},
    };
    int rc = test_run_cases("test_antialias", cases, TEST_COUNT(cases), argc, argv);
    biref_phase_prefilter_destroy(pf);
    biref_spectral_destroy(sp);
    return rc;
}
