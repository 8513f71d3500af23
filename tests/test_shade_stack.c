/* biref_shade_stack_hit: a one-layer stack at a hit is the slab at that hit (exactly with the numeric
 * method, under world-fixed polarizers and random hit geometries; to the expansion's tolerance with
 * the analytic method), a layer cut into two halves changes nothing, and bad hits are refused. */
#include <math.h>
#include <string.h>

#include "biref/biref.h"
#include "test_cases.h"

static biref_spectral *sp;

static biref_shader *shader(biref_method m, int world_fixed)
{
    biref_integrator_options opt;
    biref_integrator_options_default(&opt);
    opt.method = m;
    opt.samples = 48;
    static const double half[2] = {0.5, 0.5}, pass[2] = {1, 1};
    static const double pol[3] = {0.6, 0.0, 0.8}, an[3] = {0.0, 0.8, -0.6};
    biref_light l;
    CHECK(biref_light_sp(half, pass, &l) == BIREF_OK);
    if (world_fixed) {
        CHECK(biref_light_world_polarizer(&l, pol) == BIREF_OK);
        CHECK(biref_light_world_analyzer(&l, an) == BIREF_OK);
    }
    biref_shader *sh = NULL;
    char msg[256];
    CHECK(biref_shader_create(sp, &opt, &l, &sh, msg, sizeof msg) == BIREF_OK);
    return sh;
}

/* A random slab at a random hit: unit normal, tangent, view ray not in the surface. */
static void random_hit(test_rng *rng, biref_surface *s, double view[3])
{
    double n = 0, t = 0, v;
    do {
        n = t = 0;
        for (int k = 0; k < 3; k++) {
            s->normal[k] = test_uniform(rng, -1, 1);
            s->tangent[k] = test_uniform(rng, -1, 1);
            s->axis[k] = test_uniform(rng, -1, 1);
            view[k] = test_uniform(rng, -1, 1);
            n += s->normal[k] * s->normal[k];
            t += s->tangent[k] * s->tangent[k];
        }
        v = view[0] * s->normal[0] + view[1] * s->normal[1] + view[2] * s->normal[2];
    } while (n < 0.1 || t < 0.1 || fabs(v) < 0.2 * sqrt(n));
    s->eta_o = test_uniform(rng, 1.4, 1.7);
    s->eta_e = s->eta_o + test_uniform(rng, -0.05, 0.05);
    s->thickness_nm = test_uniform(rng, 500, 20000);
    s->eta_i = test_uniform(rng, 1.0, 1.4);
}

/* The surface's slab as a one-layer stack (eta_i the surround). */
static void one_layer(const biref_surface *s, biref_stack *st, biref_stack_surface *ss)
{
    memset(st, 0, sizeof *st);
    st->eta_i = s->eta_i;
    st->n_layers = 1;
    st->layers[0] = (biref_layer){s->eta_o, s->eta_e, {s->axis[0], s->axis[1], s->axis[2]}, s->thickness_nm, 0, NULL};
    memcpy(ss->normal, s->normal, sizeof ss->normal);
    memcpy(ss->tangent, s->tangent, sizeof ss->tangent);
    ss->stack = st;
}

/* The stack shaded by method m against the slab shaded by method ref. */
static void compare(biref_method m, biref_method ref, int world_fixed, double tol_abs)
{
    biref_shader *sh = shader(m, world_fixed), *shr = shader(ref, world_fixed);
    test_rng rng = {0x57ac4ed5ULL + (uint64_t)m * 7 + (uint64_t)world_fixed};
    double worst = 0;
    for (int trial = 0; trial < 40; trial++) {
        biref_surface s;
        double view[3], T[3], R[3], Ts[3], Rs[3];
        random_hit(&rng, &s, view);
        biref_stack st;
        biref_stack_surface ss;
        one_layer(&s, &st, &ss);
        biref_hit_frames f1, f2;
        CHECK(biref_shade_hit(shr, &s, view, T, R, &f1) == BIREF_OK);
        CHECK(biref_shade_stack_hit(sh, &ss, view, Ts, Rs, &f2) == BIREF_OK);
        CHECK_NEAR(f2.theta, f1.theta, 1e-15);
        for (int j = 0; j < 3; j++) {
            worst = fmax(worst, fmax(fabs(T[j] - Ts[j]), fabs(R[j] - Rs[j])));
            CHECK(fabs(T[j] - Ts[j]) <= tol_abs && fabs(R[j] - Rs[j]) <= tol_abs);
        }
    }
    printf("  method %d, world-fixed %d: worst |stack - slab| %.3g\n", (int)m, world_fixed, worst);
    biref_shader_destroy(sh);
    biref_shader_destroy(shr);
}

