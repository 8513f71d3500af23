/* Pictures of a plate in a polariscope at normal incidence: orthographic, the frame fills the
 * image, k x k box-filtered samples per pixel, rows in parallel; optionally each sample's fringes
 * averaged over its footprint in retardation (pe_footprint.h). */
#include <math.h>
#include <omp.h>

#include "biref/photoelastic.h"
#include "photoelastic/pe_footprint.h"

static biref_status render(const biref_pe_setup *s, const biref_spectral *sp, const biref_pe_field *f,
                           const biref_pe_image_opts *opt, int prefilter, float *xyz)
{
    if (!s || !f || !opt || !xyz || opt->width < 1 || opt->height < 1 || opt->supersample < 1 ||
        opt->supersample > BIREF_PE_MAX_SUPERSAMPLE)
        return BIREF_ERR_INVALID;
    if (s->light == BIREF_PE_WHITE && !sp) return BIREF_ERR_INVALID;
    if (!(f->frame[1] > f->frame[0] && f->frame[3] > f->frame[2])) return BIREF_ERR_INVALID;
    if (!(opt->tilt >= 0.0 && opt->tilt <= 89.0 * M_PI / 180.0)) return BIREF_ERR_INVALID;
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
    if (aa && s->light == BIREF_PE_WHITE && biref_phase_prefilter_create(sp, &pf) != BIREF_OK) return BIREF_ERR_NOMEM;

    /* Every pixel is a pure function of its position, so the picture does not depend on the
     * thread count or the schedule. */
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
                        else if (biref_pe_shade_oblique(s, sp, &p, opt->tilt, c) != BIREF_OK)
                            c[0] = c[1] = c[2] = NAN; /* cannot happen for a checked tilt; shows as black */
                    } else {
                        c[0] = c[1] = c[2] = bg;
                    }
                    for (int m = 0; m < 3; m++) acc[m] += c[m];
                }
            float *px = xyz + 3 * ((size_t)j * W + i);
            for (int m = 0; m < 3; m++) px[m] = (float)(acc[m] * inv * tint[m]);
        }
    }
    biref_phase_prefilter_destroy(pf);
    return BIREF_OK;
}

biref_status biref_pe_render(const biref_pe_setup *s, const biref_spectral *sp, const biref_pe_field *f,
                             const biref_pe_image_opts *opt, float *xyz)
{
    return render(s, sp, f, opt, 0, xyz);
}

biref_status biref_pe_render_prefiltered(const biref_pe_setup *s, const biref_spectral *sp, const biref_pe_field *f,
                                         const biref_pe_image_opts *opt, float *xyz)
{
    return render(s, sp, f, opt, 1, xyz);
}
