/* Construction and validation of media. */
#include <math.h>
#include <stdio.h>

#include "biref/optics.h"
#include "optics/validate.h"

biref_medium biref_medium_isotropic(double eta)
{
    biref_medium m = {eta, eta, {0.0, 1.0, 0.0}, 1};
    return m;
}

biref_medium biref_medium_uniaxial(double eta_o, double eta_e, const double axis[3])
{
    biref_medium m = {eta_o, eta_e, {axis[0], axis[1], axis[2]}, 0};
    return m;
}

biref_status biref_medium_check(const biref_medium *m, char *msg, size_t msg_len)
{
    if (!m) return biref_fail(msg, msg_len, "medium is NULL");
    if (m->isotropic) return biref_check_index("eta", m->eta_o, msg, msg_len);
    biref_status s = biref_check_index("eta_o", m->eta_o, msg, msg_len);
    if (s == BIREF_OK) s = biref_check_index("eta_e", m->eta_e, msg, msg_len);
    if (s == BIREF_OK) s = biref_check_axis(m->axis, msg, msg_len);
    return s;
}
