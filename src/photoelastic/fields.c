/* Closed-form plane-stress fields (docs/PHOTOELASTICITY.md, "Stress fields") and the plate
 * description that couples a field to its outline and picture frame. */
#include <math.h>
#include <string.h>

#include "biref/photoelastic.h"
#include "optics/validate.h"

void biref_pe_disk_stress(double R, double h, double P, double x, double y, biref_pe_stress *out)
{
    /* Each load is a Flamant point force on a half-plane: a purely radial stress
     * sigma_r = -2 P cos(theta) / (pi h r) about its load point, theta measured from the load's
     * line of action. For the load at (0, R) the radial unit vector is (x, y - R) / r1 and
     * cos theta = (R - y) / r1, so sigma = sigma_r n n^T gives the (R - y) x^2 / r1^4 ... terms
     * below; likewise at (0, -R). The two leave a uniform normal traction -P / (pi R h) on the
     * rim, which a uniform biaxial tension P / (pi R h) cancels (Frocht, Photoelasticity vol. 2,
     * ch. 4; Timoshenko & Goodier, Theory of Elasticity, sec. 41). At the centre this gives the
     * textbook sigma_xx = 2P / (pi D h), sigma_yy = -6P / (pi D h). */
    const double k = 2.0 * P / (M_PI * h);
    const double a = R - y, b = R + y;
    const double r1sq = x * x + a * a, r2sq = x * x + b * b;
    const double i1 = 1.0 / (r1sq * r1sq), i2 = 1.0 / (r2sq * r2sq);
    const double x2 = x * x, inv2R = 0.5 / R;
    out->sxx = -k * (a * x2 * i1 + b * x2 * i2 - inv2R);
    out->syy = -k * (a * a * a * i1 + b * b * b * i2 - inv2R);
    out->txy = k * (a * a * x * i1 - b * b * x * i2);
}

void biref_pe_kirsch_stress(double a, double S, double x, double y, biref_pe_stress *out)
{
    /* Kirsch (1898), in polar coordinates about the hole with theta from the load axis x:
     *   s_rr = S/2 (1 - a2) + S/2 (1 - 4 a2 + 3 a4) cos 2t
     *   s_tt = S/2 (1 + a2) - S/2 (1 + 3 a4) cos 2t
     *   t_rt = -S/2 (1 + 2 a2 - 3 a4) sin 2t,   a2 = a^2/r^2, a4 = a2^2
     * (Timoshenko & Goodier sec. 35), rotated to x, y with the double-angle formulas
     * sxx = (s_rr + s_tt)/2 + (s_rr - s_tt)/2 cos 2t - t_rt sin 2t, etc. cos 2t and sin 2t
     * come from x, y directly. s_tt(a, 90 deg) = 3 S: the stress concentration factor 3. */
    double r2 = x * x + y * y;
    if (r2 <= 0.0) r2 = a * a; /* the centre is inside the hole; any finite value will do */
    const double c2 = (x * x - y * y) / r2, s2 = 2.0 * x * y / r2;
    const double q2 = a * a / r2, q4 = q2 * q2, hs = 0.5 * S;
    const double srr = hs * (1.0 - q2) + hs * (1.0 - 4.0 * q2 + 3.0 * q4) * c2;
    const double stt = hs * (1.0 + q2) - hs * (1.0 + 3.0 * q4) * c2;
    const double trt = -hs * (1.0 + 2.0 * q2 - 3.0 * q4) * s2;
    const double mean = 0.5 * (srr + stt), half = 0.5 * (srr - stt);
    out->sxx = mean + half * c2 - trt * s2;
    out->syy = mean - half * c2 + trt * s2;
    out->txy = half * s2 + trt * c2;
}

void biref_pe_beam_stress(double H, double h, double M, double x, double y, biref_pe_stress *out)
{
    /* Euler-Bernoulli pure bending, exact in plane elasticity away from the load introduction
     * (Saint-Venant): sigma_xx = M y / I, I = h H^3 / 12, no other component. */
    (void)x;
    const double inertia = h * H * H * H / 12.0; /* second moment of area */
    out->sxx = M * y / inertia;
    out->syy = 0.0;
    out->txy = 0.0;
}

static int positive(double v) { return isfinite(v) && v > 0.0; }

/* The nominal stress of a load case stays within 1e12 Pa (1e6 MPa, a terapascal, the stress-grid
 * limit too): far beyond any plate in a polariscope, and low enough that stresses, retardations
 * and fringe orders stay finite everywhere. */
#define PE_MAX_NOMINAL_PA 1e12

static biref_status nominal_ok(double sigma, const char *what, char *msg, size_t msg_len)
{
    if (fabs(sigma) <= PE_MAX_NOMINAL_PA) return BIREF_OK;
    return biref_fail(msg, msg_len, "%s gives a nominal stress of %g MPa, beyond %g MPa", what, sigma / 1e6,
                      PE_MAX_NOMINAL_PA / 1e6);
}

static void base(biref_pe_field *f, biref_pe_field_kind kind, double h)
{
    memset(f, 0, sizeof *f);
    f->kind = kind;
    f->thickness = h;
}

biref_status biref_pe_field_disk(biref_pe_field *f, double R, double h, double P, char *msg, size_t msg_len)
{
    if (!positive(R)) return biref_fail(msg, msg_len, "disk radius must be positive");
    if (!positive(h)) return biref_fail(msg, msg_len, "thickness must be positive");
    if (!isfinite(P) || P < 0.0) return biref_fail(msg, msg_len, "load must be a finite compressive force >= 0");
    if (nominal_ok(P / (R * h), "load / (radius x thickness)", msg, msg_len)) return BIREF_ERR_INVALID;
    base(f, BIREF_PE_DISK, h);
    f->radius = R;
    f->load = P;
    const double m = 1.04 * R; /* a thin margin shows the rim against the background */
    f->frame[0] = -m;
    f->frame[1] = m;
    f->frame[2] = -m;
    f->frame[3] = m;
    return BIREF_OK;
}

