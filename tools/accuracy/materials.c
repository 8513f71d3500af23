/* The materials of the accuracy study: the paper's fig. 9 (a, b, c) with their light, or a JSON
 * file of slabs (--materials). */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "cli_common.h"
#include "json_strict.h"
#include "study.h"

static void set_material(acc_material *m, const char *name, double eta_o, double eta_e, double ax, double ay,
                         double az, double d_mm, double ws, double wp, const char *analyzer)
{
    memset(m, 0, sizeof *m);
    snprintf(m->name, sizeof m->name, "%s", name);
    m->base = -1;
    m->slab = (biref_slab){eta_o, eta_e, {ax, ay, az}, d_mm * 1e6, 1.0};
    m->light.w_in[0] = ws;
    m->light.w_in[1] = wp;
    m->light.mask[0] = strcmp(analyzer, "p") != 0; /* "none" passes both */
    m->light.mask[1] = strcmp(analyzer, "s") != 0;
}

/* The paper's fig. 9 (a, b, c), constants and light exactly as in its captions. */
int acc_builtin_fig9(acc_material *m)
{
    set_material(&m[0], "a", 1.40, 1.38, -0.54, 0.80, 0.27, 1.25, 0.75, 0.25, "none");
    set_material(&m[1], "b", 1.50, 1.51, 0.25, 0.97, 0.00, 3.50, 0.50, 0.50, "none");
    set_material(&m[2], "c", 1.775, 1.231, 0.084, 0.979, -0.187, 1.15, 0.02, 0.98, "s");
    return 3;
}

static int json_number(const cJSON *o, const char *key, double *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!v) return 0;
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble)) return -1;
    *out = v->valuedouble;
    return 1;
}

/* Unknown and repeated keys are refused as in scene files (io/json_strict.h). */
static int bad_key(const char *where, const cJSON *o, const char *const *keys)
{
    int twice;
    const char *k = biref_json_bad_key(o, keys, &twice);
    if (!k) return 0;
    return cli_error(ACC_CMD, "%s: \"%s\": %s", where, k, twice ? "given twice" : "unknown field"), -1;
}

