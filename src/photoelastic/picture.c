/* Pictures of a plate in a polariscope at normal incidence: orthographic, the frame fills the
 * image, k x k box-filtered samples per pixel, rows in parallel; optionally each sample's fringes
 * averaged over its footprint in retardation (pe_footprint.h). */
#include <math.h>
#include <omp.h>

#include "biref/photoelastic.h"
#include "error.h"
#include "photoelastic/pe_footprint.h"
#include "photoelastic/shade_internal.h"

/* One sample of the tilted plate: the closest uniaxial slab (biref_pe_slab_best) on the general
 * path, white light through the integrator it. */
static biref_status oblique_shade(const biref_pe_setup *setup, const biref_integrator *it,
                                  const biref_pe_principal *p, double theta, double c[3])
{
    const biref_pe_setup at = biref_pe_setup_at_lambda(setup), *s = &at;
    const biref_slab slab = biref_pe_slab_best(&s->material, s->thickness, s->eta_i, p);
    biref_slab_state st;
    biref_status r = biref_slab_prepare(&slab, theta, &st);
    return r != BIREF_OK ? r : biref_pe_shade_state(s, it, &st, c);
}

static biref_status check_picture(const biref_pe_setup *s, const biref_spectral *sp, const biref_pe_field *f,
                                  const biref_pe_image_opts *opt, const float *xyz, char *msg, size_t msg_len)
{
    if (!s || !f || !opt || !xyz) return biref_fail(msg, msg_len, "no setup, field, options or output");
    if (opt->width < 1 || opt->height < 1)
        return biref_fail(msg, msg_len, "%d x %d pixels: the picture needs at least 1 x 1", opt->width, opt->height);
    if (opt->width > BIREF_PE_MAX_SIDE || opt->height > BIREF_PE_MAX_SIDE)
        return biref_fail(msg, msg_len, "%d x %d pixels: at most %d on a side", opt->width, opt->height,
                          BIREF_PE_MAX_SIDE);
    if (opt->threads < 0 || opt->threads > 1024)
        return biref_fail(msg, msg_len, "threads %d: expected 0 (all cores) to 1024", opt->threads);
    /* The setup's ranges, as the command line's options (one validation for every caller). */
    if (s->light == BIREF_PE_MONO && !(s->lambda_nm >= 200.0 && s->lambda_nm <= 2000.0))
        return biref_fail(msg, msg_len, "wavelength %g nm: expected 200 to 2000", s->lambda_nm);
    if (!(s->eta_i >= 1.0 && s->eta_i <= 5.0))
        return biref_fail(msg, msg_len, "eta_i %g: expected 1 to 5 (the index around the plate)", s->eta_i);
    if (!(s->thickness > 0.0 && s->thickness <= 1.0))
        return biref_fail(msg, msg_len, "thickness %g m: expected more than 0 and at most 1 m", s->thickness);
    if (opt->supersample < 1 || opt->supersample > BIREF_PE_MAX_SUPERSAMPLE)
        return biref_fail(msg, msg_len, "supersampling %d: expected 1 to %d", opt->supersample,
                          BIREF_PE_MAX_SUPERSAMPLE);
    if (s->light == BIREF_PE_WHITE && !sp) return biref_fail(msg, msg_len, "white light needs a spectral context");
    char why[128];
    if (biref_pe_material_check(&s->material, why, sizeof why) != BIREF_OK) return biref_fail(msg, msg_len, "material: %s", why);
    if (s->light == BIREF_PE_WHITE && opt->tilt > 0.0 && s->material.dispersion_alpha != 0.0)
        return biref_fail(msg, msg_len, "dispersion of birefringence (alpha %g) is modelled at normal incidence only: a "
                                        "tilted white-light view takes alpha 0",
                          s->material.dispersion_alpha);
    if (!(f->frame[1] > f->frame[0] && f->frame[3] > f->frame[2]))
        return biref_fail(msg, msg_len, "the field's frame is empty");
    if (!(opt->tilt >= 0.0 && opt->tilt <= BIREF_PE_MAX_TILT_DEG * M_PI / 180.0))
        return biref_fail(msg, msg_len, "tilt %g deg: expected 0 to %g", opt->tilt * 180.0 / M_PI, BIREF_PE_MAX_TILT_DEG);
    return BIREF_OK;
}