biref_status biref_pe_field_hole(biref_pe_field *f, double a, double width, double height, double h, double S,
                                 double angle, char *msg, size_t msg_len)
{
    if (!positive(a)) return biref_fail(msg, msg_len, "hole radius must be positive");
    if (!positive(width) || !positive(height)) return biref_fail(msg, msg_len, "plate width and height must be positive");
    if (!(2.0 * a < width && 2.0 * a < height)) return biref_fail(msg, msg_len, "the hole must fit inside the plate");
    if (!positive(h)) return biref_fail(msg, msg_len, "thickness must be positive");
    if (!isfinite(S)) return biref_fail(msg, msg_len, "remote stress must be finite");
    if (nominal_ok(S, "remote stress", msg, msg_len)) return BIREF_ERR_INVALID;
    if (!isfinite(angle)) return biref_fail(msg, msg_len, "tension direction must be finite");
    base(f, BIREF_PE_HOLE, h);
    f->angle = angle;
    f->radius = a;
    f->stress = S;
    f->width = width;
    f->height = height;
    f->frame[0] = -0.5 * width;
    f->frame[1] = 0.5 * width;
    f->frame[2] = -0.5 * height;
    f->frame[3] = 0.5 * height;
    return BIREF_OK;
}

biref_status biref_pe_field_beam(biref_pe_field *f, double length, double H, double h, double M, char *msg,
                                 size_t msg_len)
{
    if (!positive(length)) return biref_fail(msg, msg_len, "beam length must be positive");
    if (!positive(H)) return biref_fail(msg, msg_len, "beam depth must be positive");
    if (!positive(h)) return biref_fail(msg, msg_len, "thickness must be positive");
    if (!isfinite(M)) return biref_fail(msg, msg_len, "bending moment must be finite");
    if (nominal_ok(6.0 * M / (h * H * H), "6 x moment / (thickness x depth^2)", msg, msg_len)) return BIREF_ERR_INVALID;
    base(f, BIREF_PE_BEAM, h);
    f->width = length;
    f->depth = H;
    f->moment = M;
    f->frame[0] = -0.5 * length;
    f->frame[1] = 0.5 * length;
    f->frame[2] = -0.75 * H;
    f->frame[3] = 0.75 * H;
    return BIREF_OK;
}

biref_status biref_pe_field_grid(biref_pe_field *f, const biref_pe_grid *g, double h, char *msg, size_t msg_len)
{
    if (!g) return biref_fail(msg, msg_len, "no grid");
    if (!positive(h)) return biref_fail(msg, msg_len, "thickness must be positive");
    base(f, BIREF_PE_GRID, h);
    f->grid = g;
    biref_pe_grid_bounds(g, f->frame);
    return BIREF_OK;
}

biref_status biref_pe_field_nodes(biref_pe_field *f, const biref_pe_mesh *m, double h, char *msg, size_t msg_len)
{
    if (!m) return biref_fail(msg, msg_len, "no nodes");
    if (!positive(h)) return biref_fail(msg, msg_len, "thickness must be positive");
    base(f, BIREF_PE_NODES, h);
    f->mesh = m;
    biref_pe_mesh_bounds(m, f->frame);
    return BIREF_OK;
}

int biref_pe_field_stress(const biref_pe_field *f, double x, double y, biref_pe_stress *out)
{
    biref_pe_stress s;
    switch (f->kind) {
    case BIREF_PE_DISK:
        if (x * x + y * y > f->radius * f->radius) return 0;
        biref_pe_disk_stress(f->radius, f->thickness, f->load, x, y, &s);
        break;
    case BIREF_PE_HOLE:
        if (x * x + y * y < f->radius * f->radius || fabs(x) > 0.5 * f->width || fabs(y) > 0.5 * f->height)
            return 0;
        if (f->angle == 0.0) {
            biref_pe_kirsch_stress(f->radius, f->stress, x, y, &s);
        } else {
            /* Kirsch in the frame of the tension (x' along it), then the tensor rotated back:
             * sigma = R sigma' R^T with R the rotation by the angle. */
            const double c = cos(f->angle), sn = sin(f->angle);
            biref_pe_stress r;
            biref_pe_kirsch_stress(f->radius, f->stress, c * x + sn * y, -sn * x + c * y, &r);
            s.sxx = r.sxx * c * c + r.syy * sn * sn - 2.0 * r.txy * sn * c;
            s.syy = r.sxx * sn * sn + r.syy * c * c + 2.0 * r.txy * sn * c;
            s.txy = (r.sxx - r.syy) * sn * c + r.txy * (c * c - sn * sn);
        }
        break;
    case BIREF_PE_BEAM:
        if (fabs(y) > 0.5 * f->depth || fabs(x) > 0.5 * f->width) return 0;
        biref_pe_beam_stress(f->depth, f->thickness, f->moment, x, y, &s);
        break;
    case BIREF_PE_GRID:
        if (!biref_pe_grid_stress(f->grid, x, y, &s)) return 0;
        break;
    case BIREF_PE_NODES:
        if (!biref_pe_mesh_stress(f->mesh, x, y, &s)) return 0;
        break;
    default: return 0;
    }
    /* The disk's load points are singular: no finite picture exists there. */
    if (!isfinite(s.sxx) || !isfinite(s.syy) || !isfinite(s.txy)) return 0;
    *out = s;
    return 1;
}
