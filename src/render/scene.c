/* Scene files: JSON (cJSON) -> biref_scene, with one-line errors that name the offending field.
 * Schema: docs/SCENES.md. Every value is checked where it is read, so the message can use the
 * JSON path; cross-field checks (camera up vs view, camera inside a slab, ...) run afterwards
 * in biref_scene_validate, whose field names are the JSON ones wherever the two coincide. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "biref/render.h"
#include "error.h"
#include "io/json_strict.h"
#include "render/scene_light.h"
#include "shading/vec3.h"

/* A JSON path such as "slabs[2].normal" names every error. 96 bytes hold the deepest path. */
typedef struct {
    char s[96];
} field_path;

/* Appends parts into a path, truncating silently (paths are far shorter than the buffer). */
static field_path path_join(const char *a, const char *b, const char *c)
{
    field_path p;
    size_t n = 0;
    const char *parts[3] = {a, b, c};
    for (int k = 0; k < 3; k++)
        for (const char *q = parts[k]; *q && n + 1 < sizeof p.s; q++) p.s[n++] = *q;
    p.s[n] = '\0';
    return p;
}

static field_path path_key(const char *parent, const char *key)
{
    return path_join(parent, parent[0] ? "." : "", key);
}

static field_path path_index(const char *parent, int i)
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

static const char *type_name(const cJSON *v)
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
static biref_status check_keys(pctx *c, const cJSON *obj, const char *where, const char *const *allowed)
{
    int twice;
    const char *k = biref_json_bad_key(obj, allowed, &twice);
    if (!k) return BIREF_OK;
    field_path p = path_key(where, k);
    return FAIL(c, p.s, twice ? "given twice" : "unknown field");
}

/* *out = the member or NULL when absent (an error when required). */
static biref_status member(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                           const cJSON **out)
{
    *out = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!*out && required) {
        field_path p = path_key(where, key);
        return FAIL(c, p.s, "missing");
    }
    return BIREF_OK;
}

static biref_status as_object(pctx *c, const cJSON *v, const char *field)
{
    if (!cJSON_IsObject(v)) return FAIL(c, field, "expected an object, got %s", type_name(v));
    return BIREF_OK;
}

static biref_status as_number(pctx *c, const cJSON *v, const char *field, double *out)
{
    if (!cJSON_IsNumber(v)) return FAIL(c, field, "expected a number, got %s", type_name(v));
    /* cJSON turns 1e999 into inf; JSON itself has no NaN or inf. */
    if (!isfinite(v->valuedouble)) return FAIL(c, field, "must be a finite number");
    *out = v->valuedouble;
    return BIREF_OK;
}

static biref_status as_vec(pctx *c, const cJSON *v, const char *field, int n, double *out)
{
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != n)
        return FAIL(c, field, "expected an array of %d numbers", n);
    int i = 0;
    for (const cJSON *e = v->child; e; e = e->next, i++) {
        field_path p = path_index(field, i);
        biref_status s = as_number(c, e, p.s, &out[i]);
        if (s) return s;
    }
    return BIREF_OK;
}

/* A direction: three finite numbers, normalised; the zero vector has no direction. */
static biref_status as_direction(pctx *c, const cJSON *v, const char *field, double out[3])
{
    biref_status s = as_vec(c, v, field, 3, out);
    if (s) return s;
    double n = v3_len(out);
    if (!(n > 1e-12) || !isfinite(n)) return FAIL(c, field, "must be a non-zero vector");
    v3_scale(out, 1.0 / n, out);
    return BIREF_OK;
}

