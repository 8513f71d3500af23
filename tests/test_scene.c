/* Scene files: good scenes parse to the expected values; every malformed scene is rejected with
 * one message that starts with the offending field's JSON path. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "biref/biref.h"
#include "test_cases.h"

static const char *const BASE =
    "{\"camera\": {\"position\": [0, 1, 4], \"look_at\": [0, 1, 0], \"up\": [0, 1, 0], \"fov_deg\": 40,"
    "             \"width\": 64, \"height\": 36},"
    " \"medium\": {\"eta\": 1.0},"
    " \"slabs\": [{\"center\": [0, 1, 0], \"size\": [2, 1.5], \"thickness_mm\": 1.25, \"normal\": [0, 0, 2],"
    "             \"tangent\": [1, 0, 0.5], \"axis\": [-0.54, 0.80, 0.27], \"eta_o\": 1.40, \"eta_e\": 1.38}],"
    " \"light\": {\"panel\": {\"center\": [0, 1, -3], \"size\": [4, 3], \"normal\": [0, 0, 1], \"radiance\": [1, 0.9, 0.8]},"
    "           \"environment\": {\"type\": \"checker\", \"a\": 0.5, \"b\": 0.1, \"size\": 0.5},"
    "           \"polarization\": {\"type\": \"sp\", \"s\": 3, \"p\": 1}},"
    " \"filter\": {\"type\": \"p\"}}";

static void test_valid_scenes_and_examples_parse_with_defaults_and_unit_vectors(void)
{
    biref_scene sc;
    char msg[256] = "";
    biref_status s = biref_scene_parse(BASE, strlen(BASE), &sc, msg, sizeof msg);
    CHECK(s == BIREF_OK);
    if (s) {
        fprintf(stderr, "base scene rejected: %s\n", msg);
        return;
    }
    CHECK(sc.camera.width == 64 && sc.camera.height == 36);
    CHECK_NEAR(sc.camera.fov_deg, 40, 0);
    CHECK_NEAR(sc.camera.exposure, 1, 0);
    CHECK(sc.n_slabs == 1);
    CHECK_NEAR(sc.slabs[0].thickness_nm, 1.25e6, 1e-6);
    CHECK_NEAR(sc.slabs[0].normal[2], 1.0, 1e-15); /* normalised */
    /* tangent orthogonalised against the normal, then normalised */
    CHECK_NEAR(sc.slabs[0].tangent[0], 1.0, 1e-15);
    CHECK_NEAR(sc.slabs[0].tangent[2], 0.0, 1e-15);
    double an = sqrt(0.54 * 0.54 + 0.8 * 0.8 + 0.27 * 0.27);
    CHECK_NEAR(sc.slabs[0].axis[1], 0.8 / an, 1e-15);
    CHECK(sc.n_panels == 1);
    CHECK_NEAR(sc.panels[0].radiance[2], 0.8, 0);
    CHECK(sc.env.type == BIREF_ENV_CHECKER);
    CHECK(sc.light.sp_model && !biref_light_is_world_fixed(&sc.light));
    CHECK_NEAR(sc.light.w_in[0], 0.75, 1e-15); /* s and p normalised to a sum of 1 */
    CHECK_NEAR(sc.light.w_in[1], 0.25, 1e-15);
    CHECK(sc.light.has_analyzer && sc.light.mask[0] == 0.0 && sc.light.mask[1] == 1.0); /* filter p */

    /* Minimal scene: defaults for everything optional. */
    const char *minimal = "{\"camera\": {\"position\": [0,0,5], \"look_at\": [0,0,0]},"
                          " \"slabs\": [{\"center\": [0,0,0], \"size\": [1,1], \"thickness_um\": 30,"
                          " \"normal\": [0,0,1], \"axis\": [1,0,0], \"eta_o\": 1.5, \"eta_e\": 1.6}],"
                          " \"comment\": \"free text\", \"_note\": 1}";
    s = biref_scene_parse(minimal, strlen(minimal), &sc, msg, sizeof msg);
    CHECK(s == BIREF_OK);
    if (!s) {
        CHECK_NEAR(sc.slabs[0].thickness_nm, 3e4, 1e-9);
        CHECK(sc.camera.width == 640 && sc.camera.height == 360);
        CHECK(sc.light.sp_model && sc.light.w_in[0] == 0.5 && sc.light.w_in[1] == 0.5); /* unpolarized */
        CHECK(!sc.light.has_analyzer && !biref_light_is_world_fixed(&sc.light));         /* no filter */
        CHECK(sc.n_panels == 0);
        CHECK_NEAR(fabs(sc.slabs[0].tangent[0]) + fabs(sc.slabs[0].tangent[1]) + fabs(sc.slabs[0].tangent[2]) > 0, 1, 0);
        CHECK_NEAR(sc.slabs[0].tangent[0] * sc.slabs[0].normal[0] + sc.slabs[0].tangent[1] * sc.slabs[0].normal[1] +
                       sc.slabs[0].tangent[2] * sc.slabs[0].normal[2],
                   0, 1e-15);
    }

    /* The shipped examples are valid. */
    const char *examples[] = {"examples/default.json", "examples/fig9a.json", "examples/fig9b.json",
                              "examples/fig9c.json"};
    for (size_t i = 0; i < sizeof examples / sizeof examples[0]; i++) {
        s = biref_scene_load(examples[i], &sc, msg, sizeof msg);
        CHECK(s == BIREF_OK);
        if (s) fprintf(stderr, "%s: %s\n", examples[i], msg);
    }
    s = biref_scene_load("examples/does-not-exist.json", &sc, msg, sizeof msg);
    CHECK(s == BIREF_ERR_IO);
    CHECK(strstr(msg, "cannot read") != NULL);
}

