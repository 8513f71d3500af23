/* Scene files: JSON (cJSON) -> biref_scene, with one-line errors that name the offending field.
 * Schema: docs/SCENES.md. Every value is checked where it is read, so the message can use the
 * JSON path; cross-field checks (camera up vs view, camera inside a slab, ...) run afterwards
 * in biref_scene_validate (scene_validate.c), whose field names are the JSON ones wherever the two
 * coincide; the typed reads of values are scene_fields.c's. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "biref/render.h"
#include "io/json_strict.h"
#include "optics/stack_file.h"
#include "render/scene_fields.h"
#include "render/scene_light.h"
#include "shading/vec3.h"

static biref_status parse_camera(pctx *c, const cJSON *cam, biref_camera *out)
{
    static const char *const keys[] = {"position", "look_at", "up", "fov_deg", "width", "height", "exposure", NULL};
    const char *w = "camera";
    biref_status s = biref_field_as_object(c, cam, w);
    if (!s) s = biref_field_check_keys(c, cam, w, keys);
    if (!s) s = biref_field_get_vec(c, cam, w, "position", 1, 3, out->position);
    if (!s) s = biref_field_get_vec(c, cam, w, "look_at", 1, 3, out->look_at);
    if (!s) s = biref_field_get_direction(c, cam, w, "up", 0, out->up);
    if (!s) s = biref_field_get_number(c, cam, w, "fov_deg", 0, &out->fov_deg);
    if (!s) s = biref_field_get_image_side(c, cam, w, "width", &out->width);
    if (!s) s = biref_field_get_image_side(c, cam, w, "height", &out->height);
    if (!s) s = biref_field_get_positive(c, cam, w, "exposure", 0, &out->exposure);
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
    biref_status s = biref_field_member(c, obj, where, "tangent", 0, &v);
    if (s) return s;
    if (!v) {
        any_perpendicular(n, t);
        return BIREF_OK;
    }
    field_path p = path_key(where, "tangent");
    double raw[3];
    s = biref_field_as_direction(c, v, p.s, raw);
    if (s) return s;
    if (v3_orthonormalize(raw, n, t)) return FAIL(c, p.s, "must not be parallel to the normal");
    return BIREF_OK;
}

/* A stack slab: "layers" as in stack files (the stack reader's own), none of the plain slab's
 * optics next to it. */
static biref_status parse_stack_slab(pctx *c, const cJSON *sl, const char *w, biref_scene_slab *out)
{
    static const char *const plain[] = {"thickness_mm", "thickness_um", "axis", "eta_o", "eta_e", "material"};
    for (int k = 0; k < 6; k++)
        if (cJSON_GetObjectItemCaseSensitive(sl, plain[k])) {
            field_path p = path_key(w, plain[k]);
            return FAIL(c, p.s, "a stack slab (layers) takes its optics from its layers; give one or the other");
        }
    biref_stack st;
    biref_status s = biref_stack_parse_layers(cJSON_GetObjectItemCaseSensitive(sl, "layers"), w, &st, c->msg,
                                              c->msg_len);
    if (s) return s;
    out->n_layers = st.n_layers;
    memcpy(out->layers, st.layers, (size_t)st.n_layers * sizeof st.layers[0]);
    out->thickness_nm = 0.0;
    for (int i = 0; i < st.n_layers; i++) out->thickness_nm += st.layers[i].thickness_nm;
    v3_set(out->axis, 0, 1, 0);
    out->eta_o = out->eta_e = 1.0;
    s = biref_field_get_direction(c, sl, w, "normal", 1, out->normal);
    if (!s) s = tangent_frame(c, sl, w, out->normal, out->tangent);
    return s;
}

/* "eta_o" and "eta_e", or "material" (a named dispersive material, docs/MATERIALS.md). */
static biref_status parse_slab_indices(pctx *c, const cJSON *sl, const char *w, biref_scene_slab *out)
{
    const cJSON *mat = cJSON_GetObjectItemCaseSensitive(sl, "material");
    out->material = NULL;
    if (!mat) {
        biref_status s = biref_field_get_positive(c, sl, w, "eta_o", 1, &out->eta_o);
        return s ? s : biref_field_get_positive(c, sl, w, "eta_e", 1, &out->eta_e);
    }
    field_path p = path_key(w, "material");
    for (int e = 0; e < 2; e++)
        if (cJSON_GetObjectItemCaseSensitive(sl, e ? "eta_e" : "eta_o"))
            return FAIL(c, p.s, "given with %s (the material gives both indices)", e ? "eta_e" : "eta_o");
    if (!cJSON_IsString(mat)) return FAIL(c, p.s, "must be the name of a material (biref material list)");
    out->material = biref_material_find(mat->valuestring);
    if (!out->material) return FAIL(c, p.s, "unknown material '%s' (biref material list names them)", mat->valuestring);
    out->eta_o = out->eta_e = 0.0;
    return BIREF_OK;
}