/* A radiance: a grey number or linear sRGB [r, g, b], each finite and >= 0. */
static biref_status as_colour(pctx *c, const cJSON *v, const char *field, double out[3])
{
    if (cJSON_IsNumber(v)) {
        biref_status s = as_number(c, v, field, &out[0]);
        if (s) return s;
        out[1] = out[2] = out[0];
    } else if (cJSON_IsArray(v)) {
        biref_status s = as_vec(c, v, field, 3, out);
        if (s) return s;
    } else {
        return FAIL(c, field, "expected a number or an array of 3 numbers, got %s", type_name(v));
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
static biref_status get_number(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                               double *out)
{
    const cJSON *v;
    biref_status s = member(c, obj, where, key, required, &v);
    if (s || !v) return s;
    field_path p = path_key(where, key);
    return as_number(c, v, p.s, out);
}

static biref_status get_positive(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                                 double *out)
{
    const cJSON *v;
    biref_status s = member(c, obj, where, key, required, &v);
    if (s || !v) return s;
    field_path p = path_key(where, key);
    s = as_number(c, v, p.s, out);
    return s ? s : positive(c, p.s, *out);
}

static biref_status get_vec(pctx *c, const cJSON *obj, const char *where, const char *key, int required, int n,
                            double *out)
{
    const cJSON *v;
    biref_status s = member(c, obj, where, key, required, &v);
    if (s || !v) return s;
    field_path p = path_key(where, key);
    return as_vec(c, v, p.s, n, out);
}

static biref_status get_direction(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                                  double out[3])
{
    const cJSON *v;
    biref_status s = member(c, obj, where, key, required, &v);
    if (s || !v) return s;
    field_path p = path_key(where, key);
    return as_direction(c, v, p.s, out);
}

static biref_status get_colour(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                               double out[3])
{
    const cJSON *v;
    biref_status s = member(c, obj, where, key, required, &v);
    if (s || !v) return s;
    field_path p = path_key(where, key);
    return as_colour(c, v, p.s, out);
}

static biref_status get_image_side(pctx *c, const cJSON *obj, const char *where, const char *key, int *out)
{
    double v = *out;
    biref_status s = get_number(c, obj, where, key, 0, &v);
    if (s) return s;
    field_path p = path_key(where, key);
    if (v != floor(v)) return FAIL(c, p.s, "must be a whole number of pixels");
    if (v < 1 || v > BIREF_SCENE_MAX_SIDE) return FAIL(c, p.s, "must be between 1 and %d", BIREF_SCENE_MAX_SIDE);
    *out = (int)v;
    return BIREF_OK;
}

/* Reads obj[key] as a string into *out (NULL when absent and optional). */
static biref_status get_string(pctx *c, const cJSON *obj, const char *where, const char *key, int required,
                               const char **out)
{
    const cJSON *v;
    *out = NULL;
    biref_status s = member(c, obj, where, key, required, &v);
    if (s || !v) return s;
    field_path p = path_key(where, key);
    if (!cJSON_IsString(v)) return FAIL(c, p.s, "expected a string, got %s", type_name(v));
    *out = v->valuestring;
    return BIREF_OK;
}

/* ------------------------------------------------------------------------ */

static biref_status parse_camera(pctx *c, const cJSON *cam, biref_camera *out)
{
    static const char *const keys[] = {"position", "look_at", "up", "fov_deg", "width", "height", "exposure", NULL};
    const char *w = "camera";
    biref_status s = as_object(c, cam, w);
    if (!s) s = check_keys(c, cam, w, keys);
    if (!s) s = get_vec(c, cam, w, "position", 1, 3, out->position);
    if (!s) s = get_vec(c, cam, w, "look_at", 1, 3, out->look_at);
    if (!s) s = get_direction(c, cam, w, "up", 0, out->up);
    if (!s) s = get_number(c, cam, w, "fov_deg", 0, &out->fov_deg);
    if (!s) s = get_image_side(c, cam, w, "width", &out->width);
    if (!s) s = get_image_side(c, cam, w, "height", &out->height);
    if (!s) s = get_positive(c, cam, w, "exposure", 0, &out->exposure);
    return s;
}

/* A unit vector orthogonal to n (for optional tangents): the axis least aligned with n,
 * orthogonalised. */
static void any_perpendicular(const double n[3], double out[3])
{
    double e[3] = {0, 0, 0};
    int k = fabs(n[0]) <= fabs(n[1]) ? (fabs(n[0]) <= fabs(n[2]) ? 0 : 2) : (fabs(n[1]) <= fabs(n[2]) ? 1 : 2);
    e[k] = 1.0;
    v3_orthonormalize(e, n, out);
}

/* Tangent given: orthogonalise against the normal (Gram–Schmidt); parallel is an error. */
static biref_status tangent_frame(pctx *c, const cJSON *obj, const char *where, const double n[3], double t[3])
{
    const cJSON *v;
    biref_status s = member(c, obj, where, "tangent", 0, &v);
    if (s) return s;
    if (!v) {
        any_perpendicular(n, t);
        return BIREF_OK;
    }
    field_path p = path_key(where, "tangent");
    double raw[3];
    s = as_direction(c, v, p.s, raw);
    if (s) return s;
    if (v3_orthonormalize(raw, n, t)) return FAIL(c, p.s, "must not be parallel to the normal");
    return BIREF_OK;
}

static biref_status parse_slab(pctx *c, const cJSON *sl, const char *w, biref_scene_slab *out)
{
    static const char *const keys[] = {"center", "size",  "thickness_mm", "thickness_um", "normal",
                                       "tangent", "axis", "eta_o",        "eta_e",        NULL};
    biref_status s = as_object(c, sl, w);
    if (!s) s = check_keys(c, sl, w, keys);
    if (!s) s = get_vec(c, sl, w, "center", 1, 3, out->center);
    if (!s) s = get_vec(c, sl, w, "size", 1, 2, out->size);
    if (s) return s;
    for (int i = 0; i < 2; i++) {
        field_path p = path_key(w, "size");
        field_path q = path_index(p.s, i);
        if (!(out->size[i] > 0.0)) return FAIL(c, q.s, "must be positive");
    }
    const cJSON *tmm = cJSON_GetObjectItemCaseSensitive(sl, "thickness_mm");
    const cJSON *tum = cJSON_GetObjectItemCaseSensitive(sl, "thickness_um");
    if (tmm && tum) {
        field_path p = path_key(w, "thickness_um");
        return FAIL(c, p.s, "thickness given twice (thickness_mm and thickness_um)");
    }
    if (!tmm && !tum) {
        field_path p = path_key(w, "thickness_mm");
        return FAIL(c, p.s, "missing (give thickness_mm or thickness_um)");
    }
    double d = 0;
    s = get_positive(c, sl, w, tmm ? "thickness_mm" : "thickness_um", 1, &d);
    if (s) return s;
    out->thickness_nm = d * (tmm ? 1e6 : 1e3);
    if (!isfinite(out->thickness_nm)) {
        field_path p = path_key(w, tmm ? "thickness_mm" : "thickness_um");
        return FAIL(c, p.s, "too large");
    }
    if (!s) s = get_direction(c, sl, w, "normal", 1, out->normal);
    if (!s) s = tangent_frame(c, sl, w, out->normal, out->tangent);
    if (!s) s = get_direction(c, sl, w, "axis", 1, out->axis);
    if (!s) s = get_positive(c, sl, w, "eta_o", 1, &out->eta_o);
    if (!s) s = get_positive(c, sl, w, "eta_e", 1, &out->eta_e);
    return s;
}

static biref_status parse_panel(pctx *c, const cJSON *pn, const char *w, biref_panel *out)
{
    static const char *const keys[] = {"center", "size", "normal", "tangent", "radiance", NULL};
    biref_status s = as_object(c, pn, w);
    if (!s) s = check_keys(c, pn, w, keys);
    if (!s) s = get_vec(c, pn, w, "center", 1, 3, out->center);
    if (!s) s = get_vec(c, pn, w, "size", 1, 2, out->size);
    if (s) return s;
    for (int i = 0; i < 2; i++) {
        field_path p = path_key(w, "size");
        field_path q = path_index(p.s, i);
        if (!(out->size[i] > 0.0)) return FAIL(c, q.s, "must be positive");
    }
    s = get_direction(c, pn, w, "normal", 1, out->normal);
    if (!s) s = tangent_frame(c, pn, w, out->normal, out->tangent);
    if (!s) s = get_colour(c, pn, w, "radiance", 1, out->radiance);
    return s;
}

static biref_status parse_environment(pctx *c, const cJSON *env, biref_environment *out)
{
    static const char *const keys[] = {"type", "up", "zenith", "horizon", "ground", "a", "b", "size", NULL};
    const char *w = "light.environment";
    biref_status s = as_object(c, env, w);
    if (!s) s = check_keys(c, env, w, keys);
    const char *type = NULL;
    if (!s) s = get_string(c, env, w, "type", 0, &type);
    if (s) return s;
    if (type) {
        if (!strcmp(type, "gradient"))
            out->type = BIREF_ENV_GRADIENT;
        else if (!strcmp(type, "checker"))
            out->type = BIREF_ENV_CHECKER;
        else {
            field_path p = path_key(w, "type");
            return FAIL(c, p.s, "unknown type '%s' (expected gradient or checker)", type);
        }
    }
    s = get_direction(c, env, w, "up", 0, out->up);
    if (!s) s = get_colour(c, env, w, "zenith", 0, out->zenith);
    if (!s) s = get_colour(c, env, w, "horizon", 0, out->horizon);
    if (!s) s = get_colour(c, env, w, "ground", 0, out->ground);
    if (!s) s = get_colour(c, env, w, "a", 0, out->check_a);
    if (!s) s = get_colour(c, env, w, "b", 0, out->check_b);
    if (!s) s = get_positive(c, env, w, "size", 0, &out->check_size);
    return s;
}

static biref_status parse_polarization(pctx *c, const cJSON *pol, scene_pol *out)
{
    static const char *const keys[] = {"type", "s", "p", "direction", NULL};
    const char *w = "light.polarization";
    biref_status s = as_object(c, pol, w);
    if (!s) s = check_keys(c, pol, w, keys);
    const char *type = NULL;
    if (!s) s = get_string(c, pol, w, "type", 1, &type);
    if (s) return s;
    if (!strcmp(type, "unpolarized")) {
        out->type = POL_UNPOLARIZED;
        out->s = out->p = 0.5;
    } else if (!strcmp(type, "sp")) {
        out->type = POL_SP;
        s = get_number(c, pol, w, "s", 1, &out->s);
        if (!s) s = get_number(c, pol, w, "p", 1, &out->p);
        if (s) return s;
        if (out->s < 0) return FAIL(c, "light.polarization.s", "must not be negative");
        if (out->p < 0) return FAIL(c, "light.polarization.p", "must not be negative");
        double sum = out->s + out->p;
        if (!(sum > 0)) return FAIL(c, "light.polarization", "s + p must be positive");
        out->s /= sum;
        out->p /= sum;
    } else if (!strcmp(type, "linear")) {
        out->type = POL_LINEAR;
        s = get_direction(c, pol, w, "direction", 1, out->direction);
        if (s) return s;
    } else {
        return FAIL(c, "light.polarization.type", "unknown type '%s' (expected unpolarized, sp or linear)", type);
    }
    /* Fields that belong to another type are mistakes (e.g. "s" with type linear). */
    if (out->type != POL_SP) {
        if (cJSON_GetObjectItemCaseSensitive(pol, "s"))
            return FAIL(c, "light.polarization.s", "only allowed with type sp");
        if (cJSON_GetObjectItemCaseSensitive(pol, "p"))
            return FAIL(c, "light.polarization.p", "only allowed with type sp");
    }
    if (out->type != POL_LINEAR && cJSON_GetObjectItemCaseSensitive(pol, "direction"))
        return FAIL(c, "light.polarization.direction", "only allowed with type linear");
    return BIREF_OK;
}

static biref_status parse_filter(pctx *c, const cJSON *f, scene_filter *out)
{
    static const char *const keys[] = {"type", "direction", NULL};
    const char *w = "filter";
    biref_status s = as_object(c, f, w);
    if (!s) s = check_keys(c, f, w, keys);
    const char *type = NULL;
    if (!s) s = get_string(c, f, w, "type", 1, &type);
    if (s) return s;
    if (!strcmp(type, "none"))
        out->type = FILTER_NONE;
    else if (!strcmp(type, "s"))
        out->type = FILTER_S;
    else if (!strcmp(type, "p"))
        out->type = FILTER_P;
    else if (!strcmp(type, "linear"))
        out->type = FILTER_LINEAR;
    else
        return FAIL(c, "filter.type", "unknown type '%s' (expected none, s, p or linear)", type);
    if (out->type == FILTER_LINEAR) return get_direction(c, f, w, "direction", 1, out->direction);
    if (cJSON_GetObjectItemCaseSensitive(f, "direction"))
        return FAIL(c, "filter.direction", "only allowed with type linear");
    return BIREF_OK;
}

static biref_status parse_light(pctx *c, const cJSON *light, biref_scene *sc, scene_pol *pol)
{
    static const char *const keys[] = {"panel", "panels", "environment", "polarization", NULL};
    const char *w = "light";
    biref_status s = as_object(c, light, w);
    if (!s) s = check_keys(c, light, w, keys);
    if (s) return s;
    /* "panel" (one object or an array) and "panels" (an array) are synonyms. */
    const cJSON *pn = cJSON_GetObjectItemCaseSensitive(light, "panel");
    const char *pname = "light.panel";
    const cJSON *pns = cJSON_GetObjectItemCaseSensitive(light, "panels");
    if (pn && pns) return FAIL(c, "light.panels", "give either panel or panels, not both");
    if (pns) {
        pn = pns;
        pname = "light.panels";
        if (!cJSON_IsArray(pn)) return FAIL(c, pname, "expected an array, got %s", type_name(pn));
    }
    if (pn && cJSON_IsObject(pn)) {
        sc->n_panels = 1;
        s = parse_panel(c, pn, pname, &sc->panels[0]);
        if (s) return s;
    } else if (pn && cJSON_IsArray(pn)) {
        int n = cJSON_GetArraySize(pn);
        if (n > BIREF_SCENE_MAX_PANELS) return FAIL(c, pname, "at most %d panels", BIREF_SCENE_MAX_PANELS);
        int i = 0;
        for (const cJSON *e = pn->child; e; e = e->next, i++) {
            field_path p = path_index(pname, i);
            s = parse_panel(c, e, p.s, &sc->panels[i]);
            if (s) return s;
        }
        sc->n_panels = n;
    } else if (pn) {
        return FAIL(c, pname, "expected an object or an array, got %s", type_name(pn));
    }
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(light, "environment");
    if (v && (s = parse_environment(c, v, &sc->env))) return s;
    v = cJSON_GetObjectItemCaseSensitive(light, "polarization");
    if (v && (s = parse_polarization(c, v, pol))) return s;
    return BIREF_OK;
}

static void scene_defaults(biref_scene *sc)
{
    memset(sc, 0, sizeof *sc);
    sc->camera.up[1] = 1.0;
    sc->camera.fov_deg = 40.0;
    sc->camera.width = 640;
    sc->camera.height = 360;
    sc->camera.exposure = 1.0;
    sc->eta_medium = 1.0;
    sc->env.type = BIREF_ENV_GRADIENT;
    sc->env.up[1] = 1.0;
    v3_set(sc->env.zenith, 0.25, 0.40, 0.80);
    v3_set(sc->env.horizon, 0.85, 0.85, 0.90);
    v3_set(sc->env.ground, 0.20, 0.18, 0.16);
    v3_set(sc->env.check_a, 0.80, 0.80, 0.80);
    v3_set(sc->env.check_b, 0.10, 0.10, 0.10);
    sc->env.check_size = 0.5;
    static const double half[2] = {0.5, 0.5}, pass[2] = {1.0, 1.0};
    biref_light_sp(half, pass, &sc->light);
}

biref_status biref_scene_parse(const char *text, size_t len, biref_scene *out, char *msg, size_t msg_len)
{
    pctx ctx = {msg, msg_len}, *c = &ctx;
    if (!text || !out) return FAIL(c, "scene", "no input");
    char why[160];
    cJSON *root = biref_json_parse_strict(text, len, why, sizeof why);
    if (!root) return FAIL(c, "scene", "%s", why);
    biref_status s = BIREF_OK;

    biref_scene sc;
    scene_defaults(&sc);
    scene_pol pol = {POL_UNPOLARIZED, 0.5, 0.5, {0, 0, 0}};
    scene_filter filter = {FILTER_NONE, {0, 0, 0}};
    static const char *const keys[] = {"camera", "medium", "slabs", "light", "filter", NULL};
    if (!cJSON_IsObject(root)) {
        s = FAIL(c, "scene", "expected a JSON object at the top level, got %s", type_name(root));
        goto done;
    }
    if ((s = check_keys(c, root, "", keys))) goto done;
    const cJSON *v;
    if ((s = member(c, root, "", "camera", 1, &v)) || (s = parse_camera(c, v, &sc.camera))) goto done;
    if ((s = member(c, root, "", "medium", 0, &v))) goto done;
    if (v) {
        static const char *const mkeys[] = {"eta", NULL};
        if ((s = as_object(c, v, "medium")) || (s = check_keys(c, v, "medium", mkeys)) ||
            (s = get_positive(c, v, "medium", "eta", 1, &sc.eta_medium)))
            goto done;
    }
    if ((s = member(c, root, "", "slabs", 1, &v))) goto done;
    if (!cJSON_IsArray(v)) {
        s = FAIL(c, "slabs", "expected an array, got %s", type_name(v));
        goto done;
    }
    int n = cJSON_GetArraySize(v);
    if (n < 1) {
        s = FAIL(c, "slabs", "needs at least one slab");
        goto done;
    }
    if (n > BIREF_SCENE_MAX_SLABS) {
        s = FAIL(c, "slabs", "at most %d slabs", BIREF_SCENE_MAX_SLABS);
        goto done;
    }
    int i = 0;
    for (const cJSON *e = v->child; e; e = e->next, i++) {
        field_path p = path_index("slabs", i);
        if ((s = parse_slab(c, e, p.s, &sc.slabs[i]))) goto done;
    }
    sc.n_slabs = n;
    if ((s = member(c, root, "", "light", 0, &v))) goto done;
    if (v && (s = parse_light(c, v, &sc, &pol))) goto done;
    if ((s = member(c, root, "", "filter", 0, &v))) goto done;
    if (v && (s = parse_filter(c, v, &filter))) goto done;
    biref_scene_light(&pol, &filter, &sc.light);
    if ((s = biref_scene_validate(&sc, msg, msg_len))) goto done;
    *out = sc;
done:
    cJSON_Delete(root);
    return s;
}

biref_status biref_scene_load(const char *path, biref_scene *out, char *msg, size_t msg_len)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        if (msg && msg_len) snprintf(msg, msg_len, "cannot read: %s", strerror(errno));
        return BIREF_ERR_IO;
    }
    /* Scenes are small; 16 MiB is far beyond any sensible one and bounds the allocation. */
    const size_t cap = 16u << 20;
    size_t len = 0, size = 4096;
    char *buf = malloc(size);
    biref_status s = BIREF_OK;
    while (buf) {
        size_t got = fread(buf + len, 1, size - len, f);
        len += got;
        if (got == 0) break;
        if (len == size) {
            if (size >= cap) {
                s = BIREF_ERR_INVALID;
                if (msg && msg_len) snprintf(msg, msg_len, "scene: file too large (over 16 MiB)");
                break;
            }
            char *nb = realloc(buf, size * 2);
            if (!nb) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = nb;
            size *= 2;
        }
    }
    int read_error = ferror(f);
    fclose(f);
    if (!buf) {
        if (msg && msg_len) snprintf(msg, msg_len, "out of memory");
        return BIREF_ERR_NOMEM;
    }
    if (!s && read_error) {
        s = BIREF_ERR_IO;
        if (msg && msg_len) snprintf(msg, msg_len, "cannot read: I/O error");
    }
    if (!s) s = biref_scene_parse(buf, len, out, msg, msg_len);
    free(buf);
    return s;
}

