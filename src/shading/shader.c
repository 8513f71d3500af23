/* The shader (shading.h): {spectral context, integrator, one light}. Every picture of the library
 * shades its slab hits here; world-fixed polarizers become each hit's coherency and analyzer here. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "optics/slab_internal.h"
#include "shading/shader_internal.h"
#include "shading/vec3.h"

static int finite_light(const biref_light *l)
{
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            if (!isfinite(creal(l->C[i][j])) || !isfinite(cimag(l->C[i][j])) || !isfinite(creal(l->P[i][j])) ||
                !isfinite(cimag(l->P[i][j])))
                return 0;
    for (int k = 0; k < 3; k++)
        if (!isfinite(l->polarizer_axis[k]) || !isfinite(l->analyzer_axis[k])) return 0;
    return 1;
}

/* Whether the integrator takes the light: one slab integrated under it, with its world-fixed
 * parts resolved in some wave's basis. The method decides, not the shader. */
static biref_status probe(const biref_integrator *it, const biref_light *l, char *msg, size_t msg_len)
{
    static const biref_slab slab = {1.5, 1.6, {0.6, 0.8, 0.0}, 2000.0, 1.0};
    static const double s[3] = {1, 0, 0}, p[3] = {0, 0.8, 0.6};
    biref_light at;
    biref_light_at(l, s, p, p, &at);
    biref_slab_state st;
    biref_integration res;
    biref_status r = biref_slab_prepare(&slab, 0.3, &st);
    if (r == BIREF_OK) r = biref_integrate(it, &st, BIREF_SIDE_TRANSMISSION, &at, &res);
    if (r != BIREF_ERR_INVALID) return BIREF_OK;
    const char *name = biref_method_name(biref_integrator_method(it));
    return biref_fail(msg, msg_len, "the %s method cannot integrate this light (a general coherency or analyzer)",
                      name ? name : "chosen");
}

/* The light's packet form (packet_light.h) when its coherency is Hermitian (the kernel's form
 * keeps C01 and takes C10 as its conjugate); 0 otherwise. */
static int packet_source(const biref_light *l, biref_packet_light_source *out)
{
    static const double complex ID[2][2] = {{1, 0}, {0, 1}};
    const double complex(*P)[2] = l->has_analyzer ? (const double complex(*)[2])l->P : ID;
    const int hermitian = l->world_polarizer || (cimag(l->C[0][0]) == 0.0 && cimag(l->C[1][1]) == 0.0 &&
                                                 l->C[1][0] == conj(l->C[0][1]));
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            out->P[2 * i + j] = creal(P[i][j]);
            out->Pi[2 * i + j] = cimag(P[i][j]);
        }
    out->C[0] = creal(l->C[0][0]);
    out->C[1] = creal(l->C[0][1]);
    out->C[2] = creal(l->C[1][1]);
    out->Ci = cimag(l->C[0][1]);
    out->polarizer = l->world_polarizer;
    out->analyzer = l->world_analyzer;
    memcpy(out->pol, l->polarizer_axis, sizeof out->pol);
    memcpy(out->ana, l->analyzer_axis, sizeof out->ana);
    return hermitian;
}

biref_status biref_shader_create(const biref_spectral *sp, const biref_integrator_options *opt,
                                 const biref_light *light, biref_shader **out, char *msg, size_t msg_len)
{
    if (!out) return biref_fail(msg, msg_len, "no output");
    *out = NULL;
    if (!sp) return biref_fail(msg, msg_len, "no spectral context");
    biref_integrator_options defaults;
    biref_integrator_options_default(&defaults);
    biref_light unpolarized;
    static const double half[2] = {0.5, 0.5}, pass[2] = {1.0, 1.0};
    biref_light_sp(half, pass, &unpolarized);
    if (!light) light = &unpolarized;
    if (!finite_light(light)) return biref_fail(msg, msg_len, "the light's matrices and axes must be finite");
    biref_shader *sh = calloc(1, sizeof *sh);
    if (!sh) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    sh->sp = sp;
    sh->light = *light;
    sh->world_fixed = biref_light_is_world_fixed(light);
    sh->passthrough = biref_light_passthrough(light);
    sh->packet_lit = !light->sp_model && packet_source(light, &sh->packet_light);
    biref_status s = biref_integrator_create(sp, opt ? opt : &defaults, &sh->it, msg, msg_len);
    if (s == BIREF_OK) s = probe(sh->it, light, msg, msg_len);
    if (s != BIREF_OK) {
        biref_shader_destroy(sh);
        return s;
    }
    *out = sh;
    return BIREF_OK;
}

void biref_shader_destroy(biref_shader *sh)
{
    if (!sh) return;
    biref_integrator_destroy(sh->it);
    free(sh);
}

biref_method biref_shader_method(const biref_shader *sh) { return biref_integrator_method(sh->it); }

const biref_light *biref_shader_light(const biref_shader *sh) { return &sh->light; }

/* The light of one side of a hit: s is the frame's x axis for both waves, p = k x s. */
void biref_shader_side_light(const biref_shader *sh, const double x[3], const double k_in[3], const double k_out[3],
                       biref_light *out)
{
    double p_in[3], p_out[3];
    v3_cross(k_in, x, p_in);
    v3_cross(k_out, x, p_out);
    biref_light_at(&sh->light, x, p_in, p_out, out);
}