static biref_status parse_slab(pctx *c, const cJSON *sl, const char *w, biref_scene_slab *out)
{
    static const char *const keys[] = {"center", "size",  "thickness_mm", "thickness_um", "normal", "tangent",
                                       "axis",   "eta_o", "eta_e",        "material",     "layers", NULL};
    biref_status s = biref_field_as_object(c, sl, w);
    if (!s) s = biref_field_check_keys(c, sl, w, keys);
    if (!s) s = biref_field_get_vec(c, sl, w, "center", 1, 3, out->center);
    if (!s) s = biref_field_get_vec(c, sl, w, "size", 1, 2, out->size);
    if (s) return s;
    for (int i = 0; i < 2; i++) {
        field_path p = path_key(w, "size");
        field_path q = path_index(p.s, i);
        if (!(out->size[i] > 0.0)) return FAIL(c, q.s, "must be positive");
    }
    if (cJSON_GetObjectItemCaseSensitive(sl, "layers")) return parse_stack_slab(c, sl, w, out);
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
    s = biref_field_get_positive(c, sl, w, tmm ? "thickness_mm" : "thickness_um", 1, &d);
    if (s) return s;
    out->thickness_nm = d * (tmm ? 1e6 : 1e3);
    if (!isfinite(out->thickness_nm)) {
        field_path p = path_key(w, tmm ? "thickness_mm" : "thickness_um");
        return FAIL(c, p.s, "too large");
    }
    if (!s) s = biref_field_get_direction(c, sl, w, "normal", 1, out->normal);
    if (!s) s = tangent_frame(c, sl, w, out->normal, out->tangent);
    if (!s) s = biref_field_get_direction(c, sl, w, "axis", 1, out->axis);
    if (!s) s = parse_slab_indices(c, sl, w, out);
    return s;
}

static biref_status parse_panel(pctx *c, const cJSON *pn, const char *w, biref_panel *out)
{
    static const char *const keys[] = {"center", "size", "normal", "tangent", "radiance", NULL};
    biref_status s = biref_field_as_object(c, pn, w);
    if (!s) s = biref_field_check_keys(c, pn, w, keys);
    if (!s) s = biref_field_get_vec(c, pn, w, "center", 1, 3, out->center);
    if (!s) s = biref_field_get_vec(c, pn, w, "size", 1, 2, out->size);
    if (s) return s;
    for (int i = 0; i < 2; i++) {
        field_path p = path_key(w, "size");
        field_path q = path_index(p.s, i);
        if (!(out->size[i] > 0.0)) return FAIL(c, q.s, "must be positive");
    }
    s = biref_field_get_direction(c, pn, w, "normal", 1, out->normal);
    if (!s) s = tangent_frame(c, pn, w, out->normal, out->tangent);
    if (!s) s = biref_field_get_colour(c, pn, w, "radiance", 1, out->radiance);
    return s;
}

static biref_status parse_environment(pctx *c, const cJSON *env, biref_environment *out)
{
    static const char *const keys[] = {"type", "up", "zenith", "horizon", "ground", "a", "b", "size", NULL};
    const char *w = "light.environment";
    biref_status s = biref_field_as_object(c, env, w);
    if (!s) s = biref_field_check_keys(c, env, w, keys);
    const char *type = NULL;
    if (!s) s = biref_field_get_string(c, env, w, "type", 0, &type);
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
    s = biref_field_get_direction(c, env, w, "up", 0, out->up);
    if (!s) s = biref_field_get_colour(c, env, w, "zenith", 0, out->zenith);
    if (!s) s = biref_field_get_colour(c, env, w, "horizon", 0, out->horizon);
    if (!s) s = biref_field_get_colour(c, env, w, "ground", 0, out->ground);
    if (!s) s = biref_field_get_colour(c, env, w, "a", 0, out->check_a);
    if (!s) s = biref_field_get_colour(c, env, w, "b", 0, out->check_b);
    if (!s) s = biref_field_get_positive(c, env, w, "size", 0, &out->check_size);
    return s;
}

