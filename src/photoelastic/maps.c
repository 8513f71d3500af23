/* Full-field maps of a plate: fringe order, isoclinic angle, retardation and principal stresses
 * on the pixel grid of the pictures, NaN where there is no material. */
#include <math.h>
#include <omp.h>
#include <string.h>

#include "biref/photoelastic.h"
#include "error.h"

static const char *const NAMES[BIREF_PE_MAP_COUNT] = {"fringe-order", "isoclinic", "retardation", "sigma1", "sigma2"};
static const char *const UNITS[BIREF_PE_MAP_COUNT] = {"1", "deg", "nm", "MPa", "MPa"};

const char *biref_pe_map_name(biref_pe_map_kind k)
{
    return (unsigned)k < BIREF_PE_MAP_COUNT ? NAMES[k] : "?";
}

const char *biref_pe_map_unit(biref_pe_map_kind k)
{
    return (unsigned)k < BIREF_PE_MAP_COUNT ? UNITS[k] : "?";
}

biref_status biref_pe_map_from_name(const char *name, biref_pe_map_kind *out)
{
    for (int i = 0; name && i < BIREF_PE_MAP_COUNT; i++)
        if (!strcmp(name, NAMES[i])) {
            *out = (biref_pe_map_kind)i;
            return BIREF_OK;
        }
    return BIREF_ERR_INVALID;
}

double biref_pe_map_value(biref_pe_map_kind k, const biref_pe_setup *s, double lambda_nm, const biref_pe_principal *p)
{
    switch (k) {
    case BIREF_PE_MAP_FRINGE_ORDER: return biref_pe_retardation_at_nm(s, p, lambda_nm) / lambda_nm;
    case BIREF_PE_MAP_ISOCLINIC: return p->phi * (180.0 / M_PI);
    case BIREF_PE_MAP_RETARDATION: return biref_pe_retardation_nm(s, p);
    case BIREF_PE_MAP_SIGMA1: return p->s1 * 1e-6;
    case BIREF_PE_MAP_SIGMA2: return p->s2 * 1e-6;
    default: return NAN;
    }
}

biref_status biref_pe_render_map(const biref_pe_setup *s, const biref_pe_field *f, biref_pe_map_kind k,
                                 double lambda_nm, int width, int height, int threads, float *out, char *msg,
                                 size_t msg_len)
{
    if (!s || !f || !out) return biref_fail(msg, msg_len, "no setup, field or output");
    if (width < 1 || height < 1) return biref_fail(msg, msg_len, "%d x %d pixels: the map needs at least 1 x 1", width, height);
    if ((unsigned)k >= BIREF_PE_MAP_COUNT) return biref_fail(msg, msg_len, "unknown map (%d)", (int)k);
    if (!(lambda_nm > 0 && isfinite(lambda_nm)))
        return biref_fail(msg, msg_len, "wavelength %g nm: expected a positive number", lambda_nm);
    if (!(f->frame[1] > f->frame[0] && f->frame[3] > f->frame[2]))
        return biref_fail(msg, msg_len, "the field's frame is empty");
    const double x0 = f->frame[0], sx = (f->frame[1] - f->frame[0]) / width;
    const double y1 = f->frame[3], sy = (f->frame[3] - f->frame[2]) / height;
    const int nt = threads > 0 ? threads : omp_get_max_threads();
    /* Pixel centres, as the picture's 1 x 1 sampling: a map is data, not a filtered image. */
#pragma omp parallel for schedule(dynamic, 4) num_threads(nt)
    for (int j = 0; j < height; j++)
        for (int i = 0; i < width; i++) {
            biref_pe_stress st;
            float v = NAN;
            if (biref_pe_field_stress(f, x0 + (i + 0.5) * sx, y1 - (j + 0.5) * sy, &st)) {
                biref_pe_principal p;
                biref_pe_principal_of(&st, &p);
                v = (float)biref_pe_map_value(k, s, lambda_nm, &p);
            }
            out[(size_t)j * width + i] = v;
        }
    return BIREF_OK;
}
