/* The renderer's tiles (its one pixel path: rays, slab intersections, hit frames, radiance look-ups
 * and colours in structure-of-arrays loops) against a reference that shades one sample at a time
 * (test_render_reference.h), on the examples, on a scene that exercises what the examples do not:
 * two slabs (one in the coherent regime, which the packet kernel declines), a panel, a checker
 * ground, an s/p light and a p analyzer, at a width that leaves a partial tile, and on the same
 * scene under world-fixed polarizers (each hit's light resolved in its frames for the packet kernel,
 * the background through per-ray analyzers), also with a world-fixed polarizer before the p
 * analyzer. BIREF_TEST_QUICK (set under sanitizers) shrinks the images. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"
#include "render/render_internal.h"
#include "render/render_tile.h"
#include "spectral/analytic_packet.h"
#include "spectral/integrator_internal.h"
#include "test_cases.h"
#include "test_render_reference.h"
#include "test_render_util.h"

static int quick;

static const char MIXED[] =
    "{\"camera\": {\"position\": [1.2, 2.6, 2.2], \"look_at\": [0, 0, 0], \"fov_deg\": 60, \"width\": 8,"
    " \"height\": 8, \"exposure\": 1.5},"
    " \"slabs\": [{\"center\": [0, 0, 0], \"size\": [2.5, 2], \"thickness_mm\": 0.8, \"normal\": [0, 0.3, 1],"
    "   \"tangent\": [1, 0, 0], \"axis\": [0.3, 0.6, 0.5], \"eta_o\": 1.54, \"eta_e\": 1.55},"
    "  {\"center\": [0.6, 0.2, 0.5], \"size\": [1, 1.5], \"thickness_um\": 0.4, \"normal\": [0.2, 1, 0.1],"
    "   \"axis\": [1, 0, 0.2], \"eta_o\": 1.66, \"eta_e\": 1.49}],"
    " \"light\": {\"panel\": {\"center\": [-0.8, -1.5, -1.2], \"size\": [1.5, 1.5], \"normal\": [0.4, 0.8, 0.5],"
    "   \"radiance\": 2.5},"
    "  \"environment\": {\"type\": \"checker\", \"zenith\": 0.3, \"horizon\": 0.6, \"a\": 0.1, \"b\": 0.8, \"size\": 0.5},"
    "  \"polarization\": {\"type\": \"sp\", \"s\": 0.7, \"p\": 0.3}},"
    " \"filter\": {\"type\": \"p\"}}";

/* The mixed scene under a world-fixed polarizer and analyzer (the light's other form), and under a
 * world-fixed polarizer with its p analyzer. */
static char WORLD_FIXED[sizeof MIXED + 128], WORLD_POLARIZER[sizeof MIXED + 128];

/* A renderer of the scene at width x height on the instruction set isa (BIREF_SIMD), with point or
 * prefiltered look-ups. */
static biref_renderer *make(const char *path, const char *isa, int width, int height, biref_antialias aa)
{
    biref_scene sc;
    char msg[256];
    const char *text = !path                             ? MIXED
                       : !strcmp(path, "world-fixed")     ? WORLD_FIXED
                       : !strcmp(path, "world-polarizer") ? WORLD_POLARIZER
                                                          : MIXED;
    biref_status s = path && text == MIXED ? biref_scene_load(path, &sc, msg, sizeof msg)
                                           : biref_scene_parse(text, strlen(text), &sc, msg, sizeof msg);
    CHECK(s == BIREF_OK);
    if (s) {
        fprintf(stderr, "%s: %s\n", path ? path : "mixed scene", msg);
        return NULL;
    }
    sc.camera.width = width;
    sc.camera.height = height;
    setenv("BIREF_SIMD", isa, 1);
    biref_render_options opt;
    biref_render_options_default(&opt);
    opt.threads = 2;
    opt.antialias = aa;
    biref_renderer *r = NULL;
    if (biref_renderer_create(test_sp(), &sc, &opt, &r, msg, sizeof msg) != BIREF_OK) fprintf(stderr, "renderer: %s\n", msg);
    unsetenv("BIREF_SIMD");
    CHECK(r != NULL);
    return r;
}

/* The image pixel by pixel through the reference, one sample through each pixel centre, stored as
 * the renderer stores; with the prefilter each footprint spans the steps to the next pixel's ray
 * right and below. */
