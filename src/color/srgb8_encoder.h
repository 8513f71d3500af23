/* 8-bit sRGB encoding of linear values by thresholds instead of pow: for image conversion. */
#ifndef BIREF_COLOR_SRGB8_ENCODER_H
#define BIREF_COLOR_SRGB8_ENCODER_H

/* Bins of [0, 1) with the code of each bin's lower end: the search starts there. */
#define BIREF_SRGB8_BINS 4096

/* t[k - 1] is the smallest double v with code(v) >= k, k = 1..255, where code(v) is what
 * biref_xyz_to_srgb8 writes for the linear value v (encode, clamp to [0, 1], round);
 * start[b] = code(b / BIREF_SRGB8_BINS). */
typedef struct {
    double t[255];
    unsigned char start[BIREF_SRGB8_BINS];
} biref_srgb8_encoder;

void biref_srgb8_encoder_init(biref_srgb8_encoder *e);

/* code(v) = the number of thresholds <= v: the same byte as biref_xyz_to_srgb8 for every double
 * (NaN and v <= 0 give 0). From the code of v's bin (b / BINS <= v exactly: the scaling by a
 * power of two is exact and the conversion truncates) the thresholds are walked upwards; a bin
 * spans at most two codes (the curve's steepest slope, 12.92 x 255 codes per unit, is below
 * BIREF_SRGB8_BINS), so this is one or two comparisons instead of eight. */
static inline unsigned char biref_srgb8_encode(const biref_srgb8_encoder *e, double v)
{
    if (!(v > 0.0)) return 0;
    if (v >= 1.0) return 255;
    int k = e->start[(int)(v * BIREF_SRGB8_BINS)];
    while (k < 255 && v >= e->t[k]) k++;
    return (unsigned char)k;
}

#endif
