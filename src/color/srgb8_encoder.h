/* 8-bit sRGB encoding of linear values by thresholds instead of pow: for image conversion. */
#ifndef BIREF_COLOR_SRGB8_ENCODER_H
#define BIREF_COLOR_SRGB8_ENCODER_H

/* t[k - 1] is the smallest double v with code(v) >= k, k = 1..255, where code(v) is what
 * biref_xyz_to_srgb8 writes for the linear value v (encode, clamp to [0, 1], round). */
typedef struct {
    double t[255];
} biref_srgb8_encoder;

void biref_srgb8_encoder_init(biref_srgb8_encoder *e);

/* code(v), by binary search over the thresholds: the same byte as biref_xyz_to_srgb8 for every
 * double (NaN and v <= 0 give 0). */
static inline unsigned char biref_srgb8_encode(const biref_srgb8_encoder *e, double v)
{
    int k = 0; /* number of thresholds <= v */
    for (int step = 128; step; step >>= 1)
        if (k + step <= 255 && v >= e->t[k + step - 1]) k += step;
    return (unsigned char)k;
}

#endif