/* Finds the item at a path like "slabs[0].thickness_mm" in a cJSON tree; with create, the
 * last key is added to its parent object when absent. */
static cJSON *at_path(cJSON *root, const char *path, cJSON **parent, char *last_key)
{
    char buf[128];
    snprintf(buf, sizeof buf, "%s", path);
    cJSON *cur = root;
    *parent = NULL;
    last_key[0] = '\0';
    for (char *tok = strtok(buf, "."); tok; tok = strtok(NULL, ".")) {
        char *br = strchr(tok, '[');
        int idx = -1;
        if (br) {
            idx = atoi(br + 1);
            *br = '\0';
        }
        *parent = cur;
        snprintf(last_key, 64, "%s", tok);
        cur = cur ? cJSON_GetObjectItemCaseSensitive(cur, tok) : NULL;
        if (idx >= 0) {
            *parent = cur;
            last_key[0] = '\0';
            cur = cur ? cJSON_GetArrayItem(cur, idx) : NULL;
        }
    }
    return cur;
}

/* Applies "path := value" (value JSON text, NULL deletes) to BASE and returns the text. */
static char *mutate(const char *path, const char *value)
{
    cJSON *root = cJSON_Parse(BASE);
    cJSON *parent;
    char key[64];
    cJSON *item = at_path(root, path, &parent, key);
    if (!value) {
        if (item && parent && key[0]) cJSON_DeleteItemFromObjectCaseSensitive(parent, key);
    } else {
        cJSON *v = cJSON_Parse(value);
        if (!v) {
            fprintf(stderr, "test bug: bad value %s\n", value);
            exit(2);
        }
        if (item && key[0])
            cJSON_ReplaceItemInObjectCaseSensitive(parent, key, v);
        else if (item)
            cJSON_ReplaceItemViaPointer(parent, item, v); /* an array element has no key */
        else if (parent)
            cJSON_AddItemToObject(parent, key, v);
    }
    char *text = cJSON_PrintUnformatted(root);
    cJSON_Delete(root);
    return text;
}

static void expect_bad_text(const char *what, const char *text, size_t len, const char *field)
{
    biref_scene sc;
    char msg[256] = "";
    biref_status s = biref_scene_parse(text, len, &sc, msg, sizeof msg);
    size_t fl = strlen(field);
    int ok = s == BIREF_ERR_INVALID && !strncmp(msg, field, fl) && (msg[fl] == ':' || msg[fl] == '[') &&
             !strchr(msg, '\n');
    CHECK(ok);
    if (!ok) fprintf(stderr, "  %s: expected field '%s', got status %d, message '%s'\n", what, field, s, msg);
}

static void expect_bad(const char *path, const char *value, const char *field)
{
    char *text = mutate(path, value);
    char what[160];
    snprintf(what, sizeof what, "%s := %s", path, value ? value : "(deleted)");
    expect_bad_text(what, text, strlen(text), field);
    free(text);
}