static void one_layer_stack_is_the_slab_numeric(void)
{
    compare(BIREF_METHOD_NUMERIC, BIREF_METHOD_NUMERIC, 0, 1e-12);
    compare(BIREF_METHOD_NUMERIC, BIREF_METHOD_NUMERIC, 1, 1e-12);
}

/* The analytic method shades a stack by its expansion (truncation bound 1e-3 per intensity and
 * wavelength): against the slab's ground truth. */
static void one_layer_stack_is_the_slab_analytic(void)
{
    compare(BIREF_METHOD_ANALYTIC, BIREF_METHOD_GROUND_TRUTH, 0, 1e-3);
    compare(BIREF_METHOD_ANALYTIC, BIREF_METHOD_GROUND_TRUTH, 1, 1e-3);
}

static void halving_a_layer_changes_nothing(void)
{
    biref_shader *sh = shader(BIREF_METHOD_NUMERIC, 1);
    test_rng rng = {0x4a1fULL};
    for (int trial = 0; trial < 20; trial++) {
        biref_surface s;
        double view[3], T[3], R[3], T2[3], R2[3];
        random_hit(&rng, &s, view);
        biref_stack st, halves;
        biref_stack_surface ss, sh2;
        one_layer(&s, &st, &ss);
        halves = st;
        halves.n_layers = 2;
        halves.layers[0].thickness_nm *= 0.5;
        halves.layers[1] = halves.layers[0];
        sh2 = ss;
        sh2.stack = &halves;
        CHECK(biref_shade_stack_hit(sh, &ss, view, T, R, NULL) == BIREF_OK);
        CHECK(biref_shade_stack_hit(sh, &sh2, view, T2, R2, NULL) == BIREF_OK);
        for (int j = 0; j < 3; j++) {
            CHECK_NEAR(T2[j], T[j], 1e-10);
            CHECK_NEAR(R2[j], R[j], 1e-10);
        }
    }
    biref_shader_destroy(sh);
}

static void bad_stack_hits_are_refused(void)
{
    biref_shader *sh = shader(BIREF_METHOD_ANALYTIC, 0);
    biref_stack st = {1.0, 1, {{1.5, 1.6, {1, 0, 0}, 1000, 0, NULL}}};
    biref_stack_surface ss = {{0, 1, 0}, {1, 0, 0}, &st};
    const double view[3] = {0, -1, 0.2}, grazing[3] = {1, 0, 0};
    double T[3], R[3];
    CHECK(biref_shade_stack_hit(sh, &ss, view, T, R, NULL) == BIREF_OK);
    CHECK(biref_shade_stack_hit(sh, &ss, grazing, T, R, NULL) == BIREF_ERR_INVALID);
    CHECK(biref_shade_stack_hit(NULL, &ss, view, T, R, NULL) == BIREF_ERR_INVALID);
    biref_stack_surface none = ss;
    none.stack = NULL;
    CHECK(biref_shade_stack_hit(sh, &none, view, T, R, NULL) == BIREF_ERR_INVALID);
    biref_stack_surface flat = ss;
    memset(flat.normal, 0, sizeof flat.normal);
    CHECK(biref_shade_stack_hit(sh, &flat, view, T, R, NULL) == BIREF_ERR_INVALID);
    st.n_layers = 0;
    CHECK(biref_shade_stack_hit(sh, &ss, view, T, R, NULL) == BIREF_ERR_INVALID);
    st.n_layers = 1;
    st.layers[0].eta_e = NAN;
    CHECK(biref_shade_stack_hit(sh, &ss, view, T, R, NULL) == BIREF_ERR_INVALID);
    biref_shader_destroy(sh);
}

int main(int argc, char **argv)
{
    if (biref_spectral_create(NULL, &sp, NULL, 0) != BIREF_OK) return 1;
    static const test_case cases[] = {
        {"one_layer_stack_is_the_slab_numeric", one_layer_stack_is_the_slab_numeric},
        {"one_layer_stack_is_the_slab_analytic", one_layer_stack_is_the_slab_analytic},
        {"halving_a_layer_changes_nothing", halving_a_layer_changes_nothing},
        {"bad_stack_hits_are_refused", bad_stack_hits_are_refused},
    };
    int rc = test_run_cases("test_shade_stack", cases, TEST_COUNT(cases), argc, argv);
    biref_spectral_destroy(sp);
    return rc;
}
