/* Image conversion and files: PNG through libpng (read by its simplified API, written with a
 * fast compression setting), PFM written directly. Files are written through io/outfile.h
 * (atomic replace), so a failed write never leaves a partial file behind. */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <png.h>
#include <zlib.h>

#include "error.h"
#include "biref/render.h"
#include "color/srgb8_encoder.h"
#include "io/outfile.h"

void biref_xyz_image_to_srgb8(const float *xyz, size_t n_pixels, unsigned char *rgb)
{
    /* The same bytes as biref_xyz_to_srgb8 per pixel, without a pow per channel, in parallel
     * (each pixel on its own: the result does not depend on the threads). */
    biref_srgb8_encoder enc;
    biref_srgb8_encoder_init(&enc);
    const long n = (long)n_pixels;
#pragma omp parallel for schedule(static) if (n > 65536)
    for (long i = 0; i < n; i++) {
        double c[3] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}, l[3];
        biref_xyz_to_linear_srgb(c, l);
        for (int k = 0; k < 3; k++) rgb[3 * i + k] = biref_srgb8_encode(&enc, l[k]);
    }
}

void biref_xyz_image_to_linear_srgb(const float *xyz, size_t n_pixels, float *rgb)
{
    for (size_t i = 0; i < n_pixels; i++) {
        double c[3] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}, l[3];
        biref_xyz_to_linear_srgb(c, l);
        for (int k = 0; k < 3; k++) rgb[3 * i + k] = (float)l[k];
    }
}

static biref_status io_fail(char *msg, size_t msg_len, const char *path, const char *what, const char *why)
{
    return biref_fail_status(BIREF_ERR_IO, msg, msg_len, "%s: %s: %s", path, what, why);
}

/* libpng reports errors by longjmp: the message is kept for the caller's one-line error. */
typedef struct {
    jmp_buf jmp;
    char why[160];
} png_failure;

static void png_on_error(png_structp png, png_const_charp text)
{
    png_failure *f = png_get_error_ptr(png);
    snprintf(f->why, sizeof f->why, "%s", text);
    longjmp(f->jmp, 1);
}

static void png_on_warning(png_structp png, png_const_charp text)
{
    (void)png;
    (void)text;
}

/* 8-bit RGB with an sRGB chunk (the chunks libpng's simplified API writes), compressed for
 * speed: rows filtered with "up" only and deflate's run-length strategy. On the rendered
 * examples at 1920 x 1080 that takes 4.8x fewer instructions than libpng's defaults (adaptive
 * filters, zlib level 6) for files 27 % larger (docs/PERFORMANCE.md, "Serial ends"). */
static int png_write_fast(FILE *out, int width, int height, const unsigned char *rgb, png_failure *f)
{
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, f, png_on_error, png_on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_write_struct(&png, NULL);
        snprintf(f->why, sizeof f->why, "out of memory");
        return 0;
    }
    if (setjmp(f->jmp)) {
        png_destroy_write_struct(&png, &info);
        return 0;
    }
    png_init_io(png, out);
    png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
    png_set_compression_strategy(png, Z_RLE);
    png_write_info(png, info);
    for (int y = 0; y < height; y++) png_write_row(png, rgb + (size_t)y * (size_t)width * 3);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return 1;
}

biref_status biref_png_write_rgb8(const char *path, int width, int height, const unsigned char *rgb, char *msg,
                                  size_t msg_len)
{
    if (!path || !rgb || width < 1 || height < 1) return io_fail(msg, msg_len, path ? path : "(null)", "cannot write", "bad image");
    biref_outfile *o = biref_outfile_open(path, msg, msg_len);
    if (!o) return BIREF_ERR_IO;
    png_failure f = {.why = ""};
    int ok = png_write_fast(biref_outfile_stream(o), width, height, rgb, &f);
    biref_status s = biref_outfile_close(o, ok, msg, msg_len);
    if (!ok) io_fail(msg, msg_len, path, "cannot write", f.why);
    return s;
}

biref_status biref_png_read_rgb8(const char *path, int *width, int *height, unsigned char **rgb, char *msg,
                                 size_t msg_len)
{
    *rgb = NULL;
    FILE *f = fopen(path, "rb");
    if (!f) return io_fail(msg, msg_len, path, "cannot read", strerror(errno));
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_stdio(&img, f)) {
        char why[160];
        snprintf(why, sizeof why, "not a readable PNG (%s)", img.message);
        png_image_free(&img);
        fclose(f);
        if (msg && msg_len) snprintf(msg, msg_len, "%s: %s", path, why);
        return BIREF_ERR_INVALID;
    }
    /* The size a header declares costs nothing to forge (a few hundred bytes can declare
     * 16384 x 16384): refuse before allocating or decoding anything, with the same limits as
     * the images biref renders. */
    if (img.width > BIREF_SCENE_MAX_SIDE || img.height > BIREF_SCENE_MAX_SIDE ||
        (uint64_t)img.width * img.height > (uint64_t)BIREF_SCENE_MAX_PIXELS) {
        png_image_free(&img);
        fclose(f);
        if (msg && msg_len)
            snprintf(msg, msg_len, "%s: image too large (%ux%u; at most %d pixels a side and %ld pixels)", path,
                     img.width, img.height, BIREF_SCENE_MAX_SIDE, (long)BIREF_SCENE_MAX_PIXELS);
        return BIREF_ERR_INVALID;
    }
    img.format = PNG_FORMAT_RGB;
    size_t size = PNG_IMAGE_SIZE(img);
    /* calloc: an alpha channel is composited onto the buffer's contents, i.e. onto black. */
    unsigned char *buf = calloc(size, 1);
    if (!buf) {
        png_image_free(&img);
        fclose(f);
        return io_fail(msg, msg_len, path, "cannot read", "out of memory");
    }
    if (!png_image_finish_read(&img, NULL, buf, 0, NULL)) {
        char why[160];
        snprintf(why, sizeof why, "corrupt PNG (%s)", img.message);
        png_image_free(&img);
        fclose(f);
        free(buf);
        if (msg && msg_len) snprintf(msg, msg_len, "%s: %s", path, why);
        return BIREF_ERR_INVALID;
    }
    *width = (int)img.width;
    *height = (int)img.height;
    png_image_free(&img);
    fclose(f);
    *rgb = buf;
    return BIREF_OK;
}

biref_status biref_pfm_write(const char *path, int width, int height, const float *rgb, char *msg, size_t msg_len)
{
    if (!path || !rgb || width < 1 || height < 1) return io_fail(msg, msg_len, path ? path : "(null)", "cannot write", "bad image");
    biref_outfile *o = biref_outfile_open(path, msg, msg_len);
    if (!o) return BIREF_ERR_IO;
    FILE *f = biref_outfile_stream(o);
    /* The scale's sign gives the byte order of the floats: negative = little-endian. */
    const uint16_t probe = 1;
    int little = *(const unsigned char *)&probe == 1;
    int ok = fprintf(f, "PF\n%d %d\n%s\n", width, height, little ? "-1.0" : "1.0") > 0;
    /* PFM stores the bottom row first. */
    for (int y = height - 1; ok && y >= 0; y--)
        ok = fwrite(rgb + (size_t)y * width * 3, sizeof(float), (size_t)width * 3, f) == (size_t)width * 3;
    char why[160];
    snprintf(why, sizeof why, "%s", ok ? "" : strerror(errno));
    biref_status s = biref_outfile_close(o, ok, msg, msg_len);
    if (!ok) io_fail(msg, msg_len, path, "cannot write", why);
    return s;
}