static float *render_pixels(const biref_renderer *r, long *slab_pixels, long *fallbacks)
{
    const int W = biref_renderer_width(r), H = biref_renderer_height(r);
    float *xyz = malloc((size_t)W * H * 3 * sizeof *xyz);
    *slab_pixels = *fallbacks = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double c[3];
            int fb;
            *slab_pixels += ref_sample(r, x + 0.5, y + 0.5, 1.0, c, &fb);
            *fallbacks += fb;
            for (int i = 0; i < 3; i++) {
                const double v = c[i] / 1.0 * r->exposure;
                xyz[3 * ((size_t)y * W + x) + i] = (float)(isfinite(v) && fabs(v) <= FLT_MAX ? v : 0.0);
            }
        }
    return xyz;
}

/* Tiles and pixels of one renderer; returns the largest difference in units of the pixel
 * component (float rounding: 2^-24), or -1 when the slab pixel counts differ. */
static double compare(const biref_renderer *r, const char *what)
{
    const int W = biref_renderer_width(r), H = biref_renderer_height(r);
    const size_t n = (size_t)W * H * 3;
    float *tiles = malloc(n * sizeof *tiles);
    biref_render_stats st;
    CHECK(biref_render_image(r, tiles, NULL, NULL, &st) == BIREF_OK);
    long slab = 0, fb = 0;
    float *pixels = render_pixels(r, &slab, &fb);
    double worst = 0.0;
    size_t differ = 0;
    for (size_t k = 0; k < n; k++) {
        const double a = tiles[k], b = pixels[k];
        differ += a != b;
        worst = fmax(worst, fabs(a - b) / fmax(fmax(fabs(a), fabs(b)), 1e-30) * 0x1p24);
    }
    printf("%s: %ld slab pixels (%ld fallbacks) of %d; %zu of %zu components differ, worst by %.2g float roundings\n",
           what, slab, fb, W * H, differ, n, worst);
    const int same_hits = st.slab_pixels == slab;
    CHECK(same_hits);
    free(tiles);
    free(pixels);
    return same_hits ? worst : -1.0;
}

static const char *const SCENES[] = {"examples/fig9a.json", "examples/fig9b.json", "examples/fig9c.json",
                                     "examples/default.json", NULL, "world-fixed", "world-polarizer"};
#define N_SCENES (sizeof SCENES / sizeof SCENES[0])
static const biref_antialias AA[2] = {BIREF_ANTIALIAS_NONE, BIREF_ANTIALIAS_PREFILTER};
static const char *const AA_NAME[2] = {"point look-ups", "prefilter"};

/* Under BIREF_TEST_QUICK (the sanitizer build, where every renderer's tables take seconds): the
 * first example and the world-fixed scene with point look-ups, the mixed scene with the prefilter. */
static int skip(size_t scene, int aa)
{
    if (!quick) return 0;
    if (SCENES[scene] && !strcmp(SCENES[scene], "world-fixed")) return aa;
    if (SCENES[scene] && !strcmp(SCENES[scene], "world-polarizer")) return 1;
    return SCENES[scene] ? scene > 0 || aa : !aa;
}

static const char *scene_name(size_t i) { return SCENES[i] ? SCENES[i] : "mixed scene"; }

/* Without the packet kernel every hit goes the shader's one-by-one way from the same frames: the
 * tiles must give the reference's image to the bit (rays, intersections, frames, radiance,
 * colours). */
static void test_tiles_equal_pixels_scalar(void)
{
    const int W = quick ? 37 : 45, H = quick ? 9 : 24; /* 45 = a full tile and a partial one */
    for (int aa = 0; aa < 2; aa++)
        for (size_t i = 0; i < N_SCENES; i++) {
            if (skip(i, aa)) continue;
            biref_renderer *r = make(SCENES[i], "scalar", W, H, AA[aa]);
            if (!r) continue;
            char what[96];
            snprintf(what, sizeof what, "%s, scalar, %s", scene_name(i), AA_NAME[aa]);
            CHECK(compare(r, what) == 0.0);
            biref_renderer_destroy(r);
        }
}