/* One material from a JSON object; errors name the file and the material's position. */
static int parse_material(const char *path, int idx, const cJSON *o, acc_material *m)
{
    char where[600];
    snprintf(where, sizeof where, "%s: material %d", path, idx + 1);
    if (!cJSON_IsObject(o)) return cli_error(ACC_CMD, "%s: expected an object", where), -1;
    static const char *const keys[] = {"name", "eta_o", "eta_e", "eta_i", "axis", "thickness_nm", "thickness_um",
                                       "thickness_mm", "polarization", "analyzer", NULL};
    if (bad_key(where, o, keys)) return -1;
    memset(m, 0, sizeof *m);
    m->base = -1;
    m->slab.eta_i = 1.0;
    cli_light_default(&m->light);
    const cJSON *name = cJSON_GetObjectItemCaseSensitive(o, "name");
    if (!cJSON_IsString(name) || !name->valuestring[0] || strlen(name->valuestring) > 40)
        return cli_error(ACC_CMD, "%s: \"name\" must be a string of 1-40 characters", where), -1;
    snprintf(m->name, sizeof m->name, "%s", name->valuestring);
    static const char *const req[2] = {"eta_o", "eta_e"};
    double *dst[2] = {&m->slab.eta_o, &m->slab.eta_e};
    for (int k = 0; k < 2; k++) {
        int r = json_number(o, req[k], dst[k]);
        if (r <= 0) return cli_error(ACC_CMD, "%s: \"%s\" must be a finite number", where, req[k]), -1;
    }
    if (json_number(o, "eta_i", &m->slab.eta_i) < 0)
        return cli_error(ACC_CMD, "%s: \"eta_i\" must be a finite number", where), -1;
    const cJSON *axis = cJSON_GetObjectItemCaseSensitive(o, "axis");
    if (!cJSON_IsArray(axis) || cJSON_GetArraySize(axis) != 3)
        return cli_error(ACC_CMD, "%s: \"axis\" must be an array of 3 numbers", where), -1;
    for (int k = 0; k < 3; k++) {
        const cJSON *v = cJSON_GetArrayItem(axis, k);
        if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble))
            return cli_error(ACC_CMD, "%s: \"axis\" must be an array of 3 numbers", where), -1;
        m->slab.axis[k] = v->valuedouble;
    }
    static const char *const thick[3] = {"thickness_nm", "thickness_um", "thickness_mm"};
    static const double scale[3] = {1.0, 1e3, 1e6};
    int have = 0;
    for (int k = 0; k < 3; k++) {
        double v;
        int r = json_number(o, thick[k], &v);
        if (r < 0) return cli_error(ACC_CMD, "%s: \"%s\" must be a finite number", where, thick[k]), -1;
        if (r > 0) {
            have++;
            m->slab.thickness_nm = v * scale[k];
        }
    }
    if (have != 1)
        return cli_error(ACC_CMD, "%s: give exactly one of thickness_nm, thickness_um, thickness_mm", where), -1;
    const cJSON *pol = cJSON_GetObjectItemCaseSensitive(o, "polarization");
    char opt[700];
    if (pol) {
        snprintf(opt, sizeof opt, "%s: \"polarization\"", where);
        if (!cJSON_IsString(pol)) return cli_error(ACC_CMD, "%s: must be a string such as \"0.75,0.25\"", opt), -1;
        if (cli_parse_polarization(ACC_CMD, opt, pol->valuestring, m->light.w_in)) return -1;
    }
    const cJSON *an = cJSON_GetObjectItemCaseSensitive(o, "analyzer");
    if (an) {
        snprintf(opt, sizeof opt, "%s: \"analyzer\"", where);
        if (!cJSON_IsString(an)) return cli_error(ACC_CMD, "%s: must be \"none\", \"s\" or \"p\"", opt), -1;
        if (cli_parse_analyzer(ACC_CMD, opt, an->valuestring, m->light.mask)) return -1;
    }
    char msg[200];
    if (biref_slab_check(&m->slab, msg, sizeof msg) != BIREF_OK) return cli_error(ACC_CMD, "%s: %s", where, msg), -1;
    return 0;
}

/* --materials FILE: {"materials": [...]} or a bare array of material objects. */
int acc_load_materials(const char *path, acc_material *m, int cap, int *n)
{
    FILE *f = fopen(path, "rb");
    if (!f) return cli_error(ACC_CMD, "--materials: cannot open '%s': %s", path, strerror(errno)), -1;
    char *text = malloc(MAX_FILE_BYTES + 1);
    if (!text) {
        fclose(f);
        return cli_error(ACC_CMD, "out of memory"), -1;
    }
    size_t len = fread(text, 1, MAX_FILE_BYTES + 1, f);
    int rd_err = ferror(f);
    fclose(f);
    if (rd_err || len > MAX_FILE_BYTES) {
        free(text);
        return cli_error(ACC_CMD, "--materials: '%s': %s", path, rd_err ? "read error" : "larger than 1 MiB"), -1;
    }
    char why[200];
    cJSON *root = biref_json_parse_strict(text, len, why, sizeof why);
    free(text);
    if (!root) return cli_error(ACC_CMD, "--materials: '%s': %s", path, why), -1;
    const cJSON *list = cJSON_IsArray(root) ? root : cJSON_GetObjectItemCaseSensitive(root, "materials");
    static const char *const top_keys[] = {"materials", NULL};
    char where[600];
    snprintf(where, sizeof where, "--materials: '%s'", path);
    int rc = 0;
    if (cJSON_IsObject(root) && bad_key(where, root, top_keys)) {
        rc = -1;
    } else if (!cJSON_IsArray(list) || cJSON_GetArraySize(list) < 1 || cJSON_GetArraySize(list) > cap) {
        cli_error(ACC_CMD, "--materials: '%s': expected a list of 1 to %d materials", path, cap);
        rc = -1;
    } else {
        *n = cJSON_GetArraySize(list);
        for (int i = 0; i < *n && rc == 0; i++) rc = parse_material(path, i, cJSON_GetArrayItem(list, i), &m[i]);
    }
    cJSON_Delete(root);
    return rc;
}