static void test_invalid_fields_are_refused_naming_the_field(void)
{
    expect_bad("camera", NULL, "camera");
    expect_bad("camera.position", NULL, "camera.position");
    expect_bad("camera.position", "[1, 2]", "camera.position");
    expect_bad("camera.position", "[1, \"a\", 3]", "camera.position[1]");
    expect_bad("camera.position", "\"here\"", "camera.position");
    expect_bad("camera.fov_deg", "0", "camera.fov_deg");
    expect_bad("camera.fov_deg", "180", "camera.fov_deg");
    expect_bad("camera.fov_deg", "-5", "camera.fov_deg");
    expect_bad("camera.fov_deg", "\"40\"", "camera.fov_deg");
    expect_bad("camera.width", "0", "camera.width");
    expect_bad("camera.width", "-3", "camera.width");
    expect_bad("camera.width", "100000", "camera.width");
    expect_bad("camera.height", "10.5", "camera.height");
    expect_bad("camera.exposure", "0", "camera.exposure");
    expect_bad("camera.up", "[0, 0, 0]", "camera.up");
    expect_bad("camera.up", "[0, 0, -1]", "camera.up"); /* parallel to the view direction */
    expect_bad("camera.look_at", "[0, 1, 4]", "camera.look_at");
    expect_bad("camera.zoom", "2", "camera.zoom");
    expect_bad("slabs", NULL, "slabs");
    expect_bad("slabs", "[]", "slabs");
    expect_bad("slabs", "{}", "slabs");
    expect_bad("slabs[0]", "3", "slabs[0]");
    expect_bad("slabs[0].thickness_mm", "0", "slabs[0].thickness_mm");
    expect_bad("slabs[0].thickness_mm", "-1.25", "slabs[0].thickness_mm");
    expect_bad("slabs[0].thickness_mm", "null", "slabs[0].thickness_mm");
    expect_bad("slabs[0].thickness_mm", NULL, "slabs[0].thickness_mm");
    expect_bad("slabs[0].thickness_um", "5", "slabs[0].thickness_um");
    expect_bad("slabs[0].thicknes_um", "5", "slabs[0].thicknes_um");
    expect_bad("slabs[0].size", "[0, 1]", "slabs[0].size[0]");
    expect_bad("slabs[0].size", "[1, -1]", "slabs[0].size[1]");
    expect_bad("slabs[0].size", "[1, 1, 1]", "slabs[0].size");
    expect_bad("slabs[0].eta_o", "0", "slabs[0].eta_o");
    expect_bad("slabs[0].eta_e", "-1.38", "slabs[0].eta_e");
    expect_bad("slabs[0].eta_e", NULL, "slabs[0].eta_e");
    expect_bad("slabs[0].axis", "[0, 0, 0]", "slabs[0].axis");
    expect_bad("slabs[0].axis", "[1, 2]", "slabs[0].axis");
    expect_bad("slabs[0].normal", "[0, 0, 0]", "slabs[0].normal");
    expect_bad("slabs[0].tangent", "[0, 0, 3]", "slabs[0].tangent"); /* parallel to the normal */
    expect_bad("slabs[0].center", "null", "slabs[0].center");
    expect_bad("camera.position", "[0.5, 1.2, 0]", "camera.position"); /* inside the slab */
    expect_bad("medium.eta", "0", "medium.eta");
    expect_bad("medium.eta", NULL, "medium.eta");
    expect_bad("light.panel", "5", "light.panel");
    expect_bad("light.panel.radiance", "-1", "light.panel.radiance");
    expect_bad("light.panel.size", "[0, 1]", "light.panel.size[0]");
    expect_bad("light.environment.type", "\"hdr\"", "light.environment.type");
    expect_bad("light.environment.size", "0", "light.environment.size");
    expect_bad("light.polarization.type", "\"circular\"", "light.polarization.type");
    expect_bad("light.polarization.type", NULL, "light.polarization.type");
    expect_bad("light.polarization.s", "-1", "light.polarization.s");
    expect_bad("light.polarization", "{\"type\": \"sp\", \"s\": 0, \"p\": 0}", "light.polarization");
    expect_bad("light.polarization", "{\"type\": \"linear\"}", "light.polarization.direction");
    expect_bad("light.polarization", "{\"type\": \"linear\", \"direction\": [0, 0, 0]}", "light.polarization.direction");
    expect_bad("light.polarization", "{\"type\": \"unpolarized\", \"s\": 1}", "light.polarization.s");
    expect_bad("filter.type", "\"x\"", "filter.type");
    expect_bad("filter", "{\"type\": \"linear\", \"direction\": [0, 0, 0]}", "filter.direction");
    expect_bad("filter", "{\"type\": \"linear\"}", "filter.direction");
    expect_bad("filter", "\"s\"", "filter");

    /* Text-level damage. */
    size_t n = strlen(BASE);
    expect_bad_text("truncated", BASE, n / 2, "scene");
    expect_bad_text("empty", "", 0, "scene");
    expect_bad_text("array at top level", "[1, 2]", 6, "scene");
    char buf[4096];
    snprintf(buf, sizeof buf, "%s {}", BASE);
    expect_bad_text("trailing garbage", buf, strlen(buf), "scene");
    /* JSON has no NaN; cJSON rejects it, so it is a syntax error. */
    char *nan_text = strdup(BASE);
    char *p = strstr(nan_text, "40,");
    memcpy(p, "NaN", 3);
    expect_bad_text("NaN", nan_text, strlen(nan_text), "scene");
    free(nan_text);
    /* 1e999 overflows to inf in cJSON: caught as a non-finite number. */
    char *inf_text = mutate("camera.fov_deg", "1");
    char *q = strstr(inf_text, "\"fov_deg\":1");
    snprintf(buf, sizeof buf, "%.*s\"fov_deg\":1e999%s", (int)(q - inf_text), inf_text, q + strlen("\"fov_deg\":1"));
    expect_bad_text("inf", buf, strlen(buf), "camera.fov_deg");
    free(inf_text);
    /* Duplicate keys would silently use the first one. */
    snprintf(buf, sizeof buf, "%.*s\"medium\": {\"eta\": 1.0, \"eta\": 2.0}%s", (int)(strstr(BASE, "\"medium\"") - BASE),
             BASE, strstr(BASE, "\"medium\": {\"eta\": 1.0}") + strlen("\"medium\": {\"eta\": 1.0}"));
    expect_bad_text("duplicate key", buf, strlen(buf), "medium.eta");
}

