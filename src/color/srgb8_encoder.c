/* Thresholds of the 8-bit sRGB code (srgb8_encoder.h), found by bisection on the bit patterns of
 * positive doubles (ordered like the values): exact for a non-decreasing code, 255 x 62 calls of
 * the encoder per table, far fewer than one pow per channel of a large image. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "biref/color.h"
#include "color/srgb8_encoder.h"

static int code_of(double v)
{
    double s = biref_srgb_encode(v);
    if (!(s > 0.0)) s = 0.0;
    if (s > 1.0) s = 1.0;
    return (int)lround(s * 255.0);
}

static uint64_t bits_of(double v)
{
    uint64_t b;
    memcpy(&b, &v, sizeof b);
    return b;
}

static double double_of(uint64_t b)
{
    double v;
    memcpy(&v, &b, sizeof v);
    return v;
}

void biref_srgb8_encoder_init(biref_srgb8_encoder *e)
{
    uint64_t lo = bits_of(0.0); /* code 0 */
    for (int k = 1; k <= 255; k++) {
        uint64_t hi = bits_of(1.0); /* code 255 */
        while (hi - lo > 1) {
            uint64_t mid = lo + (hi - lo) / 2;
            if (code_of(double_of(mid)) >= k)
                hi = mid;
            else
                lo = mid;
        }
        e->t[k - 1] = double_of(hi);
    }
    /* The codes of the bins' lower ends, by the thresholds themselves (binary search). */
    for (int b = 0; b < BIREF_SRGB8_BINS; b++) {
        const double v = (double)b / BIREF_SRGB8_BINS;
        int k = 0;
        for (int step = 128; step; step >>= 1)
            if (k + step <= 255 && v >= e->t[k + step - 1]) k += step;
        e->start[b] = (unsigned char)k;
    }
}