/* With the packet kernel the hits' factors differ from the one-by-one worker's by roundings (its K
 * is computed from cos(theta), its arithmetic in lanes): every pixel within a few float roundings
 * of the reference, which a wrong frame, ray or look-up in a lane would exceed by far. */
static void test_tiles_near_pixels_kernel(void)
{
    const int W = quick ? 37 : 45, H = quick ? 9 : 24;
    for (int isa = BIREF_SIMD_BASELINE; isa < BIREF_SIMD_COUNT; isa++) {
        if (!biref_simd_isa_supported((biref_simd_isa)isa)) continue;
        /* Quick: the widest instruction set only (test_analytic_packet covers each kernel). */
        if (quick && isa + 1 < BIREF_SIMD_COUNT && biref_simd_isa_supported((biref_simd_isa)(isa + 1))) continue;
        const char *name = biref_simd_isa_name((biref_simd_isa)isa);
        for (int aa = 0; aa < 2; aa++)
            for (size_t i = 0; i < N_SCENES; i++) {
                if (skip(i, aa)) continue;
                biref_renderer *r = make(SCENES[i], name, W, H, AA[aa]);
                if (!r) continue;
                char what[96];
                snprintf(what, sizeof what, "%s, %s, %s", scene_name(i), name, AA_NAME[aa]);
                const double worst = compare(r, what);
                CHECK(worst >= 0.0 && worst <= 64.0);
                biref_renderer_destroy(r);
            }
    }
}

/* The tiles compiled for each instruction set give the same bits (no contracted multiply-adds):
 * the same renderer, only its tiles' instruction set changed. */
static void test_tile_isas_identical(void)
{
    const int W = quick ? 37 : 45, H = quick ? 9 : 24;
    const size_t n = (size_t)W * H * 3;
    for (size_t i = 0; i < N_SCENES; i++) {
        if (skip(i, 1)) continue;
        biref_renderer *r = make(SCENES[i], "baseline", W, H, BIREF_ANTIALIAS_PREFILTER);
        if (!r) continue;
        float *ref = malloc(n * sizeof *ref), *a = malloc(n * sizeof *a);
        r->tile_isa = BIREF_SIMD_BASELINE;
        CHECK(biref_render_image(r, ref, NULL, NULL, NULL) == BIREF_OK);
        for (int isa = BIREF_SIMD_AVX2; isa < BIREF_SIMD_COUNT; isa++) {
            if (!biref_simd_isa_supported((biref_simd_isa)isa)) continue;
            r->tile_isa = isa;
            CHECK(biref_render_image(r, a, NULL, NULL, NULL) == BIREF_OK);
            const int same = memcmp(a, ref, n * sizeof *a) == 0;
            printf("%s: %s tiles %s the baseline's\n", scene_name(i),
                   biref_simd_isa_name((biref_simd_isa)isa), same ? "equal" : "DIFFER FROM");
            CHECK(same);
        }
        free(ref);
        free(a);
        biref_renderer_destroy(r);
    }
}

int main(int argc, char **argv)
{
    quick = getenv("BIREF_TEST_QUICK") != NULL;
    /* Orthogonal axes, neither transverse to every ray: the background and the slab leak a little. */
    snprintf(WORLD_FIXED, sizeof WORLD_FIXED, "%.*s", (int)(strstr(MIXED, "\"polarization\"") - MIXED), MIXED);
    strcat(WORLD_FIXED, "\"polarization\": {\"type\": \"linear\", \"direction\": [0.6, 0, 0.8]}},"
                        " \"filter\": {\"type\": \"linear\", \"direction\": [0, 0.8, -0.6]}}");
    snprintf(WORLD_POLARIZER, sizeof WORLD_POLARIZER, "%.*s", (int)(strstr(MIXED, "\"polarization\"") - MIXED), MIXED);
    strcat(WORLD_POLARIZER, "\"polarization\": {\"type\": \"linear\", \"direction\": [0.6, 0, 0.8]}},"
                            " \"filter\": {\"type\": \"p\"}}");
    static const test_case cases[] = {
        {"tiles_equal_pixels_scalar", test_tiles_equal_pixels_scalar},
        {"tiles_near_pixels_kernel", test_tiles_near_pixels_kernel},
        {"tile_isas_identical", test_tile_isas_identical},
    };
    return test_run_cases("test_render_tile", cases, TEST_COUNT(cases), argc, argv);
}
