/* The retardation footprint of a picture sample (pe_footprint.h). */
#include <math.h>

#include "photoelastic/pe_footprint.h"

/* Retardation at (x, y), as biref_pe_retardation_nm (s1 - s2 = |(sxx - syy, 2 txy)|) without the
 * principal direction, which the footprint does not need; 0 outside the material. */
static int retardation_at(const biref_pe_setup *s, const biref_pe_field *f, double x, double y, double *delta)
{
    biref_pe_stress st;
    if (!biref_pe_field_stress(f, x, y, &st)) return 0;
    const double dxy = st.sxx - st.syy, t2 = 2.0 * st.txy;
    *delta = s->material.C_per_Pa * sqrt(dxy * dxy + t2 * t2) * s->thickness * 1e9;
    return 1;
}

double biref_pe_retardation_footprint(const biref_pe_setup *s, const biref_pe_field *f, double x, double y, double hx,
                                      double hy, double delta_nm)
{
    const double step[2][2] = {{hx, 0.0}, {0.0, -hy}};
    double g2 = 0.0;
    for (int k = 0; k < 2; k++) {
        double d;
        if (retardation_at(s, f, x + step[k][0], y + step[k][1], &d) ||
            retardation_at(s, f, x - step[k][0], y - step[k][1], &d))
            g2 += (d - delta_nm) * (d - delta_nm);
    }
    /* Huge stresses can overflow the squares: a footprint of a metre of path averages every
     * fringe away, which is what such a sample shows anyway. */
    const double w = sqrt(g2);
    return w < 1e9 ? w : 1e9;
}
