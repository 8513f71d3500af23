/* Float and 16-bit image files for the photoelastic data paths (see pe_image_io.h). PFM is a
 * text header and raw floats, no codec: nothing to reuse from a library there; PNG goes through
 * libpng. */
#include "pe_image_io.h"

#include "outfile.h"

#include <errno.h>
#include <math.h>
#include <png.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static biref_status fail(char *msg, size_t n, const char *path, const char *what, const char *why)
{
    if (msg && n) snprintf(msg, n, "%s: %s: %s", path, what, why);
    return BIREF_ERR_IO;
}

int pe_has_ext(const char *path, const char *ext)
{
    size_t n = strlen(path), m = strlen(ext);
    return n > m && !strcasecmp(path + n - m, ext);
}

/* Output goes through the library's careful writer (io/outfile.h): written aside, renamed into
 * place once complete. */
typedef struct {
    FILE *f;
    biref_outfile *o;
} temp_file;

static int temp_open(temp_file *t, const char *path, char *msg, size_t n)
{
    t->o = biref_outfile_open(path, msg, n);
    if (!t->o) return -1;
    t->f = biref_outfile_stream(t->o);
    return 0;
}

static biref_status temp_commit(temp_file *t, const char *path, int ok, char *msg, size_t n)
{
    if (!ok && msg && n) snprintf(msg, n, "%s: cannot write: write failed", path);
    biref_status st = biref_outfile_close(t->o, ok, ok ? msg : NULL, ok ? n : 0);
    return ok ? st : BIREF_ERR_IO;
}

biref_status pe_pfm_write(const char *path, int width, int height, int channels, const float *v, char *msg,
                          size_t msg_len)
{
    if (width < 1 || height < 1 || (channels != 1 && channels != 3)) return fail(msg, msg_len, path, "cannot write", "bad image");
    temp_file t;
    if (temp_open(&t, path, msg, msg_len)) return BIREF_ERR_IO;
    const uint16_t probe = 1;
    const int little = *(const unsigned char *)&probe == 1;
    int ok = fprintf(t.f, "%s\n%d %d\n%s\n", channels == 1 ? "Pf" : "PF", width, height, little ? "-1.0" : "1.0") > 0;
    const size_t row = (size_t)width * channels;
    for (int y = height - 1; ok && y >= 0; y--) ok = fwrite(v + (size_t)y * row, sizeof(float), row, t.f) == row;
    return temp_commit(&t, path, ok, msg, msg_len);
}

biref_status pe_pfm_read_gray(const char *path, int *width, int *height, float **out, char *msg, size_t msg_len)
{
    *out = NULL;
    FILE *f = fopen(path, "rb");
    if (!f) return fail(msg, msg_len, path, "cannot read", strerror(errno));
    char magic[3] = {0};
    int w = 0, h = 0;
    double scale = 0;
    int ok = fscanf(f, "%2s %d %d %lf", magic, &w, &h, &scale) == 4 && fgetc(f) != EOF;
    int ch = !strcmp(magic, "Pf") ? 1 : !strcmp(magic, "PF") ? 3 : 0;
    if (!ok || !ch || w < 1 || h < 1 || w > 65536 || h > 65536 || scale == 0 || !isfinite(scale)) {
        fclose(f);
        return fail(msg, msg_len, path, "cannot read", "not a PFM file (expected Pf or PF, size and scale)");
    }
    size_t n = (size_t)w * h, row = (size_t)w * ch;
    float *buf = malloc(n * ch * sizeof *buf), *g = malloc(n * sizeof *g);
    if (!buf || !g) {
        free(buf);
        free(g);
        fclose(f);
        return fail(msg, msg_len, path, "cannot read", "out of memory");
    }
    ok = fread(buf, sizeof(float), n * ch, f) == n * ch;
    fclose(f);
    if (!ok) {
        free(buf);
        free(g);
        return fail(msg, msg_len, path, "cannot read", "the file ends before its last pixel");
    }
    const uint16_t probe = 1;
    const int little = *(const unsigned char *)&probe == 1;
    if ((scale < 0) != little)
        for (size_t i = 0; i < n * ch; i++) {
            unsigned char *b = (unsigned char *)&buf[i], c;
            c = b[0], b[0] = b[3], b[3] = c;
            c = b[1], b[1] = b[2], b[2] = c;
        }
    /* Bottom row first in the file. */
    for (int y = 0; y < h; y++) {
        const float *src = buf + (size_t)(h - 1 - y) * row;
        for (int x = 0; x < w; x++) {
            double s = 0;
            for (int c = 0; c < ch; c++) s += src[(size_t)x * ch + c];
            g[(size_t)y * w + x] = (float)(s / ch);
        }
    }
    free(buf);
    *width = w;
    *height = h;
    *out = g;
    return BIREF_OK;
}