/* ------------------------------------------------------------------------ */
/* Validation of the assembled scene (also for scenes built in code).        */
/* ------------------------------------------------------------------------ */

static int finite_vec(const double *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i])) return 0;
    return 1;
}

static int unit_vec(const double v[3])
{
    return finite_vec(v, 3) && fabs(v3_len(v) - 1.0) < 1e-6;
}

/* Pixels are single-precision floats (at most 3.4e38): a light, the exposure and their product
 * stay far below that, so that no pixel can overflow to infinity or NaN. */
#define MAX_BRIGHTNESS 1e30

static int colour_ok(const double v[3])
{
    for (int i = 0; i < 3; i++)
        if (!(isfinite(v[i]) && v[i] >= 0 && v[i] <= MAX_BRIGHTNESS)) return 0;
    return 1;
}

static double colour_max(const double v[3]) { return fmax(v[0], fmax(v[1], v[2])); }

biref_status biref_scene_validate(const biref_scene *sc, char *msg, size_t msg_len)
{
    pctx ctx = {msg, msg_len}, *c = &ctx;
    if (!sc) return FAIL(c, "scene", "no scene");
    const biref_camera *cam = &sc->camera;
    if (!finite_vec(cam->position, 3)) return FAIL(c, "camera.position", "must be finite");
    if (!finite_vec(cam->look_at, 3)) return FAIL(c, "camera.look_at", "must be finite");
    if (!unit_vec(cam->up)) return FAIL(c, "camera.up", "must be a non-zero vector");
    if (!(cam->fov_deg > 0.0 && cam->fov_deg <= 179.0))
        return FAIL(c, "camera.fov_deg", "must be in (0, 179] degrees");
    if (cam->width < 1 || cam->width > BIREF_SCENE_MAX_SIDE)
        return FAIL(c, "camera.width", "must be between 1 and %d", BIREF_SCENE_MAX_SIDE);
    if (cam->height < 1 || cam->height > BIREF_SCENE_MAX_SIDE)
        return FAIL(c, "camera.height", "must be between 1 and %d", BIREF_SCENE_MAX_SIDE);
    if ((long)cam->width * cam->height > BIREF_SCENE_MAX_PIXELS)
        return FAIL(c, "camera", "width x height must be at most %ld pixels", (long)BIREF_SCENE_MAX_PIXELS);
    if (!(isfinite(cam->exposure) && cam->exposure > 0)) return FAIL(c, "camera.exposure", "must be positive");
    double view[3];
    v3_sub(cam->look_at, cam->position, view);
    double vl = v3_len(view);
    double scale = fmax(1.0, fmax(v3_len(cam->position), v3_len(cam->look_at)));
    if (!(vl > 1e-9 * scale)) return FAIL(c, "camera.look_at", "must differ from camera.position");
    v3_scale(view, 1.0 / vl, view);
    double cr[3];
    v3_cross(view, cam->up, cr);
    /* sin(angle) < 1e-6: the image's horizontal axis would be undefined or unstable. */
    if (!(v3_len(cr) > 1e-6)) return FAIL(c, "camera.up", "must not be parallel to the view direction");

    if (!(isfinite(sc->eta_medium) && sc->eta_medium > 0)) return FAIL(c, "medium.eta", "must be positive");
    if (sc->n_slabs < 1 || sc->n_slabs > BIREF_SCENE_MAX_SLABS)
        return FAIL(c, "slabs", "needs between 1 and %d slabs", BIREF_SCENE_MAX_SLABS);
    for (int i = 0; i < sc->n_slabs; i++) {
        const biref_scene_slab *sl = &sc->slabs[i];
        field_path w = path_index("slabs", i);
        field_path p;
#define SLAB_FAIL(key, ...) (p = path_key(w.s, key), FAIL(c, p.s, __VA_ARGS__))
        if (!finite_vec(sl->center, 3)) return SLAB_FAIL("center", "must be finite");
        if (!(isfinite(sl->size[0]) && sl->size[0] > 0 && isfinite(sl->size[1]) && sl->size[1] > 0))
            return SLAB_FAIL("size", "must be positive");
        if (!(isfinite(sl->thickness_nm) && sl->thickness_nm > 0)) return SLAB_FAIL("thickness", "must be positive");
        if (!unit_vec(sl->normal)) return SLAB_FAIL("normal", "must be a unit vector");
        if (!unit_vec(sl->tangent) || fabs(v3_dot(sl->tangent, sl->normal)) > 1e-6)
            return SLAB_FAIL("tangent", "must be a unit vector orthogonal to the normal");
        if (!unit_vec(sl->axis)) return SLAB_FAIL("axis", "must be a unit vector");
        if (!(isfinite(sl->eta_o) && sl->eta_o > 0)) return SLAB_FAIL("eta_o", "must be positive");
        if (!(isfinite(sl->eta_e) && sl->eta_e > 0)) return SLAB_FAIL("eta_e", "must be positive");
        /* The camera inside a slab sees no well-defined front face. Scene units are metres,
         * so the slab occupies |distance to its mid-plane| <= d / 2 over its rectangle. */
        double rel[3], b[3];
        v3_sub(cam->position, sl->center, rel);
        v3_cross(sl->tangent, sl->normal, b);
        double dist = fabs(v3_dot(rel, sl->normal));
        double half = fmax(0.5 * sl->thickness_nm * 1e-9, 1e-12 * fmax(1.0, v3_len(rel)));
        if (dist <= half && fabs(v3_dot(rel, sl->tangent)) <= 0.5 * sl->size[0] &&
            fabs(v3_dot(rel, b)) <= 0.5 * sl->size[1])
            return FAIL(c, "camera.position", "inside slabs[%d]", i);
#undef SLAB_FAIL
    }
    if (sc->n_panels < 0 || sc->n_panels > BIREF_SCENE_MAX_PANELS)
        return FAIL(c, "light.panels", "at most %d panels", BIREF_SCENE_MAX_PANELS);
    for (int i = 0; i < sc->n_panels; i++) {
        const biref_panel *pn = &sc->panels[i];
        field_path w = path_index("light.panels", i);
        field_path p;
#define PANEL_FAIL(key, ...) (p = path_key(w.s, key), FAIL(c, p.s, __VA_ARGS__))
        if (!finite_vec(pn->center, 3)) return PANEL_FAIL("center", "must be finite");
        if (!(isfinite(pn->size[0]) && pn->size[0] > 0 && isfinite(pn->size[1]) && pn->size[1] > 0))
            return PANEL_FAIL("size", "must be positive");
        if (!unit_vec(pn->normal)) return PANEL_FAIL("normal", "must be a unit vector");
        if (!unit_vec(pn->tangent) || fabs(v3_dot(pn->tangent, pn->normal)) > 1e-6)
            return PANEL_FAIL("tangent", "must be a unit vector orthogonal to the normal");
        if (!colour_ok(pn->radiance)) return PANEL_FAIL("radiance", "must be finite, non-negative and at most 1e30");
#undef PANEL_FAIL
    }
    const biref_environment *env = &sc->env;
    if (env->type != BIREF_ENV_GRADIENT && env->type != BIREF_ENV_CHECKER)
        return FAIL(c, "light.environment.type", "unknown type");
    if (!unit_vec(env->up)) return FAIL(c, "light.environment.up", "must be a unit vector");
    if (!colour_ok(env->zenith)) return FAIL(c, "light.environment.zenith", "must be finite, non-negative and at most 1e30");
    if (!colour_ok(env->horizon)) return FAIL(c, "light.environment.horizon", "must be finite, non-negative and at most 1e30");
    if (!colour_ok(env->ground)) return FAIL(c, "light.environment.ground", "must be finite, non-negative and at most 1e30");
    if (!colour_ok(env->check_a)) return FAIL(c, "light.environment.a", "must be finite, non-negative and at most 1e30");
    if (!colour_ok(env->check_b)) return FAIL(c, "light.environment.b", "must be finite, non-negative and at most 1e30");
    if (!(isfinite(env->check_size) && env->check_size > 0)) return FAIL(c, "light.environment.size", "must be positive");
    double brightest = fmax(fmax(colour_max(env->zenith), colour_max(env->horizon)),
                            fmax(colour_max(env->ground), fmax(colour_max(env->check_a), colour_max(env->check_b))));
    for (int i = 0; i < sc->n_panels; i++) brightest = fmax(brightest, colour_max(sc->panels[i].radiance));
    if (sc->camera.exposure > MAX_BRIGHTNESS || sc->camera.exposure * brightest > MAX_BRIGHTNESS)
        return FAIL(c, "camera.exposure", "%g times the brightest light (%g) must be at most 1e30", sc->camera.exposure,
                    brightest);

    return biref_scene_light_check(&sc->light, c->msg, c->msg_len);
}
