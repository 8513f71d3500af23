/* Typed, checked reads of the values of a scene file (JSON through cJSON), each error one line that
 * names the offending field by its JSON path ("slabs[2].normal: must be a non-zero vector").
 * Shared by the scene parser (scene.c) and the validation of assembled scenes (scene_validate.c);
 * not part of the public API. */
#ifndef BIREF_RENDER_SCENE_FIELDS_H
#define BIREF_RENDER_SCENE_FIELDS_H

#include <stddef.h>
#include <stdio.h>

#include <cjson/cJSON.h>

#include "biref/render.h"
#include "error.h"

/* A JSON path such as "slabs[2].normal" names every error. 96 bytes hold the deepest path. */
typedef struct {
    char s[96];
} field_path;

/* Appends parts into a path, truncating silently (paths are far shorter than the buffer). */
static inline field_path path_join(const char *a, const char *b, const char *c)
{
    field_path p;
    size_t n = 0;
    const char *parts[3] = {a, b, c};
    for (int k = 0; k < 3; k++)
        for (const char *q = parts[k]; *q && n + 1 < sizeof p.s; q++) p.s[n++] = *q;
    p.s[n] = '\0';
    return p;
}

static inline field_path path_key(const char *parent, const char *key)
{
    return path_join(parent, parent[0] ? "." : "", key);
}

static inline field_path path_index(const char *parent, int i)
{
    char idx[24];
    snprintf(idx, sizeof idx, "[%d]", i);
    return path_join(parent, idx, "");
}

/* Parser state: the error buffer travels with it so helpers stay short. */
typedef struct {
    char *msg;
    size_t msg_len;
} pctx;

#define FAIL(ctx, field, ...) biref_fail_field((ctx)->msg, (ctx)->msg_len, (field), __VA_ARGS__)

/* "a number", "an array", ...: what a JSON value is, for messages. */
const char *biref_field_type_name(const cJSON *v);
/* Unknown keys are errors: a typo such as "thicknes_mm" must not silently fall back to a
 * default (io/json_strict.h). */
biref_status biref_field_check_keys(pctx *c, const cJSON *obj, const char *where, const char *const *allowed);
/* *out = the member or NULL when absent (an error when required). */
biref_status biref_field_member(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                                const cJSON **out);
biref_status biref_field_as_object(pctx *c, const cJSON *v, const char *field);
biref_status biref_field_as_number(pctx *c, const cJSON *v, const char *field, double *out);
biref_status biref_field_as_vec(pctx *c, const cJSON *v, const char *field, int n, double *out);
/* A direction: three finite numbers, normalised; the zero vector has no direction. */
biref_status biref_field_as_direction(pctx *c, const cJSON *v, const char *field, double out[3]);
/* A radiance: a grey number or linear sRGB [r, g, b], each finite and >= 0. */
biref_status biref_field_as_colour(pctx *c, const cJSON *v, const char *field, double out[3]);
/* Reads obj[key] as a number; absent optional keys keep *out. */
biref_status biref_field_get_number(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                                    double *out);
biref_status biref_field_get_positive(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                                      double *out);
biref_status biref_field_get_vec(pctx *c, const cJSON *obj, const char *where, const char *key, int required, int n,
                                 double *out);
biref_status biref_field_get_direction(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                                       double out[3]);
biref_status biref_field_get_colour(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                                    double out[3]);
biref_status biref_field_get_image_side(pctx *c, const cJSON *obj, const char *where, const char *key, int *out);
/* Reads obj[key] as a string into *out (NULL when absent and optional). */
biref_status biref_field_get_string(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                                    const char **out);

/* A stack slab's stack (scene_validate.c): its layers in the scene's medium; BIREF_ERR_INVALID for a
 * plain slab (n_layers 0) or a layer count out of range. */
biref_status biref_scene_slab_stack(const biref_scene *sc, const biref_scene_slab *sl, biref_stack *out);

#endif
