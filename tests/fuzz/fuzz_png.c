/* libFuzzer target: the PNG reader (biref_png_read_rgb8) on arbitrary bytes. The reader takes a
 * path, so the input goes into an anonymous in-memory file opened through /proc/self/fd. */
#define _GNU_SOURCE /* memfd_create */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <unistd.h>

#include "biref/render.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    int fd = memfd_create("fuzz_png", MFD_CLOEXEC);
    if (fd < 0) return 0;
    if (size && write(fd, data, size) != (ssize_t)size) {
        close(fd);
        return 0;
    }
    char path[64];
    snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
    int w, h;
    unsigned char *rgb = NULL;
    char msg[320];
    if (biref_png_read_rgb8(path, &w, &h, &rgb, msg, sizeof msg) == BIREF_OK) {
        if (w < 1 || h < 1 || (long)w * h > BIREF_SCENE_MAX_PIXELS || !rgb) __builtin_trap();
        /* Touch the first and the last pixel: the buffer holds the whole image. */
        volatile unsigned char sink = rgb[0] ^ rgb[(size_t)w * h * 3 - 1];
        (void)sink;
    }
    free(rgb);
    close(fd);
    return 0;
}