static biref_status parse_polarization(pctx *c, const cJSON *pol, scene_pol *out)
{
    static const char *const keys[] = {"type", "s", "p", "direction", NULL};
    const char *w = "light.polarization";
    biref_status s = biref_field_as_object(c, pol, w);
    if (!s) s = biref_field_check_keys(c, pol, w, keys);
    const char *type = NULL;
    if (!s) s = biref_field_get_string(c, pol, w, "type", 1, &type);
    if (s) return s;
    if (!strcmp(type, "unpolarized")) {
        out->type = POL_UNPOLARIZED;
        out->s = out->p = 0.5;
    } else if (!strcmp(type, "sp")) {
        out->type = POL_SP;
        s = biref_field_get_number(c, pol, w, "s", 1, &out->s);
        if (!s) s = biref_field_get_number(c, pol, w, "p", 1, &out->p);
        if (s) return s;
        if (out->s < 0) return FAIL(c, "light.polarization.s", "must not be negative");
        if (out->p < 0) return FAIL(c, "light.polarization.p", "must not be negative");
        double sum = out->s + out->p;
        if (!(sum > 0)) return FAIL(c, "light.polarization", "s + p must be positive");
        out->s /= sum;
        out->p /= sum;
    } else if (!strcmp(type, "linear")) {
        out->type = POL_LINEAR;
        s = biref_field_get_direction(c, pol, w, "direction", 1, out->direction);
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
    biref_status s = biref_field_as_object(c, f, w);
    if (!s) s = biref_field_check_keys(c, f, w, keys);
    const char *type = NULL;
    if (!s) s = biref_field_get_string(c, f, w, "type", 1, &type);
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
    if (out->type == FILTER_LINEAR) return biref_field_get_direction(c, f, w, "direction", 1, out->direction);
    if (cJSON_GetObjectItemCaseSensitive(f, "direction"))
        return FAIL(c, "filter.direction", "only allowed with type linear");
    return BIREF_OK;
}

static biref_status parse_light(pctx *c, const cJSON *light, biref_scene *sc, scene_pol *pol)
{
    static const char *const keys[] = {"panel", "panels", "environment", "polarization", NULL};
    const char *w = "light";
    biref_status s = biref_field_as_object(c, light, w);
    if (!s) s = biref_field_check_keys(c, light, w, keys);
    if (s) return s;
    /* "panel" (one object or an array) and "panels" (an array) are synonyms. */
    const cJSON *pn = cJSON_GetObjectItemCaseSensitive(light, "panel");
    const char *pname = "light.panel";
    const cJSON *pns = cJSON_GetObjectItemCaseSensitive(light, "panels");
    if (pn && pns) return FAIL(c, "light.panels", "give either panel or panels, not both");
    if (pns) {
        pn = pns;
        pname = "light.panels";
        if (!cJSON_IsArray(pn)) return FAIL(c, pname, "expected an array, got %s", biref_field_type_name(pn));
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
        return FAIL(c, pname, "expected an object or an array, got %s", biref_field_type_name(pn));
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
        s = FAIL(c, "scene", "expected a JSON object at the top level, got %s", biref_field_type_name(root));
        goto done;
    }
    if ((s = biref_field_check_keys(c, root, "", keys))) goto done;
    const cJSON *v;
    if ((s = biref_field_member(c, root, "", "camera", 1, &v)) || (s = parse_camera(c, v, &sc.camera))) goto done;
    if ((s = biref_field_member(c, root, "", "medium", 0, &v))) goto done;
    if (v) {
        static const char *const mkeys[] = {"eta", NULL};
        if ((s = biref_field_as_object(c, v, "medium")) || (s = biref_field_check_keys(c, v, "medium", mkeys)) ||
            (s = biref_field_get_positive(c, v, "medium", "eta", 1, &sc.eta_medium)))
            goto done;
    }
    if ((s = biref_field_member(c, root, "", "slabs", 1, &v))) goto done;
    if (!cJSON_IsArray(v)) {
        s = FAIL(c, "slabs", "expected an array, got %s", biref_field_type_name(v));
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
    if ((s = biref_field_member(c, root, "", "light", 0, &v))) goto done;
    if (v && (s = parse_light(c, v, &sc, &pol))) goto done;
    if ((s = biref_field_member(c, root, "", "filter", 0, &v))) goto done;
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
