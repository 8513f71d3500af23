/* Validation of an assembled scene (biref_scene_validate), for parsed scenes and scenes built in
 * code alike: the cross-field checks (camera up vs view, camera inside a slab, ...) with the JSON
 * field names wherever the two coincide (docs/SCENES.md). */
#include <math.h>
#include <string.h>

#include "biref/render.h"
#include "render/scene_fields.h"
#include "render/scene_light.h"
#include "shading/vec3.h"

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
        if (!unit_vec(sl->normal)) return SLAB_FAIL("normal", "must be a unit vector");
        if (!unit_vec(sl->tangent) || fabs(v3_dot(sl->tangent, sl->normal)) > 1e-6)
            return SLAB_FAIL("tangent", "must be a unit vector orthogonal to the normal");
        double thickness = sl->thickness_nm;
        if (sl->n_layers != 0 && sl->material)
            return SLAB_FAIL("material", "a stack slab (layers) takes its optics from its layers");
        if (sl->n_layers != 0) {
            biref_stack st;
            char why[200];
            if (biref_scene_slab_stack(sc, sl, &st) || biref_stack_check(&st, why, sizeof why))
                return sl->n_layers < 1 || sl->n_layers > BIREF_STACK_MAX_LAYERS
                           ? SLAB_FAIL("layers", "expected 1 to %d layers", BIREF_STACK_MAX_LAYERS)
                           : FAIL(c, w.s, "%s", why);
            thickness = 0.0;
            for (int k = 0; k < st.n_layers; k++) thickness += st.layers[k].thickness_nm;
        } else {
            if (!(isfinite(sl->thickness_nm) && sl->thickness_nm > 0))
                return SLAB_FAIL("thickness", "must be positive");
            if (!unit_vec(sl->axis)) return SLAB_FAIL("axis", "must be a unit vector");
            /* A dispersive material is checked over the renderer's band when it is created. */
            if (!sl->material && !(isfinite(sl->eta_o) && sl->eta_o > 0)) return SLAB_FAIL("eta_o", "must be positive");
            if (!sl->material && !(isfinite(sl->eta_e) && sl->eta_e > 0)) return SLAB_FAIL("eta_e", "must be positive");
        }
        /* The camera inside a slab sees no well-defined front face. Scene units are metres,
         * so the slab occupies |distance to its mid-plane| <= d / 2 over its rectangle. */
        double rel[3], b[3];
        v3_sub(cam->position, sl->center, rel);
        v3_cross(sl->tangent, sl->normal, b);
        double dist = fabs(v3_dot(rel, sl->normal));
        double half = fmax(0.5 * thickness * 1e-9, 1e-12 * fmax(1.0, v3_len(rel)));
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

    return biref_scene_light_check(&sc->light, msg, msg_len);
}

biref_status biref_scene_slab_stack(const biref_scene *sc, const biref_scene_slab *sl, biref_stack *out)
{
    if (sl->n_layers < 1 || sl->n_layers > BIREF_STACK_MAX_LAYERS) return BIREF_ERR_INVALID;
    out->eta_i = sc->eta_medium;
    out->n_layers = sl->n_layers;
    memcpy(out->layers, sl->layers, (size_t)sl->n_layers * sizeof sl->layers[0]);
    return BIREF_OK;
}