biref_status biref_shader_eval(const biref_shader *sh, const biref_hit_frames *f, const biref_opl_footprint *fpT,
                               double T[3], double R[3])
{
    if (!sh->world_fixed)
        return biref_integrate_hit(sh->it, &(biref_slab_hit){f->slab, f->theta}, fpT, &sh->light, T, R);
    /* One optics set-up per hit: the reflection frame is the transmission frame rotated by 180
     * degrees about z, i.e. the same slab lit from the other face (biref_slab_state_flip). */
    biref_slab_state stT, stR;
    biref_status s = biref_slab_prepare_trusted(&f->slab, f->theta, &stT);
    if (s != BIREF_OK) return s;
    biref_slab_state_flip(&stT, &stR);
    biref_opl_footprint fpR;
    if (fpT) biref_opl_footprint_flip(fpT, &fpR); /* the flip swaps the down and up legs */
    double k_refl_in[3];
    v3_scale(f->mirror, -1.0, k_refl_in);
    biref_light lT, lR;
    biref_shader_side_light(sh, f->x_T, f->k_view, f->k_view, &lT);
    biref_shader_side_light(sh, f->x_R, k_refl_in, f->k_view, &lR);
    biref_integration res;
    s = biref_integrate_footprint(sh->it, &stT, fpT, BIREF_SIDE_TRANSMISSION, &lT, &res);
    if (s != BIREF_OK) return s;
    memcpy(T, res.T, sizeof res.T);
    s = biref_integrate_footprint(sh->it, &stR, fpT ? &fpR : NULL, BIREF_SIDE_REFLECTION, &lR, &res);
    memcpy(R, res.R, sizeof res.R);
    return s;
}

biref_status biref_shader_eval_material(const biref_shader *sh, const biref_material *m, const biref_hit_frames *f,
                                        double T[3], double R[3])
{
    biref_light lT = sh->light, lR = sh->light;
    if (sh->world_fixed) {
        double k_refl_in[3];
        v3_scale(f->mirror, -1.0, k_refl_in);
        biref_shader_side_light(sh, f->x_T, f->k_view, f->k_view, &lT);
        biref_shader_side_light(sh, f->x_R, k_refl_in, f->k_view, &lR);
    }
    /* Reflection: the same slab lit from the other face, the frame rotated by 180 degrees about z
     * (axis (a, b, c) -> (-a, -b, c), as biref_slab_state_flip). */
    biref_slab flipped = f->slab;
    flipped.axis[0] = -f->slab.axis[0];
    flipped.axis[1] = -f->slab.axis[1];
    biref_integration res;
    biref_status s = biref_integrate_material(sh->it, m, &f->slab, f->theta, BIREF_SIDE_TRANSMISSION, &lT, &res);
    if (s != BIREF_OK) return s;
    memcpy(T, res.T, sizeof res.T);
    s = biref_integrate_material(sh->it, m, &flipped, f->theta, BIREF_SIDE_REFLECTION, &lR, &res);
    memcpy(R, res.R, sizeof res.R);
    return s;
}

const biref_packet_light_source *biref_shader_packet_light(const biref_shader *sh)
{
    return sh->packet_lit ? &sh->packet_light : NULL;
}

void biref_shader_packet(const biref_shader *sh, const biref_packet_hits *hits, const biref_packet_hit_light *lights,
                         const biref_opl_footprint *fp, size_t n, double (*T)[3], double (*R)[3],
                         unsigned char *scalar)
{
    if (sh->light.sp_model)
        biref_integrate_packet_hits(sh->it, hits, fp, n, &sh->light, T, R, scalar);
    else if (sh->packet_lit && lights)
        biref_integrate_packet_hits_lit(sh->it, hits, fp, n, lights, T, R, scalar);
    else
        memset(scalar, 1, n); /* no per-hit form: one by one */
}

double biref_shader_background(const biref_shader *sh, const double k[3], const double normal[3],
                               const double tangent[3])
{
    if (!sh->world_fixed) return sh->passthrough; /* diagonal in every wave's own basis */
    double s[3], p[3];
    v3_cross(k, normal, s);
    if (v3_normalize(s, s) < 1e-9 && v3_orthonormalize(tangent, k, s)) {
        /* k is parallel to both the normal and the tangent: impossible for an orthonormal pair. */
        v3_set(s, 1, 0, 0);
    }
    v3_cross(k, s, p);
    biref_light l;
    biref_light_at(&sh->light, s, p, p, &l);
    return biref_light_passthrough(&l);
}

void biref_shader_failed_hit(const biref_shader *sh, const biref_hit_frames *f, double T[3], double R[3])
{
    /* A failed evaluation (grazing-angle breakdown) must not put a NaN in the image: the slab is
     * shown as a perfect mirror seen through the analyzer. */
    double f_pass = sh->passthrough;
    if (sh->world_fixed) {
        double k_refl_in[3];
        v3_scale(f->mirror, -1.0, k_refl_in);
        biref_light l;
        biref_shader_side_light(sh, f->x_R, k_refl_in, f->k_view, &l);
        f_pass = biref_light_passthrough(&l);
    }
    v3_set(T, 0, 0, 0);
    v3_set(R, f_pass, f_pass, f_pass);
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
    st = biref_shader_eval(sh, f, NULL, T_xyz, R_xyz);
    return st == BIREF_OK ? BIREF_OK : BIREF_ERR_ILLCOND;
}
