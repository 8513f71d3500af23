/* Float and 16-bit image files for the photoelastic data paths: grey PFM (read/write), linear
 * 16-bit grey PNG (libpng, read/write) and CSV maps on the pixel grid. Writers go through
 * io/outfile.h: a failure leaves no partial file. */
#ifndef BIREF_CLI_PE_IMAGE_IO_H
#define BIREF_CLI_PE_IMAGE_IO_H

#include <stddef.h>

#include "biref/biref.h"

/* Grey ("Pf") or colour ("PF", channels = 3) PFM, top row first in memory. NaN allowed. */
biref_status pe_pfm_write(const char *path, int width, int height, int channels, const float *v, char *msg,
                          size_t msg_len);
/* Reads a PFM; colour files are reduced to their mean over the channels. *v is malloc'ed. */
biref_status pe_pfm_read_gray(const char *path, int *width, int *height, float **v, char *msg, size_t msg_len);
/* Linear 16-bit grey PNG: 0..1 -> 0..65535 (clamped; NaN -> 0). */
biref_status pe_png16_write_gray(const char *path, int width, int height, const float *v, char *msg, size_t msg_len);
/* Any PNG as linear grey 0..1 (libpng's simplified API: 8-bit sRGB files are linearised). */
biref_status pe_png_read_gray(const char *path, int *width, int *height, float **v, char *msg, size_t msg_len);
/* Any PNG as RGB 0..1 with its stored values (8-bit: encoded as written, e.g. sRGB; 16-bit: as
 * stored), 3 floats per pixel, top row first; *bits 8 or 16. */
biref_status pe_png_read_rgb(const char *path, int *width, int *height, float **v, int *bits, char *msg,
                             size_t msg_len);
/* Reads .pfm or .png by extension. */
biref_status pe_image_read_gray(const char *path, int *width, int *height, float **v, char *msg, size_t msg_len);

/* CSV map: header "x_mm,y_mm,<name>", one row per pixel (top row first), NaN written as "nan".
 * frame (m) maps the pixel centres; frame == NULL writes "col,row,<name>" with pixel indices. */
biref_status pe_csv_write_map(const char *path, int width, int height, const double frame[4], const char *name,
                              const float *v, char *msg, size_t msg_len);

/* 1 if path ends with ext (case-insensitive, ext with the dot). */
int pe_has_ext(const char *path, const char *ext);

#endif
