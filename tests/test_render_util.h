/* Scenes and renders for the renderer's tests: a scene file at a test-sized resolution, and a
 * linear XYZ image of it under given options. */
#ifndef BIREF_TEST_RENDER_UTIL_H
#define BIREF_TEST_RENDER_UTIL_H

#include <stdio.h>
#include <stdlib.h>

#include "biref/biref.h"
#include "test_util.h"

/* The test program's one spectral context (as a process has one), created at the first call and
 * left to the process's exit. */
static inline const biref_spectral *test_sp(void)
{
    static biref_spectral *sp;
    if (!sp && biref_spectral_create(NULL, &sp, NULL, 0) != BIREF_OK) {
        fprintf(stderr, "cannot create the spectral context\n");
        exit(1);
    }
    return sp;
}

/* Loads path (relative to the source tree, ctest's working directory) at width x height; that
 * it loads is a check. */
static inline int test_load_scene(const char *path, biref_scene *sc, int width, int height)
{
    char msg[256];
    const biref_status s = biref_scene_load(path, sc, msg, sizeof msg);
    CHECK(s == BIREF_OK);
    if (s != BIREF_OK) {
        fprintf(stderr, "%s: %s\n", path, msg);
        return -1;
    }
    sc->camera.width = width;
    sc->camera.height = height;
    return 0;
}

/* The scene's XYZ image (3 floats a pixel, malloc'd; its pixel count in *pixels unless NULL), or
 * NULL with the reason on stderr. */
static inline float *test_render_xyz(const biref_scene *sc, const biref_render_options *opt, int *pixels)
{
    biref_renderer *r = NULL;
    char msg[256];
    if (biref_renderer_create(test_sp(), sc, opt, &r, msg, sizeof msg) != BIREF_OK) {
        fprintf(stderr, "renderer: %s\n", msg);
        return NULL;
    }
    const int n = biref_renderer_width(r) * biref_renderer_height(r);
    if (pixels) *pixels = n;
    float *xyz = malloc((size_t)n * 3 * sizeof *xyz);
    if (xyz && biref_render_image(r, xyz, NULL, NULL, NULL) != BIREF_OK) {
        fprintf(stderr, "render failed\n");
        free(xyz);
        xyz = NULL;
    }
    biref_renderer_destroy(r);
    return xyz;
}

#endif
