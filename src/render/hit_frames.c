/* The paper's frames of a view ray at a slab hit (docs/SCENES.md "Frames"), and the public
 * world-space shading entry point built on them and on the renderer's per-hit evaluation. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "biref/shading.h"
#include "render/render_internal.h"
#include "render/vec3.h"

#define THETA_MAX BIREF_RENDER_THETA_MAX

void biref_render_hit_frames(const double normal[3], const double tangent[3], const double axis_world[3],
                       const biref_slab *base, const double dir[3], biref_hit_frames *f)
{
    double dn = v3_dot(dir, normal);
    f->theta = acos(fmin(1.0, fabs(dn)));
    if (f->theta > THETA_MAX) f->theta = THETA_MAX;
    /* Transmission: y = normal pointing away from the viewer (towards the light behind), z = the
     * view ray's tangential part, x = y x z. The reflection frame has y towards the viewer and the
     * same z, hence x_R = -x_T: the same slab lit from its other face. */
    v3_scale(normal, dn < 0 ? -1.0 : 1.0, f->y_T);
    v3_axpy(dir, -dn, normal, f->z);
    if (v3_normalize(f->z, f->z) < 1e-9) memcpy(f->z, tangent, sizeof f->z);
    v3_cross(f->y_T, f->z, f->x_T);
    v3_scale(f->x_T, -1.0, f->x_R);
    v3_scale(f->y_T, -1.0, f->y_R);
    v3_scale(dir, -1.0, f->k_view); /* light reaching the eye travels against the view ray */
    v3_axpy(dir, -2.0 * dn, normal, f->mirror);
    f->slab = *base;
    f->slab.axis[0] = v3_dot(axis_world, f->x_T);
    f->slab.axis[1] = v3_dot(axis_world, f->y_T);
    f->slab.axis[2] = v3_dot(axis_world, f->z);
}

static int finite3(const double v[3]) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

biref_status biref_hit_frames_make(const biref_surface *s, const double view_dir[3], biref_hit_frames *out)
{
    if (!s || !view_dir || !out) return BIREF_ERR_INVALID;
    if (!finite3(s->normal) || !finite3(s->tangent) || !finite3(s->axis) || !finite3(view_dir))
        return BIREF_ERR_INVALID;
    double n[3], t[3], b[3], v[3], a[3];
    if (!(v3_normalize(s->normal, n) > 0.0) || !(v3_normalize(view_dir, v) > 0.0)) return BIREF_ERR_INVALID;
    if (v3_orthonormalize(s->tangent, n, t)) return BIREF_ERR_INVALID;
    if (fabs(v3_dot(v, n)) < 1e-12) return BIREF_ERR_INVALID;
    v3_cross(t, n, b); /* local z = x cross y */
    for (int k = 0; k < 3; k++) a[k] = s->axis[0] * t[k] + s->axis[1] * n[k] + s->axis[2] * b[k];
    if (!(v3_normalize(a, a) > 0.0)) return BIREF_ERR_INVALID;
    biref_slab base = {s->eta_o, s->eta_e, {0, 0, 0}, s->thickness_nm, s->eta_i};
    biref_render_hit_frames(n, t, a, &base, v, out);
    return BIREF_OK;
}

struct biref_shader {
    biref_renderer *r; /* a renderer of a one-slab scene: its method, spectral tables, light, filter */
};

biref_status biref_shader_create(const biref_render_options *opt, const biref_polarization *light,
                                 const biref_filter *filter, biref_shader **out, char *msg, size_t msg_len)
{
    if (!out) return BIREF_ERR_INVALID;
    *out = NULL;
    /* The renderer checks the options and polarizers exactly as for a scene file. */
    static const char SCENE[] = "{\"camera\": {\"position\": [0, 1, 0], \"look_at\": [0, 0, 0], \"up\": [0, 0, 1]},"
                                " \"slabs\": [{\"center\": [0, 0, 0], \"size\": [1, 1], \"normal\": [0, 1, 0],"
                                " \"eta_o\": 1.5, \"eta_e\": 1.6, \"axis\": [1, 0, 0], \"thickness_um\": 1}]}";
    biref_scene scene;
    biref_status st = biref_scene_parse(SCENE, sizeof SCENE - 1, &scene, msg, msg_len);
    if (st) return st;
    if (light) scene.polarization = *light;
    if (filter) scene.filter = *filter;
    biref_render_options defaults;
    biref_render_options_default(&defaults);
    biref_shader *sh = calloc(1, sizeof *sh);
    if (!sh) return BIREF_ERR_NOMEM;
    st = biref_renderer_create(&scene, opt ? opt : &defaults, &sh->r, msg, msg_len);
    if (st) {
        free(sh);
        return st;
    }
    *out = sh;
    return BIREF_OK;
}

void biref_shader_destroy(biref_shader *sh)
{
    if (!sh) return;
    biref_renderer_destroy(sh->r);
    free(sh);
}

biref_status biref_shade_hit(const biref_shader *sh, const biref_surface *s, const double view_dir[3],
                             double T_xyz[3], double R_xyz[3], biref_hit_frames *frames)
{
    if (!sh || !T_xyz || !R_xyz) return BIREF_ERR_INVALID;
    biref_hit_frames local;
    biref_hit_frames *f = frames ? frames : &local;
    biref_status st = biref_hit_frames_make(s, view_dir, f);
    if (st) return st;
    st = biref_slab_check(&f->slab, NULL, 0);
    if (st) return st;
    return biref_render_shade_hit(sh->r, f, T_xyz, R_xyz) ? BIREF_ERR_ILLCOND : BIREF_OK;
}