static void test_scenes_built_in_code_are_validated_like_parsed_ones(void)
{
    /* Scenes built in code go through the same checks. */
    biref_scene sc;
    char msg[256];
    CHECK(biref_scene_parse(BASE, strlen(BASE), &sc, msg, sizeof msg) == BIREF_OK);
    biref_scene bad = sc;
    bad.slabs[0].thickness_nm = NAN;
    CHECK(biref_scene_validate(&bad, msg, sizeof msg) == BIREF_ERR_INVALID && !strncmp(msg, "slabs[0].thickness", 18));
    bad = sc;
    bad.camera.width = 0;
    CHECK(biref_scene_validate(&bad, msg, sizeof msg) == BIREF_ERR_INVALID && !strncmp(msg, "camera.width", 12));
    bad = sc;
    bad.camera.width = 16384;
    bad.camera.height = 16384;
    CHECK(biref_scene_validate(&bad, msg, sizeof msg) == BIREF_ERR_INVALID && !strncmp(msg, "camera", 6));
    bad = sc;
    bad.slabs[0].axis[0] = INFINITY;
    CHECK(biref_scene_validate(&bad, msg, sizeof msg) == BIREF_ERR_INVALID && !strncmp(msg, "slabs[0].axis", 13));
    CHECK(biref_scene_validate(&sc, msg, sizeof msg) == BIREF_OK);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"valid_scenes_and_examples_parse_with_defaults_and_unit_vectors",
         test_valid_scenes_and_examples_parse_with_defaults_and_unit_vectors},
        {"invalid_fields_are_refused_naming_the_field", test_invalid_fields_are_refused_naming_the_field},
        {"scenes_built_in_code_are_validated_like_parsed_ones",
         test_scenes_built_in_code_are_validated_like_parsed_ones},
    };
    return test_run_cases("test_scene", cases, TEST_COUNT(cases), argc, argv);
}
