/* Stack files (docs/STACKS.md): {"eta_i": 1.0, "layers": [{...}, ...]}, strict JSON. Every
 * error names its JSON path ("layers[2].thickness_um: must be positive"). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "biref/stack.h"
#include "error.h"
#include "io/json_strict.h"
#include "optics/stack_file.h"
#include "io/textfile.h"

/* Files beyond this are not stacks (64 layers take a few KB). */
#define STACK_FILE_MAX_BYTES (1u << 20)

typedef struct {
    char *msg;
    size_t msg_len;
    char path[64]; /* "layers[3]" */
} stack_ctx;

static biref_status fail_at(stack_ctx *c, const char *key, const char *what)
{
    char field[96];
    snprintf(field, sizeof field, "%s%s%s", c->path, c->path[0] && key[0] ? "." : "", key);
    return biref_fail_field(c->msg, c->msg_len, field, "%s", what);
}

/* obj[key] as a finite number; absent: *present = 0 (an error when required). */
static biref_status get_num(stack_ctx *c, const cJSON *obj, const char *key, int required, double *out, int *present)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (present) *present = v != NULL;
    if (!v) return required ? fail_at(c, key, "missing") : BIREF_OK;
    if (!cJSON_IsNumber(v)) return fail_at(c, key, "expected a number");
    if (!isfinite(v->valuedouble)) return fail_at(c, key, "must be a finite number");
    *out = v->valuedouble;
    return BIREF_OK;
}

static biref_status get_positive(stack_ctx *c, const cJSON *obj, const char *key, int required, double *out,
                                 int *present)
{
    biref_status s = get_num(c, obj, key, required, out, present);
    if (s == BIREF_OK && (!present || *present) && !(*out > 0.0)) return fail_at(c, key, "must be positive");
    return s;
}

/* Exactly one of thickness_nm, thickness_um, thickness_mm. */
static biref_status get_thickness(stack_ctx *c, const cJSON *obj, double *nm)
{
    static const char *const keys[3] = {"thickness_nm", "thickness_um", "thickness_mm"};
    static const double scale[3] = {1.0, 1e3, 1e6};
    int found = -1;
    for (int k = 0; k < 3; k++) {
        double v = 0.0;
        int present;
        biref_status s = get_positive(c, obj, keys[k], 0, &v, &present);
        if (s != BIREF_OK) return s;
        if (!present) continue;
        if (found >= 0) return fail_at(c, keys[k], "thickness given twice (give one of thickness_nm, _um, _mm)");
        found = k;
        *nm = v * scale[k];
    }
    if (found < 0) return fail_at(c, "thickness_um", "missing (give thickness_nm, thickness_um or thickness_mm)");
    if (!isfinite(*nm)) return fail_at(c, keys[found], "too large");
    return BIREF_OK;
}

static biref_status get_axis(stack_ctx *c, const cJSON *obj, double axis[3])
{
    const cJSON *ax = cJSON_GetObjectItemCaseSensitive(obj, "axis");
    const cJSON *az = cJSON_GetObjectItemCaseSensitive(obj, "azimuth_deg");
    if (ax && az) return fail_at(c, "azimuth_deg", "give axis or azimuth_deg, not both");
    if (az) {
        double phi = 0.0;
        biref_status s = get_num(c, obj, "azimuth_deg", 1, &phi, NULL);
        if (s != BIREF_OK) return s;
        /* In the surface (y = 0), from x (s) towards z (p at normal incidence). */
        axis[0] = cos(phi * M_PI / 180.0);
        axis[1] = 0.0;
        axis[2] = sin(phi * M_PI / 180.0);
        return BIREF_OK;
    }
    if (!ax) return fail_at(c, "axis", "missing (give axis or azimuth_deg)");
    if (!cJSON_IsArray(ax) || cJSON_GetArraySize(ax) != 3) return fail_at(c, "axis", "expected an array of 3 numbers");
    int i = 0;
    for (const cJSON *e = ax->child; e; e = e->next, i++) {
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble)) return fail_at(c, "axis", "expected 3 finite numbers");
        axis[i] = e->valuedouble;
    }
    double n = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (!(n > 1e-12) || !isfinite(n)) return fail_at(c, "axis", "must be a non-zero vector");
    return BIREF_OK;
}

/* {"material": "quartz", "axis" or "azimuth_deg"}: a named dispersive material (docs/MATERIALS.md);
 * an isotropic one takes no axis. */
static biref_status parse_material_layer(stack_ctx *c, const cJSON *obj, const cJSON *mat, biref_layer *l)
{
    static const char *const fixed[] = {"eta", "eta_o", "eta_e"};
    for (int k = 0; k < 3; k++)
        if (cJSON_GetObjectItemCaseSensitive(obj, fixed[k]))
            return fail_at(c, fixed[k], "given with material (the material gives the indices)");
    if (!cJSON_IsString(mat)) return fail_at(c, "material", "must be the name of a material (biref material list)");
    l->material = biref_material_find(mat->valuestring);
    if (!l->material) {
        char what[160];
        snprintf(what, sizeof what, "unknown material '%.80s' (biref material list names them)", mat->valuestring);
        return fail_at(c, "material", what);
    }
    biref_material_info info;
    biref_material_get_info(l->material, &info);
    if (info.isotropic) {
        static const char *const axis[] = {"axis", "azimuth_deg"};
        for (int k = 0; k < 2; k++)
            if (cJSON_GetObjectItemCaseSensitive(obj, axis[k]))
                return fail_at(c, axis[k], "an isotropic material has no optic axis");
        l->isotropic = 1;
        l->axis[1] = 1.0;
        return BIREF_OK;
    }
    return get_axis(c, obj, l->axis);
}

