/* Image conversion to 8-bit sRGB by thresholds: the same bytes as biref_xyz_to_srgb8, for
 * random values, every threshold and its neighbouring doubles, and special values. */
#include <math.h>
#include <stdlib.h>

#include "biref/biref.h"
#include "color/srgb8_encoder.h"
#include "test_util.h"

static int reference_code(double v)
{
    double s = biref_srgb_encode(v);
    if (!(s > 0.0)) s = 0.0;
    if (s > 1.0) s = 1.0;
    return (int)lround(s * 255.0);
}

int main(void)
{
    biref_srgb8_encoder e;
    biref_srgb8_encoder_init(&e);
    int bad = 0;
    for (int k = 0; k < 255; k++) {
        double t = e.t[k];
        bad += biref_srgb8_encode(&e, t) != reference_code(t);
        bad += biref_srgb8_encode(&e, nextafter(t, 0.0)) != reference_code(nextafter(t, 0.0));
        bad += biref_srgb8_encode(&e, nextafter(t, 2.0)) != reference_code(nextafter(t, 2.0));
        CHECK(k == 0 || e.t[k] > e.t[k - 1]);
    }
    test_rng rng = {42};
    for (int i = 0; i < 200000; i++) {
        double v = i % 2 ? test_uniform(&rng, -0.1, 1.2) : exp(test_uniform(&rng, log(1e-6), 0.0));
        bad += biref_srgb8_encode(&e, v) != reference_code(v);
    }
    const double special[] = {0.0, -0.0, 1.0, -1.0, INFINITY, -INFINITY, NAN, 1e-300, 1e300};
    for (size_t i = 0; i < sizeof special / sizeof special[0]; i++)
        bad += biref_srgb8_encode(&e, special[i]) != reference_code(special[i]);
    CHECK(bad == 0);

    /* The whole image (parallel above 65536 pixels) equals the per-pixel conversion. */
    enum { N = 300 * 300 };
    float *xyz = malloc(sizeof(float) * 3 * N);
    unsigned char *a = malloc(3 * N), b[3];
    CHECK(xyz && a);
    for (int i = 0; i < 3 * N; i++) xyz[i] = (float)test_uniform(&rng, -0.05, 1.1);
    xyz[0] = NAN;
    biref_xyz_image_to_srgb8(xyz, N, a);
    int diff = 0;
    for (int i = 0; i < N; i++) {
        double c[3] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
        biref_xyz_to_srgb8(c, b);
        diff += a[3 * i] != b[0] || a[3 * i + 1] != b[1] || a[3 * i + 2] != b[2];
    }
    CHECK(diff == 0);
    printf("srgb8 encoder: %d value and %d pixel mismatches\n", bad, diff);
    free(xyz);
    free(a);
    return test_report("test_srgb8_encoder");
}
