/* Image conversion to 8-bit sRGB by thresholds: the same bytes as biref_xyz_to_srgb8, for
 * random values, every threshold and its neighbouring doubles, and special values. */
#include <math.h>
#include <stdlib.h>

#include "biref/biref.h"
#include "color/srgb8_encoder.h"
#include "test_cases.h"

/* Seed of the random values; the image case continues the same sequence after them. */
enum { SEED = 42, RANDOM_VALUES = 200000 };

static int reference_code(double v)
{
    double s = biref_srgb_encode(v);
    if (!(s > 0.0)) s = 0.0;
    if (s > 1.0) s = 1.0;
    return (int)lround(s * 255.0);
}

static int mismatch(const biref_srgb8_encoder *e, double v) { return biref_srgb8_encode(e, v) != reference_code(v); }

static void thresholds_increase_and_encode_as_reference(void)
{
    biref_srgb8_encoder e;
    biref_srgb8_encoder_init(&e);
    int bad = 0;
    for (int k = 0; k < 255; k++) {
        double t = e.t[k];
        bad += mismatch(&e, t) + mismatch(&e, nextafter(t, 0.0)) + mismatch(&e, nextafter(t, 2.0));
        CHECK(k == 0 || e.t[k] > e.t[k - 1]);
    }
    printf("thresholds and their neighbours: %d mismatches\n", bad);
    CHECK(bad == 0);
}

static void random_values_encode_as_reference(void)
{
    biref_srgb8_encoder e;
    biref_srgb8_encoder_init(&e);
    test_rng rng = {SEED};
    int bad = 0;
    for (int i = 0; i < RANDOM_VALUES; i++) {
        double v = i % 2 ? test_uniform(&rng, -0.1, 1.2) : exp(test_uniform(&rng, log(1e-6), 0.0));
        bad += mismatch(&e, v);
    }
    printf("random values: %d mismatches\n", bad);
    CHECK(bad == 0);
}

static void special_values_encode_as_reference(void)
{
    biref_srgb8_encoder e;
    biref_srgb8_encoder_init(&e);
    const double special[] = {0.0, -0.0, 1.0, -1.0, INFINITY, -INFINITY, NAN, 1e-300, 1e300};
    int bad = 0;
    for (size_t i = 0; i < sizeof special / sizeof special[0]; i++) bad += mismatch(&e, special[i]);
    CHECK(bad == 0);
}

/* The whole image (parallel above 65536 pixels) equals the per-pixel conversion. */
static void image_conversion_equals_per_pixel(void)
{
    enum { N = 300 * 300 };
    test_rng rng = {SEED};
    test_skip(&rng, RANDOM_VALUES);
    float *xyz = malloc(sizeof(float) * 3 * N);
    unsigned char *a = malloc(3 * N), b[3];
    CHECK(xyz && a);
    if (!xyz || !a) goto done;
    for (int i = 0; i < 3 * N; i++) xyz[i] = (float)test_uniform(&rng, -0.05, 1.1);
    xyz[0] = NAN;
    biref_xyz_image_to_srgb8(xyz, N, a);
    int diff = 0;
    for (int i = 0; i < N; i++) {
        double c[3] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
        biref_xyz_to_srgb8(c, b);
        diff += a[3 * i] != b[0] || a[3 * i + 1] != b[1] || a[3 * i + 2] != b[2];
    }
    printf("image: %d pixel mismatches\n", diff);
    CHECK(diff == 0);
done:
    free(xyz);
    free(a);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"thresholds_increase_and_encode_as_reference", thresholds_increase_and_encode_as_reference},
        {"random_values_encode_as_reference", random_values_encode_as_reference},
        {"special_values_encode_as_reference", special_values_encode_as_reference},
        {"image_conversion_equals_per_pixel", image_conversion_equals_per_pixel},
    };
    return test_run_cases("test_srgb8_encoder", cases, TEST_COUNT(cases), argc, argv);
}
