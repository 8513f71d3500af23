/* Typed, checked reads of scene-file values (scene_fields.h): every reader names the field by its
 * JSON path in its one-line error. */
#include "render/scene_fields.h"

#include <math.h>

#include "io/json_strict.h"
#include "shading/vec3.h"

const char *biref_field_type_name(const cJSON *v)
{
    if (cJSON_IsNumber(v)) return "a number";
    if (cJSON_IsString(v)) return "a string";
    if (cJSON_IsArray(v)) return "an array";
    if (cJSON_IsObject(v)) return "an object";
    if (cJSON_IsBool(v)) return "a boolean";
    if (cJSON_IsNull(v)) return "null";
    return "an invalid value";
}

/* Unknown keys are errors: a typo such as "thicknes_mm" must not silently fall back to a
 * default (io/json_strict.h). */
biref_status biref_field_check_keys(pctx *c, const cJSON *obj, const char *where, const char *const *allowed)
{
    int twice;
    const char *k = biref_json_bad_key(obj, allowed, &twice);
    if (!k) return BIREF_OK;
    field_path p = path_key(where, k);
    return FAIL(c, p.s, twice ? "given twice" : "unknown field");
}

/* *out = the member or NULL when absent (an error when required). */
biref_status biref_field_member(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                                const cJSON **out)
{
    *out = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!*out && required) {
        field_path p = path_key(where, key);
        return FAIL(c, p.s, "missing");
    }
    return BIREF_OK;
}

biref_status biref_field_as_object(pctx *c, const cJSON *v, const char *field)
{
    if (!cJSON_IsObject(v)) return FAIL(c, field, "expected an object, got %s", biref_field_type_name(v));
    return BIREF_OK;
}

biref_status biref_field_as_number(pctx *c, const cJSON *v, const char *field, double *out)
{
    if (!cJSON_IsNumber(v)) return FAIL(c, field, "expected a number, got %s", biref_field_type_name(v));
    /* cJSON turns 1e999 into inf; JSON itself has no NaN or inf. */
    if (!isfinite(v->valuedouble)) return FAIL(c, field, "must be a finite number");
    *out = v->valuedouble;
    return BIREF_OK;
}

biref_status biref_field_as_vec(pctx *c, const cJSON *v, const char *field, int n, double *out)
{
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != n)
        return FAIL(c, field, "expected an array of %d numbers", n);
    int i = 0;
    for (const cJSON *e = v->child; e; e = e->next, i++) {
        field_path p = path_index(field, i);
        biref_status s = biref_field_as_number(c, e, p.s, &out[i]);
        if (s) return s;
    }
    return BIREF_OK;
}

/* A direction: three finite numbers, normalised; the zero vector has no direction. */
biref_status biref_field_as_direction(pctx *c, const cJSON *v, const char *field, double out[3])
{
    biref_status s = biref_field_as_vec(c, v, field, 3, out);
    if (s) return s;
    double n = v3_len(out);
    if (!(n > 1e-12) || !isfinite(n)) return FAIL(c, field, "must be a non-zero vector");
    v3_scale(out, 1.0 / n, out);
    return BIREF_OK;
}

/* A radiance: a grey number or linear sRGB [r, g, b], each finite and >= 0. */
biref_status biref_field_as_colour(pctx *c, const cJSON *v, const char *field, double out[3])
{
    if (cJSON_IsNumber(v)) {
        biref_status s = biref_field_as_number(c, v, field, &out[0]);
        if (s) return s;
        out[1] = out[2] = out[0];
    } else if (cJSON_IsArray(v)) {
        biref_status s = biref_field_as_vec(c, v, field, 3, out);
        if (s) return s;
    } else {
        return FAIL(c, field, "expected a number or an array of 3 numbers, got %s", biref_field_type_name(v));
    }
    for (int i = 0; i < 3; i++)
        if (out[i] < 0.0) return FAIL(c, field, "must not be negative");
    return BIREF_OK;
}

static biref_status positive(pctx *c, const char *field, double v)
{
    if (!(v > 0.0)) return FAIL(c, field, "must be positive");
    return BIREF_OK;
}

/* Reads obj[key] as a number; absent optional keys keep *out. */
biref_status biref_field_get_number(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                                    double *out)
{
    const cJSON *v;
    biref_status s = biref_field_member(c, obj, where, key, required, &v);
    if (s || !v) return s;
    field_path p = path_key(where, key);
    return biref_field_as_number(c, v, p.s, out);
}

biref_status biref_field_get_positive(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                                      double *out)
{
    const cJSON *v;
    biref_status s = biref_field_member(c, obj, where, key, required, &v);
    if (s || !v) return s;
    field_path p = path_key(where, key);
    s = biref_field_as_number(c, v, p.s, out);
    return s ? s : positive(c, p.s, *out);
}

biref_status biref_field_get_vec(pctx *c, const cJSON *obj, const char *where, const char *key, int required, int n,
                                 double *out)
{
    const cJSON *v;
    biref_status s = biref_field_member(c, obj, where, key, required, &v);
    if (s || !v) return s;
    field_path p = path_key(where, key);
    return biref_field_as_vec(c, v, p.s, n, out);
}

biref_status biref_field_get_direction(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                                       double out[3])
{
    const cJSON *v;
    biref_status s = biref_field_member(c, obj, where, key, required, &v);
    if (s || !v) return s;
    field_path p = path_key(where, key);
    return biref_field_as_direction(c, v, p.s, out);
}

biref_status biref_field_get_colour(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                                    double out[3])
{
    const cJSON *v;
    biref_status s = biref_field_member(c, obj, where, key, required, &v);
    if (s || !v) return s;
    field_path p = path_key(where, key);
    return biref_field_as_colour(c, v, p.s, out);
}

biref_status biref_field_get_image_side(pctx *c, const cJSON *obj, const char *where, const char *key, int *out)
{
    double v = *out;
    biref_status s = biref_field_get_number(c, obj, where, key, 0, &v);
    if (s) return s;
    field_path p = path_key(where, key);
    if (v != floor(v)) return FAIL(c, p.s, "must be a whole number of pixels");
    if (v < 1 || v > BIREF_SCENE_MAX_SIDE) return FAIL(c, p.s, "must be between 1 and %d", BIREF_SCENE_MAX_SIDE);
    *out = (int)v;
    return BIREF_OK;
}

/* Reads obj[key] as a string into *out (NULL when absent and optional). */
biref_status biref_field_get_string(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                                    const char **out)
{
    const cJSON *v;
    *out = NULL;
    biref_status s = biref_field_member(c, obj, where, key, required, &v);
    if (s || !v) return s;
    field_path p = path_key(where, key);
    if (!cJSON_IsString(v)) return FAIL(c, p.s, "expected a string, got %s", biref_field_type_name(v));
    *out = v->valuestring;
    return BIREF_OK;
}
