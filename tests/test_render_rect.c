/* biref_renderer_render_rect (experimental.h): a frame cut into rectangles at odd offsets and sizes,
 * each rendered into a buffer of its own and pasted together, equals the whole frame's render bit
 * for bit (plain, prefiltered, supersampled with pixel groups that straddle the cuts, world-fixed
 * polarizers); the rectangle writes nothing outside itself; bad rectangles are refused. */
#include <stdlib.h>
#include <string.h>

#include "test_cases.h"
#include "test_render_util.h"

static int quick;

/* Renders sc in rectangles of tw x th (the last of each row and column smaller), each into its own
 * buffer with a guard row stride, pasted into out; stats summed. Returns 0 or -1. */
static int render_in_rects(const biref_renderer *r, int tw, int th, float *out, biref_render_stats *sum)
{
    const int W = biref_renderer_width(r), H = biref_renderer_height(r);
    const size_t stride = 3 * (size_t)tw + 5; /* more than the rectangle's width: rows are strided */
    float *buf = malloc(stride * (size_t)th * sizeof *buf);
    if (!buf) return -1;
    memset(sum, 0, sizeof *sum);
    int rc = 0;
    for (int y = 0; y < H && !rc; y += th)
        for (int x = 0; x < W && !rc; x += tw) {
            const int w = W - x < tw ? W - x : tw, h = H - y < th ? H - y : th;
            for (size_t i = 0; i < stride * (size_t)th; i++) buf[i] = -7.0f;
            biref_render_stats st;
            if (biref_renderer_render_rect(r, x, y, w, h, buf, stride, &st) != BIREF_OK) rc = -1;
            for (int j = 0; j < h; j++) {
                memcpy(out + ((size_t)(y + j) * W + x) * 3, buf + (size_t)j * stride, 3 * (size_t)w * sizeof *buf);
                /* The padding past the rectangle's width is untouched. */
                for (size_t i = 3 * (size_t)w; i < stride; i++) CHECK(buf[(size_t)j * stride + i] == -7.0f);
            }
            CHECK(st.pixels == (long)w * h);
            sum->pixels += st.pixels;
            sum->slab_pixels += st.slab_pixels;
            sum->fallback_evals += st.fallback_evals;
        }
    free(buf);
    return rc;
}

static void check_scene(const char *path, biref_antialias aa, int supersample, int threads)
{
    const int W = quick ? 41 : 83, H = quick ? 23 : 47;
    biref_scene sc;
    if (test_load_scene(path, &sc, W, H)) return;
    biref_render_options opt;
    biref_render_options_default(&opt);
    opt.antialias = aa;
    opt.supersample = supersample;
    opt.threads = threads;
    biref_renderer *r = NULL;
    char msg[256];
    if (biref_renderer_create(test_sp(), &sc, &opt, &r, msg, sizeof msg) != BIREF_OK) {
        fprintf(stderr, "%s: %s\n", path, msg);
        CHECK(0);
        return;
    }
    const size_t n = (size_t)W * H * 3;
    float *ref = malloc(n * sizeof *ref), *cut = malloc(n * sizeof *cut);
    biref_render_stats whole, parts;
    CHECK(ref && cut);
    if (ref && cut && biref_render_image(r, ref, NULL, NULL, &whole) == BIREF_OK) {
        /* 13 x 7: groups of 32 pixels (and of 3 supersampled pixels) cut at other places. */
        CHECK(render_in_rects(r, 13, 7, cut, &parts) == 0);
        const int same = memcmp(ref, cut, n * sizeof *ref) == 0;
        printf("%s (antialias %d, %dx%d samples, %d threads): rectangles %s the frame\n", path, (int)aa, supersample,
               supersample, threads, same ? "equal" : "DIFFER FROM");
        CHECK(same);
        CHECK(parts.pixels == whole.pixels && parts.slab_pixels == whole.slab_pixels &&
              parts.fallback_evals == whole.fallback_evals);
        CHECK(whole.slab_pixels > 0);
    } else {
        CHECK(0);
    }
    free(ref);
    free(cut);
    biref_renderer_destroy(r);
}

static void test_rects_equal_frame(void)
{
    check_scene("examples/fig9a.json", BIREF_ANTIALIAS_NONE, 1, 2);
    check_scene("examples/fig9c.json", BIREF_ANTIALIAS_PREFILTER, 1, 1);
    check_scene("examples/fig9c_analyzer45.json", BIREF_ANTIALIAS_NONE, 1, 2);
    if (!quick) check_scene("examples/fig9b.json", BIREF_ANTIALIAS_PREFILTER, 3, 2);
}

static void test_rect_refuses_outside(void)
{
    biref_scene sc;
    if (test_load_scene("examples/fig9a.json", &sc, 16, 8)) return;
    biref_render_options opt;
    biref_render_options_default(&opt);
    biref_renderer *r = NULL;
    if (biref_renderer_create(test_sp(), &sc, &opt, &r, NULL, 0) != BIREF_OK) {
        CHECK(0);
        return;
    }
    float buf[16 * 8 * 3];
    CHECK(biref_renderer_render_rect(r, 0, 0, 16, 8, buf, 48, NULL) == BIREF_OK);
    CHECK(biref_renderer_render_rect(r, 1, 0, 16, 8, buf, 48, NULL) == BIREF_ERR_INVALID);  /* past the right */
    CHECK(biref_renderer_render_rect(r, 0, 4, 16, 5, buf, 48, NULL) == BIREF_ERR_INVALID);  /* past the bottom */
    CHECK(biref_renderer_render_rect(r, -1, 0, 4, 4, buf, 48, NULL) == BIREF_ERR_INVALID);
    CHECK(biref_renderer_render_rect(r, 0, 0, 0, 4, buf, 48, NULL) == BIREF_ERR_INVALID);   /* empty */
    CHECK(biref_renderer_render_rect(r, 0, 0, 4, 4, buf, 11, NULL) == BIREF_ERR_INVALID);   /* stride < 3 width */
    CHECK(biref_renderer_render_rect(r, 0, 0, 4, 4, NULL, 12, NULL) == BIREF_ERR_INVALID);
    CHECK(biref_renderer_render_rect(NULL, 0, 0, 4, 4, buf, 12, NULL) == BIREF_ERR_INVALID);
    biref_renderer_destroy(r);
}

int main(int argc, char **argv)
{
    quick = getenv("BIREF_TEST_QUICK") != NULL;
    static const test_case cases[] = {
        {"rects_equal_frame", test_rects_equal_frame},
        {"rect_refuses_outside", test_rect_refuses_outside},
    };
    return test_run_cases("test_render_rect", cases, TEST_COUNT(cases), argc, argv);
}