static biref_status parse_layer(stack_ctx *c, const cJSON *obj, biref_layer *l)
{
    static const char *const keys[] = {"eta",          "eta_o",        "eta_e",        "axis",     "azimuth_deg",
                                       "thickness_nm", "thickness_um", "thickness_mm", "material", NULL};
    if (!cJSON_IsObject(obj)) return fail_at(c, "", "expected an object");
    int twice;
    const char *bad = biref_json_bad_key(obj, keys, &twice);
    if (bad) return fail_at(c, bad, twice ? "given twice" : "unknown field");
    memset(l, 0, sizeof *l);
    const cJSON *mat = cJSON_GetObjectItemCaseSensitive(obj, "material");
    if (mat) {
        biref_status s = parse_material_layer(c, obj, mat, l);
        return s ? s : get_thickness(c, obj, &l->thickness_nm);
    }
    int iso = cJSON_GetObjectItemCaseSensitive(obj, "eta") != NULL;
    biref_status s;
    if (iso) {
        static const char *const aniso[] = {"eta_o", "eta_e", "axis", "azimuth_deg"};
        for (int k = 0; k < 4; k++)
            if (cJSON_GetObjectItemCaseSensitive(obj, aniso[k]))
                return fail_at(c, aniso[k], "an isotropic layer (eta) has no optic axis or second index");
        l->isotropic = 1;
        if ((s = get_positive(c, obj, "eta", 1, &l->eta_o, NULL))) return s;
        l->eta_e = l->eta_o;
        l->axis[1] = 1.0;
    } else {
        if ((s = get_positive(c, obj, "eta_o", 1, &l->eta_o, NULL)) ||
            (s = get_positive(c, obj, "eta_e", 1, &l->eta_e, NULL)) || (s = get_axis(c, obj, l->axis)))
            return s;
    }
    return get_thickness(c, obj, &l->thickness_nm);
}

/* The "layers" array (NULL: missing) into out->layers and out->n_layers; errors name the JSON path
 * below prefix ("" for a stack file, "slabs[2]" in a scene). */
biref_status biref_stack_parse_layers(const cJSON *layers, const char *prefix, biref_stack *out, char *msg,
                                      size_t msg_len)
{
    stack_ctx ctx = {msg, msg_len, ""}, *c = &ctx;
    snprintf(c->path, sizeof c->path, "%s", prefix);
    if (!layers) return fail_at(c, "layers", "missing");
    int n = cJSON_IsArray(layers) ? cJSON_GetArraySize(layers) : -1;
    if (n < 1 || n > BIREF_STACK_MAX_LAYERS) {
        char what[96];
        snprintf(what, sizeof what, "expected an array of 1 to %d layers", BIREF_STACK_MAX_LAYERS);
        return fail_at(c, "layers", what);
    }
    int i = 0;
    for (const cJSON *e = layers->child; e; e = e->next, i++) {
        snprintf(c->path, sizeof c->path, "%s%slayers[%d]", prefix, prefix[0] ? "." : "", i);
        biref_status s = parse_layer(c, e, &out->layers[i]);
        if (s) return s;
    }
    out->n_layers = n;
    return BIREF_OK;
}

biref_status biref_stack_parse(const char *text, size_t len, biref_stack *out, char *msg, size_t msg_len)
{
    stack_ctx ctx = {msg, msg_len, ""}, *c = &ctx;
    if (!text || !out) return biref_fail_field(msg, msg_len, "stack", "no input");
    char why[160];
    cJSON *root = biref_json_parse_strict(text, len, why, sizeof why);
    if (!root) return biref_fail_field(msg, msg_len, "stack", "%s", why);
    biref_stack *st = calloc(1, sizeof *st);
    biref_status s = BIREF_OK;
    if (!st) {
        s = biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
        goto done;
    }
    static const char *const keys[] = {"eta_i", "layers", NULL};
    if (!cJSON_IsObject(root)) {
        s = biref_fail_field(msg, msg_len, "stack", "expected a JSON object at the top level");
        goto done;
    }
    int twice;
    const char *bad = biref_json_bad_key(root, keys, &twice);
    if (bad) {
        s = fail_at(c, bad, twice ? "given twice" : "unknown field");
        goto done;
    }
    st->eta_i = 1.0;
    if ((s = get_positive(c, root, "eta_i", 0, &st->eta_i, NULL))) goto done;
    if ((s = biref_stack_parse_layers(cJSON_GetObjectItemCaseSensitive(root, "layers"), "", st, msg, msg_len)))
        goto done;
    if ((s = biref_stack_check(st, msg, msg_len)) == BIREF_OK) *out = *st;
done:
    free(st);
    cJSON_Delete(root);
    return s;
}

biref_status biref_stack_load(const char *path, biref_stack *out, char *msg, size_t msg_len)
{
    char *text = NULL;
    size_t len = 0;
    biref_status s = biref_read_text(path, STACK_FILE_MAX_BYTES, &text, &len, msg, msg_len);
    if (s != BIREF_OK) return s;
    s = biref_stack_parse(text, len, out, msg, msg_len);
    free(text);
    return s;
}