biref_status pe_png16_write_gray(const char *path, int width, int height, const float *v, char *msg, size_t msg_len)
{
    size_t n = (size_t)width * height;
    uint16_t *px = malloc(n * sizeof *px);
    if (!px) return fail(msg, msg_len, path, "cannot write", "out of memory");
    for (size_t i = 0; i < n; i++) {
        double x = v[i];
        px[i] = (uint16_t)(x > 0 ? (x < 1 ? lround(x * 65535.0) : 65535) : 0);
    }
    temp_file t;
    if (temp_open(&t, path, msg, msg_len)) {
        free(px);
        return BIREF_ERR_IO;
    }
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = (png_uint_32)width;
    img.height = (png_uint_32)height;
    img.format = PNG_FORMAT_LINEAR_Y; /* 16-bit, gamma 1 */
    int ok = png_image_write_to_stdio(&img, t.f, 0, px, 0, NULL);
    png_image_free(&img);
    free(px);
    return temp_commit(&t, path, ok, msg, msg_len);
}

/* Opens a PNG with libpng's simplified API; BIREF_ERR_IO with the reason. */
static biref_status begin_read(png_image *img, const char *path, char *msg, size_t msg_len)
{
    memset(img, 0, sizeof *img);
    img->version = PNG_IMAGE_VERSION;
    if (png_image_begin_read_from_file(img, path)) return BIREF_OK;
    char why[128];
    snprintf(why, sizeof why, "%s", img->message[0] ? img->message : strerror(errno));
    png_image_free(img);
    return fail(msg, msg_len, path, "cannot read", why);
}

biref_status pe_png_read_gray(const char *path, int *width, int *height, float **out, char *msg, size_t msg_len)
{
    *out = NULL;
    png_image img;
    if (begin_read(&img, path, msg, msg_len) != BIREF_OK) return BIREF_ERR_IO;
    img.format = PNG_FORMAT_LINEAR_Y;
    size_t n = (size_t)img.width * img.height;
    uint16_t *px = malloc(n * sizeof *px);
    float *g = malloc(n * sizeof *g);
    if (!px || !g || !png_image_finish_read(&img, NULL, px, 0, NULL)) {
        free(px);
        free(g);
        png_image_free(&img);
        return fail(msg, msg_len, path, "cannot read", px && g ? "corrupt PNG" : "out of memory");
    }
    for (size_t i = 0; i < n; i++) g[i] = (float)(px[i] / 65535.0);
    free(px);
    *width = (int)img.width;
    *height = (int)img.height;
    *out = g;
    return BIREF_OK;
}

biref_status pe_png_read_rgb(const char *path, int *width, int *height, float **out, int *bits, char *msg,
                             size_t msg_len)
{
    *out = NULL;
    png_image img;
    if (begin_read(&img, path, msg, msg_len) != BIREF_OK) return BIREF_ERR_IO;
    /* The stored values, unconverted: 8-bit files as they are (encoded), 16-bit files are linear to
     * libpng and come back as stored. */
    const int wide = (img.format & PNG_FORMAT_FLAG_LINEAR) != 0;
    img.format = wide ? PNG_FORMAT_LINEAR_RGB : PNG_FORMAT_RGB;
    const size_t n = (size_t)img.width * img.height * 3;
    void *px = malloc(n * (wide ? 2 : 1));
    float *v = malloc(n * sizeof *v);
    if (!px || !v || !png_image_finish_read(&img, NULL, px, 0, NULL)) {
        free(px);
        free(v);
        png_image_free(&img);
        return fail(msg, msg_len, path, "cannot read", px && v ? "corrupt PNG" : "out of memory");
    }
    for (size_t i = 0; i < n; i++) v[i] = wide ? (float)(((uint16_t *)px)[i] / 65535.0) : (float)(((unsigned char *)px)[i] / 255.0);
    free(px);
    *width = (int)img.width;
    *height = (int)img.height;
    *bits = wide ? 16 : 8;
    *out = v;
    return BIREF_OK;
}

biref_status pe_image_read_gray(const char *path, int *width, int *height, float **v, char *msg, size_t msg_len)
{
    if (pe_has_ext(path, ".pfm")) return pe_pfm_read_gray(path, width, height, v, msg, msg_len);
    if (pe_has_ext(path, ".png")) return pe_png_read_gray(path, width, height, v, msg, msg_len);
    return fail(msg, msg_len, path, "cannot read", "expected a .pfm or .png file");
}

biref_status pe_csv_write_map(const char *path, int width, int height, const double frame[4], const char *name,
                              const float *v, char *msg, size_t msg_len)
{
    temp_file t;
    if (temp_open(&t, path, msg, msg_len)) return BIREF_ERR_IO;
    int ok = fprintf(t.f, frame ? "x_mm,y_mm,%s\n" : "col,row,%s\n", name) > 0;
    for (int j = 0; ok && j < height; j++)
        for (int i = 0; ok && i < width; i++) {
            const float x = v[(size_t)j * width + i];
            char val[32];
            if (isnan(x))
                strcpy(val, "nan");
            else
                snprintf(val, sizeof val, "%.7g", x);
            if (frame) {
                double px = frame[0] + (i + 0.5) * (frame[1] - frame[0]) / width;
                double py = frame[3] - (j + 0.5) * (frame[3] - frame[2]) / height;
                ok = fprintf(t.f, "%.6g,%.6g,%s\n", px * 1e3, py * 1e3, val) > 0;
            } else {
                ok = fprintf(t.f, "%d,%d,%s\n", i, j, val) > 0;
            }
        }
    return temp_commit(&t, path, ok, msg, msg_len);
}