static biref_status render(const biref_pe_setup *s, const biref_spectral *sp, const biref_pe_field *f,
                           const biref_pe_image_opts *opt, int prefilter, float *xyz, char *msg, size_t msg_len)
{
    biref_status chk = check_picture(s, sp, f, opt, xyz, msg, msg_len);
    if (chk != BIREF_OK) return chk;
    const int oblique = opt->tilt > 0.0;
    const int W = opt->width, H = opt->height, k = opt->supersample;
    const double x0 = f->frame[0], sx = (f->frame[1] - f->frame[0]) / W;
    const double y1 = f->frame[3], sy = (f->frame[3] - f->frame[2]) / H;
    const double inv = 1.0 / (k * k);
    const int mono = s->light == BIREF_PE_MONO;
    const double tint[3] = {mono ? opt->tint[0] : 1.0, mono ? opt->tint[1] : 1.0, mono ? opt->tint[2] : 1.0};
    /* Outside the material the polariscope is seen without a specimen. */
    const double bg = biref_pe_polariscope_background(&s->pol);
    const int threads = opt->threads > 0 ? opt->threads : omp_get_max_threads();
    /* The prefilter needs the pre-integrated table for white light; monochromatic light is
     * averaged in closed form. Oblique views go through the general path, not prefiltered. */
    const int aa = prefilter && !oblique;
    biref_phase_prefilter *pf = NULL;
    if (aa && s->light == BIREF_PE_WHITE && biref_phase_prefilter_create(sp, &pf) != BIREF_OK)
        return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    /* Tilted white light goes through the expansion integrator, made once for the picture. */
    biref_integrator *it = NULL;
    if (oblique && s->light == BIREF_PE_WHITE && biref_pe_expansion_integrator(sp, &it) != BIREF_OK) {
        biref_phase_prefilter_destroy(pf);
        return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    }

    /* Every pixel is a pure function of its position, so the picture does not depend on the
     * thread count or the schedule. */
    int rows_done = 0;
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
    for (int j = 0; j < H; j++) {
        for (int i = 0; i < W; i++) {
            double acc[3] = {0, 0, 0};
            for (int b = 0; b < k; b++)
                for (int a = 0; a < k; a++) {
                    const double x = x0 + (i + (a + 0.5) / k) * sx;
                    const double y = y1 - (j + (b + 0.5) / k) * sy;
                    biref_pe_stress st;
                    double c[3];
                    if (biref_pe_field_stress(f, x, y, &st)) {
                        biref_pe_principal p;
                        biref_pe_principal_of(&st, &p);
                        if (!oblique)
                            biref_pe_shade_footprint(s, sp, pf,
                                                     aa ? biref_pe_retardation_footprint(s, f, x, y, sx / k, sy / k,
                                                                                         biref_pe_retardation_nm(s, &p))
                                                        : 0.0,
                                                     &p, c);
                        else if (oblique_shade(s, it, &p, opt->tilt, c) != BIREF_OK)
                            c[0] = c[1] = c[2] = NAN; /* cannot happen for a checked tilt; shows as black */
                    } else {
                        c[0] = c[1] = c[2] = bg;
                    }
                    for (int m = 0; m < 3; m++) acc[m] += c[m];
                }
            float *px = xyz + 3 * ((size_t)j * W + i);
            for (int m = 0; m < 3; m++) px[m] = (float)(acc[m] * inv * tint[m]);
        }
        if (opt->progress) {
#pragma omp critical(biref_pe_progress)
            opt->progress(opt->progress_user, ++rows_done, H);
        }
    }
    biref_phase_prefilter_destroy(pf);
    biref_integrator_destroy(it);
    return BIREF_OK;
}

biref_status biref_pe_render(const biref_pe_setup *s, const biref_spectral *sp, const biref_pe_field *f,
                             const biref_pe_image_opts *opt, float *xyz, char *msg, size_t msg_len)
{
    return render(s, sp, f, opt, 0, xyz, msg, msg_len);
}

biref_status biref_pe_render_prefiltered(const biref_pe_setup *s, const biref_spectral *sp, const biref_pe_field *f,
                                         const biref_pe_image_opts *opt, float *xyz, char *msg, size_t msg_len)
{
    return render(s, sp, f, opt, 1, xyz, msg, msg_len);
}
