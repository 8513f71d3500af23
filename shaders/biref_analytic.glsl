/* biref — the paper's analytic spectral integration (Steinberg 2019, §3-§5) in GLSL.
 *
 * One source for desktop GLSL (>= 4.30 core) and GLSL ES 3.00 (WebGL2). The loader prepends
 *   desktop:  #version 430 core
 *   WebGL2:   #version 300 es + precision highp float; precision highp int; precision highp sampler2D;
 * and then one of
 *   #define BIREF_VERTEX          the full-screen triangle (vertex stage)
 *   #define BIREF_FRAGMENT        the scene ray caster (fragment stage)
 * plus BIREF_MAX_SLABS / BIREF_MAX_PANELS (array sizes) and, for a display, BIREF_OUTPUT_SRGB
 * (8-bit sRGB out instead of linear XYZ). Without BIREF_SCENE only the per-hit-point part is
 * compiled: paste it into another renderer and call biref_shade_slab (docs/GPU.md); with
 * BIREF_MATERIALS also biref_shade_material (dispersive materials; two more samplers).
 *
 * Everything is single precision. Where double precision is needed on the CPU, the shader
 * computes differences directly instead of subtracting large numbers (docs/GPU.md):
 *   - q_e - q_o = (q_e^2 - q_o^2) / (q_e + q_o) with q_e^2 - q_o^2 proportional to Δε;
 *   - look-up-table phases are reduced to a node (carrier exported by the library) plus a
 *     rotation of at most one table step, so no cos/sin sees an argument above ~0.7 rad;
 *   - the asymptotic far-field phases are reduced to the nearest cycle before cos/sin.
 * Physics and corrections to the paper: docs/PHYSICS.md; frames: docs/SCENES.md.
 */

#ifdef BIREF_VERTEX
void main()
{
    /* One triangle covering the viewport: (-1,-1), (3,-1), (-1,3). */
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
#else

const float BIREF_PI = 3.14159265358979;

/* ------------------------------------------------------------------------------------------ */
/* Complex numbers as vec2 (re, im)                                                            */
/* ------------------------------------------------------------------------------------------ */
vec2 cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
vec2 cconj(vec2 a) { return vec2(a.x, -a.y); }
vec2 cinv(vec2 z) { float n = 1.0 / dot(z, z); return vec2(z.x * n, -z.y * n); }
/* conj(a) * b */
vec2 cmulc(vec2 a, vec2 b) { return vec2(a.x * b.x + a.y * b.y, a.x * b.y - a.y * b.x); }
float cabs2(vec2 z) { return dot(z, z); }
float cl1(vec2 z) { return abs(z.x) + abs(z.y); }
/* sqrt of a real number on the branch used for normal components: i sqrt(-d) when d < 0. */
vec2 csqrt_real(float d) { return d >= 0.0 ? vec2(sqrt(d), 0.0) : vec2(0.0, sqrt(-d)); }

/* ------------------------------------------------------------------------------------------ */
/* Look-up table of S(cos kD), S(sin kD) (paper §5.2), exported by the C library               */
/* ------------------------------------------------------------------------------------------ */
/* Texture rows 0-2: F_j(D) demodulated by the band centre, (re, im, dre/dD, dim/dD) at node m
 * (D = m * step); row 3: the carrier e^{2 pi i nu_c m step} (cos, sin). */
uniform highp sampler2D u_lut;
uniform vec4 u_lut_grid;     /* step (nm), nodes, d_max, d_far */
uniform vec4 u_lut_band;     /* nu_c (1/nm), lambda_min, lambda_max, unused */
uniform vec3 u_lut_edge_lo;  /* Λ_j(λmin) λmin^2: endpoint terms of the asymptotics */
uniform vec3 u_lut_edge_hi;
uniform vec3 u_k_centroid;   /* band centroids of 2 pi / λ */

/* e^{2 pi i x} with x reduced to the nearest cycle first (|angle| <= pi). */
vec2 cycles_exp(float x)
{
    float f = x - floor(x + 0.5);
    float a = 2.0 * BIREF_PI * f;
    return vec2(cos(a), sin(a));
}

/* Where 0 <= D <= d_max falls between the table's nodes: node m, the Hermite weights and the
 * carrier (the node's, exported in double precision, times a rotation below one step). */
struct TableNodes {
    int m;
    vec4 h; /* h00, step h10, h01, step h11 */
    vec2 carrier;
};

TableNodes table_nodes(float D)
{
    TableNodes tn;
    float step_nm = u_lut_grid.x;
    float x = D / step_nm;
    tn.m = min(int(x), int(u_lut_grid.y) - 2);
    float t = x - float(tn.m), t2 = t * t, t3 = t2 * t;
    tn.h = vec4(2.0 * t3 - 3.0 * t2 + 1.0, step_nm * (t3 - 2.0 * t2 + t), -2.0 * t3 + 3.0 * t2, step_nm * (t3 - t2));
    vec2 node = texelFetch(u_lut, ivec2(tn.m, 3), 0).xy;
    float a = 2.0 * BIREF_PI * u_lut_band.x * (D - float(tn.m) * step_nm);
    tn.carrier = cmul(node, vec2(cos(a), sin(a)));
    return tn;
}

/* One band's value from its texels (re, im, dre/dD, dim/dD) at nodes m and m + 1. */
vec2 table_value(TableNodes tn, vec4 A, vec4 B)
{
    return cmul(tn.carrier, tn.h.x * A.xy + tn.h.y * A.zw + tn.h.z * B.xy + tn.h.w * B.zw);
}

/* The first moment in k of the same, S(k e^{ikD}) = -i d/dD S(e^{ikD}): the carrier times
 * (2 pi nu_c F - i F') (spectral_table_eval_moment). */
vec2 table_moment(TableNodes tn, float D, vec4 A, vec4 B)
{
    float step_nm = u_lut_grid.x, t = D / step_nm - float(tn.m), t2 = t * t;
    float g00 = (6.0 * t2 - 6.0 * t) / step_nm, g10 = 3.0 * t2 - 4.0 * t + 1.0, g11 = 3.0 * t2 - 2.0 * t;
    vec2 F = tn.h.x * A.xy + tn.h.y * A.zw + tn.h.z * B.xy + tn.h.w * B.zw;
    vec2 dF = g00 * A.xy + g10 * A.zw - g00 * B.xy + g11 * B.zw;
    float kc = 2.0 * BIREF_PI * u_lut_band.x;
    return cmul(tn.carrier, vec2(kc * F.x + dF.y, kc * F.y - dF.x));
}

/* S(cos(2 pi D / λ), Λ_j) and S(sin(...)) for the three bands. */
void biref_phase_integrals(float D, out vec3 c, out vec3 s)
{
    float sgn = 1.0;
    if (D < 0.0) {
        D = -D;
        sgn = -1.0; /* cos even, sin odd */
    }
    c = vec3(0.0);
    s = vec3(0.0);
    float d_max = u_lut_grid.z, d_far = u_lut_grid.w;
    if (D > d_far) return;
    if (D > d_max) {
        /* Endpoint asymptotics: S(e^{ikD}) ~ i/(2 pi D) [Λ λ^2 e^{2 pi i D/λ}] from λmin to λmax. */
        vec2 hi = cycles_exp(D / u_lut_band.z), lo = cycles_exp(D / u_lut_band.y);
        float e = 1.0 / (2.0 * BIREF_PI * D);
        /* i e (edge_hi hi - edge_lo lo) */
        vec3 re = u_lut_edge_hi * hi.x - u_lut_edge_lo * lo.x;
        vec3 im = u_lut_edge_hi * hi.y - u_lut_edge_lo * lo.y;
        c = -e * im;
        s = sgn * e * re;
        return;
    }
    TableNodes tn = table_nodes(D);
    vec3 fre, fim;
    for (int j = 0; j < 3; j++) {
        vec2 v = table_value(tn, texelFetch(u_lut, ivec2(tn.m, j), 0), texelFetch(u_lut, ivec2(tn.m + 1, j), 0));
        fre[j] = v.x;
        fim[j] = v.y;
    }
    c = fre;
    s = sgn * fim;
}

struct PhaseInt {
    vec3 c, s, att; /* S(cos kD), S(sin kD), e^{-k_j Im D} per band */
};

/* opd: complex optical path difference; re_opd: its real part computed without cancellation. */
PhaseInt phase_eval(float re_opd, float im_opd)
{
    PhaseInt p;
    biref_phase_integrals(re_opd, p.c, p.s);
    p.att = im_opd != 0.0 ? exp(-u_k_centroid * im_opd) : vec3(1.0);
    return p;
}

/* h += w * S(Re(coef e^{ikD})) = w (Re coef S(cos) - Im coef S(sin)) */
void add_re(inout vec3 h, vec3 w, vec2 coef, PhaseInt p) { h += w * p.att * (coef.x * p.c - coef.y * p.s); }

vec3 leg_energy(vec2 opl) { return opl.y != 0.0 ? exp(-2.0 * u_k_centroid * opl.y) : vec3(1.0); }

/* ------------------------------------------------------------------------------------------ */
/* Modes (paper §3, eqs. 2-3 corrected, docs/PHYSICS.md §1)                                    */
/* ------------------------------------------------------------------------------------------ */
/* Mode order: 0 o/s down, 1 e/p down, 2 o/s up, 3 e/p up. E[3 * mode + component]. */
struct Modes {
    vec2 q[4];
    vec2 E[12];
    vec2 dq_down, dq_up; /* q_e - q_o, computed without cancellation */
};

void iso_normal(float eps, float K, out vec2 qd, out vec2 qu)
{
    vec2 r = csqrt_real(eps - K * K);
    qd = -r;
    qu = r;
}

/* s = x and p = k x s / |k| (degenerate direction or isotropic medium). */
void sp_fields(inout Modes m, int io, int ie, vec2 q, float K, float eta)
{
    m.E[3 * io] = vec2(1.0, 0.0);
    m.E[3 * io + 1] = vec2(0.0);
    m.E[3 * io + 2] = vec2(0.0);
    m.E[3 * ie] = vec2(0.0);
    m.E[3 * ie + 1] = vec2(-K / eta, 0.0);
    m.E[3 * ie + 2] = -q / eta;
}

Modes isotropic_modes(float eta, float K)
{
    Modes m;
    vec2 qd, qu;
    iso_normal(eta * eta, K, qd, qu);
    m.q[0] = qd;
    m.q[1] = qd;
    m.q[2] = qu;
    m.q[3] = qu;
    sp_fields(m, 0, 1, qd, K, eta);
    sp_fields(m, 2, 3, qu, K, eta);
    m.dq_down = vec2(0.0);
    m.dq_up = vec2(0.0);
    return m;
}

float herm_norm3(vec2 a, vec2 b, vec2 c) { return sqrt(dot(a, a) + dot(b, b) + dot(c, c)); }

/* Below this relative size E_o = -k x A is taken as zero (k parallel to A). Single precision:
 * the C library's 1e-9 would be rounding noise here. */
const float DEGENERATE_REL = 1e-4;

Modes uniaxial_modes(float eta_o, float eta_e, vec3 A, float K)
{
    Modes m;
    float al = A.x, be = A.y, ga = A.z;
    float eo = eta_o * eta_o, ee = eta_e * eta_e, de = ee - eo;
    vec2 qod, qou;
    iso_normal(eo, K, qod, qou);
    float a = eo + be * be * de;
    float disc = ee * (eo + be * be * de) + K * K * (al * al * de - ee);
    vec2 root = csqrt_real(eo * disc);
    vec2 lin = vec2(be * ga * K * de, 0.0);
    m.q[0] = qod;
    m.q[2] = qou;
    m.q[1] = (lin - root) / a;
    m.q[3] = (lin + root) / a;
    for (int dir = 0; dir < 2; dir++) {
        int io = dir == 1 ? 2 : 0, ie = dir == 1 ? 3 : 1;
        vec2 qo = m.q[io], qe = m.q[ie];
        /* eq. 3: E_o = -k x A */
        vec2 Eo0 = -be * K * vec2(1.0, 0.0) - ga * qo, Eo1 = vec2(al * K, 0.0), Eo2 = al * qo;
        float scale_o = sqrt(cabs2(qo) + K * K);
        float no = herm_norm3(Eo0, Eo1, Eo2);
        /* eq. 3: E_e = eps_o A - (A.k) k */
        vec2 ak = be * qe - vec2(ga * K, 0.0);
        vec2 Ee0 = vec2(eo * al, 0.0), Ee1 = vec2(eo * be, 0.0) - cmul(ak, qe), Ee2 = vec2(eo * ga, 0.0) + ak * K;
        float ne = herm_norm3(Ee0, Ee1, Ee2);
        /* q_e^2 - q_o^2 = Δε (2 β γ K q_e + ε_o (1 - β^2) + K^2 (β^2 - γ^2)) / a, from the two
         * dispersion relations: no cancellation, unlike q_e - q_o (docs/GPU.md). */
        vec2 sum = qe + qo;
        vec2 dq = qe - qo;
        if (cabs2(sum) > 1e-8 * eo) {
            vec2 num = de * (2.0 * be * ga * K * qe + vec2(eo * (1.0 - be * be) + K * K * (be * be - ga * ga), 0.0)) / a;
            dq = cmul(num, cinv(sum));
        }
        if (no <= DEGENERATE_REL * (scale_o > 0.0 ? scale_o : 1.0) || ne <= DEGENERATE_REL * eo) {
            sp_fields(m, io, ie, qo, K, eta_o);
            m.q[ie] = qo;
            dq = vec2(0.0);
        } else {
            m.E[3 * io] = Eo0 / no;
            m.E[3 * io + 1] = Eo1 / no;
            m.E[3 * io + 2] = Eo2 / no;
            m.E[3 * ie] = Ee0 / ne;
            m.E[3 * ie + 1] = Ee1 / ne;
            m.E[3 * ie + 2] = Ee2 / ne;
        }
        if (dir == 0)
            m.dq_down = dq;
        else
            m.dq_up = dq;
    }
    return m;
}

/* ------------------------------------------------------------------------------------------ */
/* Interfaces: continuity of E_x, E_z, H_x, H_z as a 4x4 complex system (docs/PHYSICS.md §2)   */
/* ------------------------------------------------------------------------------------------ */
/* Each 2x2 matrix is [incident mode][outgoing mode] at index 2 i + j. */
struct Iface {
    vec2 rd[4], td[4], ru[4], tu[4];
};

/* (E_x, E_z, H_x, H_z) with H = k x E, k = (0, q, -K). */
void tangential(Modes m, int i, float K, out vec2 f[4])
{
    vec2 q = m.q[i], Ex = m.E[3 * i], Ey = m.E[3 * i + 1], Ez = m.E[3 * i + 2];
    f[0] = Ex;
    f[1] = Ez;
    f[2] = cmul(q, Ez) + K * Ey;
    f[3] = -cmul(q, Ex);
}

/* Gaussian elimination with partial pivoting, A X = B for four right-hand sides (row-major). */
bool solve4(inout vec2 A[16], inout vec2 B[16])
{
    float scale = 0.0;
    for (int i = 0; i < 16; i++) scale = max(scale, cl1(A[i]));
    vec2 invd[4];
    bool singular = false;
    for (int c = 0; c < 4; c++) {
        int p = c;
        float best = cl1(A[5 * c]);
        for (int r = c + 1; r < 4; r++) {
            float v = cl1(A[4 * r + c]);
            if (v > best) {
                best = v;
                p = r;
            }
        }
        /* No early return: inlined into the loops of the exact integrals, a return from inside
         * this loop broke the enclosing loop under Mesa (llvmpipe 22.3). */
        if (!(best > 1e-7 * scale)) singular = true;
        if (p != c) {
            for (int j = 0; j < 4; j++) {
                vec2 t = A[4 * c + j];
                A[4 * c + j] = A[4 * p + j];
                A[4 * p + j] = t;
                t = B[4 * c + j];
                B[4 * c + j] = B[4 * p + j];
                B[4 * p + j] = t;
            }
        }
        vec2 inv = cinv(A[5 * c]);
        invd[c] = inv;
        for (int r = c + 1; r < 4; r++) {
            vec2 f = cmul(A[4 * r + c], inv);
            for (int j = c; j < 4; j++) A[4 * r + j] -= cmul(f, A[4 * c + j]);
            for (int j = 0; j < 4; j++) B[4 * r + j] -= cmul(f, B[4 * c + j]);
        }
    }
    for (int c = 3; c >= 0; c--) {
        for (int j = 0; j < 4; j++) {
            vec2 s = B[4 * c + j];
            for (int k = c + 1; k < 4; k++) s -= cmul(A[4 * c + k], B[4 * k + j]);
            B[4 * c + j] = cmul(s, invd[c]);
        }
    }
    return !singular;
}

bool interface_from_modes(Modes up, Modes lo, float K, out Iface o)
{
    vec2 A[16], B[16], f[4];
    for (int j = 0; j < 2; j++) {
        tangential(up, 2 + j, K, f);
        for (int r = 0; r < 4; r++) A[4 * r + j] = f[r];
        tangential(lo, j, K, f);
        for (int r = 0; r < 4; r++) A[4 * r + 2 + j] = -f[r];
    }
    for (int i = 0; i < 2; i++) {
        tangential(up, i, K, f); /* incident from above */
        for (int r = 0; r < 4; r++) B[4 * r + i] = -f[r];
        tangential(lo, 2 + i, K, f); /* incident from below */
        for (int r = 0; r < 4; r++) B[4 * r + 2 + i] = f[r];
    }
    bool ok = solve4(A, B);
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            o.rd[2 * i + j] = B[4 * j + i];
            o.td[2 * i + j] = B[4 * (2 + j) + i];
            o.tu[2 * i + j] = B[4 * j + 2 + i];
            o.ru[2 * i + j] = B[4 * (2 + j) + 2 + i];
        }
    return ok;
}

/* ------------------------------------------------------------------------------------------ */
/* Slab (paper §4): interfaces and the optical paths of the four leg types                     */
/* ------------------------------------------------------------------------------------------ */
struct SlabState {
    Iface top, bot;
    vec2 od[2], ou[2]; /* optical path of a down / up leg, [o, e], nm (complex when evanescent) */
    float dd, du;      /* Re(od[e] - od[o]), Re(ou[e] - ou[o]) without cancellation */
};

/* axis: unit optic axis in the paper frame of the ray; sin_theta of the incidence angle. */
bool slab_prepare(float eta_o, float eta_e, vec3 axis, float d_nm, float eta_i, float sin_theta, out SlabState st)
{
    float K = eta_i * sin_theta; /* eq. 1 */
    Modes amb = isotropic_modes(eta_i, K);
    Modes sl = uniaxial_modes(eta_o, eta_e, axis, K);
    bool ok = interface_from_modes(amb, sl, K, st.top);
    ok = interface_from_modes(sl, amb, K, st.bot) && ok;
    /* Each leg gains k0 (-q_down) d or k0 q_up d (docs/PHYSICS.md §3). */
    st.od[0] = -sl.q[0] * d_nm;
    st.od[1] = -sl.q[1] * d_nm;
    st.ou[0] = sl.q[2] * d_nm;
    st.ou[1] = sl.q[3] * d_nm;
    st.dd = -sl.dq_down.x * d_nm;
    st.du = sl.dq_up.x * d_nm;
    return ok;
}

/* The same slab lit from its other face (biref_slab_state_flip): relabel, do not solve again. */
SlabState slab_flip(SlabState s)
{
    SlabState o;
    o.top.rd = s.bot.ru;
    o.top.td = s.bot.tu;
    o.top.ru = s.bot.rd;
    o.top.tu = s.bot.td;
    o.bot.rd = s.top.ru;
    o.bot.td = s.top.tu;
    o.bot.ru = s.top.rd;
    o.bot.tu = s.top.td;
    o.od = s.ou;
    o.ou = s.od;
    o.dd = s.du;
    o.du = s.dd;
    return o;
}

/* ------------------------------------------------------------------------------------------ */
/* Analytic spectral integration (paper §5, eqs. 19-26 with m = 1)                             */
/* ------------------------------------------------------------------------------------------ */
/* Polarisation is general: incident coherency matrix C (real symmetric, (C00, C01, C11)) in the
 * incident wave's (s, p) basis and analyzer P (real, [in][out] = (P00, P01, P10, P11)) in the
 * outgoing wave's basis. For the paper's model C = diag(s, p), P = diag(sqrt(mask)) and every term
 * below equals the C library's biref_analytic_terms mixed by biref_spectrum_mix: the pair
 * coefficients factor into an entry part Ein (paths share their first leg's input) and an exit
 * part Xout (docs/GPU.md). */

/* Ein[2a + b] = sum_ij C_ij t[i][b] conj(t[j][a]) */
void entry_matrix(vec3 C, vec2 t[4], out vec2 Ein[4])
{
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++)
            Ein[2 * a + b] = C.x * cmulc(t[a], t[b]) + C.y * (cmulc(t[2 + a], t[b]) + cmulc(t[a], t[2 + b])) +
                             C.z * cmulc(t[2 + a], t[2 + b]);
}

/* TP = t P; Xout[2a + b] = sum_o TP[b][o] conj(TP[a][o]) */
void exit_matrix(vec2 t[4], vec4 P, out vec2 TP[4], out vec2 Xout[4])
{
    for (int x = 0; x < 2; x++) {
        TP[2 * x] = t[2 * x] * P.x + t[2 * x + 1] * P.z;
        TP[2 * x + 1] = t[2 * x] * P.y + t[2 * x + 1] * P.w;
    }
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) Xout[2 * a + b] = cmulc(TP[2 * a], TP[2 * b]) + cmulc(TP[2 * a + 1], TP[2 * b + 1]);
}

/* Energies of all paths arriving at a reflection point (eqs. 20-21): w (I - Dbar)^{-1} per band,
 * Dbar[m][m2] = sum_n |Rin[m][n]|^2 e_mid[n] |Rout[n][m2]|^2 e_end[m2]. */
void path_energies(vec3 w0[2], vec2 Rin[4], vec3 e_mid[2], vec2 Rout[4], vec3 e_end[2], out vec3 W[2])
{
    vec3 D[4];
    for (int m = 0; m < 2; m++)
        for (int m2 = 0; m2 < 2; m2++)
            D[2 * m + m2] = (cabs2(Rin[2 * m]) * e_mid[0] * cabs2(Rout[m2]) +
                             cabs2(Rin[2 * m + 1]) * e_mid[1] * cabs2(Rout[2 + m2])) * e_end[m2];
    vec3 a = 1.0 - D[0], b = -D[1], c = -D[2], d = 1.0 - D[3];
    vec3 det = a * d - b * c;
    W[0] = (w0[0] * d - w0[1] * c) / det;
    W[1] = (-w0[0] * b + w0[1] * a) / det;
}

/* Table look-ups of one direction, shared by every polarisation form. Transmission: the order-0
 * pair and the four round trips (bottom reflection into y, up, top reflection into x2). */
struct TransPhases {
    PhaseInt h0, trip[4], e2[3]; /* e2[m + 1]: 2 dd + m du, the entry pairs' lags beyond pair's */
};

TransPhases transmission_phases(SlabState st)
{
    TransPhases ph;
    ph.h0 = phase_eval(st.dd, st.od[1].y + st.od[0].y);
    for (int y = 0; y < 2; y++)
        for (int x2 = 0; x2 < 2; x2++) {
            vec2 trip = st.ou[y] + st.od[x2];
            ph.trip[2 * y + x2] = phase_eval(trip.x, trip.y);
        }
    for (int m = 0; m < 3; m++) ph.e2[m] = phase_eval(2.0 * st.dd + float(m - 1) * st.du, 0.0);
    return ph;
}

/* Transmission, S(|e J P|^2) = E + 2H for light entering through top and leaving through bot;
 * pair: reflection's order-1 pairs (ReflPhases), whose lags the siblings share. */
void transmission_terms(SlabState st, TransPhases ph, PhaseInt pair[6], vec3 C, vec4 P, out vec3 E, out vec3 H)
{
    vec2 Ein[4], TP[4], Xout[4];
    entry_matrix(C, st.top.td, Ein);
    exit_matrix(st.bot.td, P, TP, Xout);
    vec3 ed[2], eu[2], w0[2], W[2];
    for (int m = 0; m < 2; m++) {
        ed[m] = leg_energy(st.od[m]);
        eu[m] = leg_energy(st.ou[m]);
        w0[m] = Ein[3 * m].x * ed[m];
    }
    path_energies(w0, st.bot.rd, eu, st.top.ru, ed, W);
    E = W[0] * Xout[0].x + W[1] * Xout[3].x;
    H = vec3(0.0);
    /* H0 (eq. 24): the ordinary and the extraordinary order-0 path. */
    add_re(H, vec3(1.0), cmul(Ein[1], Xout[1]), ph.h0);
    /* Descendants (eq. 23, m = 1): one more round trip. */
    for (int y = 0; y < 2; y++)
        for (int x2 = 0; x2 < 2; x2++)
            for (int x = 0; x < 2; x++)
                add_re(H, W[x], cmul(cmul(st.bot.rd[2 * x + y], st.top.ru[2 * y + x2]), Xout[2 * x + x2]),
                       ph.trip[2 * y + x2]);
    /* Siblings (analytic.c): from the bottom in mode x, two last round trips a < b
     * (a = (down x2, up y)), with the lags of reflection's order-1 pairs (k as there). */
    int k = 0;
    for (int a = 0; a < 4; a++)
        for (int b = a + 1; b < 4; b++) {
            int xa = a / 2, ya = a - 2 * xa, xb = b / 2, yb = b - 2 * xb;
            for (int x = 0; x < 2; x++) {
                vec2 ca = cmul(st.bot.rd[2 * x + ya], st.top.ru[2 * ya + xa]);
                vec2 cb = cmul(st.bot.rd[2 * x + yb], st.top.ru[2 * yb + xb]);
                add_re(H, W[x], cmul(cmulc(ca, cb), Xout[2 * xa + xb]), pair[k]);
            }
            k++;
        }
    /* The order-1 paths whose entry legs differ, (o, a) and (e, b): lag kk dd + m du with
     * kk = 1 + x_b - x_a, m = y_b - y_a (analytic.c's biref_entry_pairs). */
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++) {
            int xa = a / 2, ya = a - 2 * xa, xb = b / 2, yb = b - 2 * xb;
            int kk = 1 + xb - xa, m = yb - ya;
            PhaseInt p = pair[0]; /* kk = 0: +-du, or 0 */
            if (kk == 2) {
                p = ph.e2[m + 1];
            } else if (kk == 1) {
                if (m == 0)
                    p = ph.h0;
                else if (m > 0)
                    p = pair[2];
                else
                    p = pair[3];
            } else {
                p.s *= float(m);
                if (m == 0) p.c = vec3(1.0);
            }
            float im = st.od[0].y + st.od[xa].y + st.ou[ya].y + st.od[1].y + st.od[xb].y + st.ou[yb].y;
            p.att = im != 0.0 ? exp(-u_k_centroid * im) : vec3(1.0);
            vec2 ca = cmul(st.bot.rd[ya], st.top.ru[2 * ya + xa]);
            vec2 cb = cmul(st.bot.rd[2 + yb], st.top.ru[2 * yb + xb]);
            add_re(H, vec3(1.0), cmul(cmul(Ein[1], cmulc(ca, cb)), Xout[2 * xa + xb]), p);
        }
}

/* Reflection: the four order-1 paths a = (down x, up y) and their six pairwise differences. */
struct ReflPhases {
    PhaseInt p1[4], pair[6];
};

ReflPhases reflection_phases(SlabState st)
{
    ReflPhases ph;
    for (int a = 0; a < 4; a++) {
        int x = a / 2, y = a - 2 * x;
        vec2 opl = st.od[x] + st.ou[y];
        ph.p1[a] = phase_eval(opl.x, opl.y);
    }
    int k = 0;
    for (int a = 0; a < 4; a++)
        for (int b = a + 1; b < 4; b++) {
            int xa = a / 2, ya = a - 2 * xa, xb = b / 2, yb = b - 2 * xb;
            float re = float(xb - xa) * st.dd + float(yb - ya) * st.du;
            float im = st.od[xb].y + st.od[xa].y + st.ou[yb].y + st.ou[ya].y;
            ph.pair[k++] = phase_eval(re, im);
        }
    return ph;
}

/* Reflection: the direct reflection, the four order-1 paths and their descendants. */
void reflection_terms(SlabState st, ReflPhases ph, vec3 C, vec4 P, out vec3 E, out vec3 H)
{
    vec2 Ein[4], UP[4], Xout[4], RP[4], dummy[4];
    entry_matrix(C, st.top.td, Ein);
    exit_matrix(st.top.tu, P, UP, Xout);
    exit_matrix(st.top.rd, P, RP, dummy);
    vec3 ed[2], eu[2], u0[2], U[2];
    for (int m = 0; m < 2; m++) {
        ed[m] = leg_energy(st.od[m]);
        eu[m] = leg_energy(st.ou[m]);
    }
    for (int y = 0; y < 2; y++)
        u0[y] = (Ein[0].x * ed[0] * cabs2(st.bot.rd[y]) + Ein[3].x * ed[1] * cabs2(st.bot.rd[2 + y])) * eu[y];
    path_energies(u0, st.top.ru, ed, st.bot.rd, eu, U);
    /* Direct reflection energy sum_ij C_ij sum_o RP[i][o] conj(RP[j][o]). */
    float e0 = C.x * (cabs2(RP[0]) + cabs2(RP[1])) + C.z * (cabs2(RP[2]) + cabs2(RP[3])) +
               2.0 * C.y * (cmulc(RP[2], RP[0]).x + cmulc(RP[3], RP[1]).x);
    E = vec3(e0) + U[0] * Xout[0].x + U[1] * Xout[3].x;
    H = vec3(0.0);
    /* Q[2j + y] = sum_o UP[y][o] conj(RP[j][o]) */
    vec2 Q[4];
    for (int j = 0; j < 2; j++)
        for (int y = 0; y < 2; y++) Q[2 * j + y] = cmulc(RP[2 * j], UP[2 * y]) + cmulc(RP[2 * j + 1], UP[2 * y + 1]);
    for (int a = 0; a < 4; a++) {
        int x = a / 2, y = a - 2 * x;
        /* direct x order-1: sum_ij C_ij t01[i][x] r12[x][y] Q[j][y] */
        vec2 ti0 = st.top.td[x], ti1 = st.top.td[2 + x];
        vec2 c = C.x * cmul(ti0, Q[y]) + C.y * (cmul(ti0, Q[2 + y]) + cmul(ti1, Q[y])) + C.z * cmul(ti1, Q[2 + y]);
        add_re(H, vec3(1.0), cmul(st.bot.rd[2 * x + y], c), ph.p1[a]);
    }
    int k = 0;
    for (int a = 0; a < 4; a++)
        for (int b = a + 1; b < 4; b++) {
            int xa = a / 2, ya = a - 2 * xa, xb = b / 2, yb = b - 2 * xb;
            vec2 c = cmul(cmulc(st.bot.rd[2 * xa + ya], st.bot.rd[2 * xb + yb]), cmul(Ein[2 * xa + xb], Xout[2 * ya + yb]));
            add_re(H, vec3(1.0), c, ph.pair[k++]);
        }
    /* Descendants: a path arriving at the top in up mode y, one more round trip (x', y'). */
    for (int y = 0; y < 2; y++)
        for (int a = 0; a < 4; a++) {
            int x = a / 2, y2 = a - 2 * x;
            add_re(H, U[y], cmul(cmul(st.top.ru[2 * y + x], st.bot.rd[2 * x + y2]), Xout[2 * y + y2]), ph.p1[a]);
        }
}

/* ------------------------------------------------------------------------------------------ */
/* Keeping the result physical (biref_physical_limit, src/spectral/analytic.c)                 */
/* ------------------------------------------------------------------------------------------ */
/* X[4 d + 2 i + o], E likewise: direction d (0 T, 1 R), input i, output o (s/p).
 * 1. Per direction and input: X - E scaled towards E (one factor for bands and outputs) until
 *    every entry is >= 0. 2. Per input and band: divided by sum over outputs and directions. */
void physical_limit(vec3 E[8], inout vec3 X[8])
{
    for (int d = 0; d < 2; d++)
        for (int i = 0; i < 2; i++) {
            float s = 1.0;
            for (int o = 0; o < 2; o++) {
                int n = 4 * d + 2 * i + o;
                for (int j = 0; j < 3; j++)
                    if (X[n][j] < 0.0) s = min(s, E[n][j] > 0.0 ? E[n][j] / (E[n][j] - X[n][j]) : 0.0);
            }
            if (s < 1.0)
                for (int o = 0; o < 2; o++) {
                    int n = 4 * d + 2 * i + o;
                    X[n] = E[n] + s * (X[n] - E[n]);
                }
        }
    for (int i = 0; i < 2; i++) {
        vec3 sum = X[2 * i] + X[2 * i + 1] + X[4 + 2 * i] + X[4 + 2 * i + 1];
        for (int j = 0; j < 3; j++) {
            if (!(sum[j] > 0.0)) continue;
            for (int d = 0; d < 2; d++)
                for (int o = 0; o < 2; o++) X[4 * d + 2 * i + o][j] /= sum[j];
        }
    }
}

/* ------------------------------------------------------------------------------------------ */
/* The coherent regime (src/spectral/coherent.c): exact integral of eq. 17                     */
/* ------------------------------------------------------------------------------------------ */
/* Thin slabs (round trips shorter than the band's coherence) and evanescent legs that couple the
 * faces: the path picture fails, so the closed form is integrated with a midpoint plan of the
 * library (48 * 2^i samples). Constants as in src/spectral/coherent.c. */
uniform highp sampler2D u_plans; /* texel n: (lambda_nm, w_x, w_y, w_z), plan i from 48 (2^i - 1) */
uniform vec4 u_plan_grid;        /* texture width, number of plans, samples of plan 0, rows per slab of u_material */
const float EVANESCENT_COUPLING = 1e-7;
const float COHERENT_ROUND_TRIP_NM = 10000.0;
const float ORDER_AMPLITUDE_FLOOR = 1e-4;
const float SAMPLES_PER_PERIOD = 8.0;
const float MIN_SAMPLES = 48.0;

/* Largest row sum of |D| (round trip) with each leg's decay at wavenumber k. */
float round_trip_norm(SlabState st, float k)
{
    float pd[2], pu[2], worst = 0.0;
    for (int m = 0; m < 2; m++) {
        pd[m] = exp(-k * st.od[m].y);
        pu[m] = exp(-k * st.ou[m].y);
    }
    for (int x = 0; x < 2; x++) {
        float row = 0.0;
        for (int x2 = 0; x2 < 2; x2++) {
            vec2 d = vec2(0.0);
            for (int y = 0; y < 2; y++) d += pd[x] * pu[y] * cmul(st.bot.rd[2 * x + y], st.top.ru[2 * y + x2]);
            row += length(d);
        }
        worst = max(worst, row);
    }
    return worst;
}

/* Number of samples of the plan that integrates this slab state exactly
 * (biref_resolving_plan). */
int plan_samples(SlabState st)
{
    float lmin = u_lut_band.y, lmax = u_lut_band.z, k_lo = 2.0 * BIREF_PI / lmax;
    float rt_max = 0.0;
    for (int x = 0; x < 2; x++)
        for (int y = 0; y < 2; y++) rt_max = max(rt_max, abs(st.od[x].x + st.ou[y].x));
    float rho = round_trip_norm(st, k_lo), orders;
    if (!(rho < 1.0 - 1e-7))
        orders = 1e9;
    else
        orders = rho <= ORDER_AMPLITUDE_FLOOR ? 1.0 : ceil(log(ORDER_AMPLITUDE_FLOOR) / log(rho));
    float opd = abs(st.dd) + abs(st.du) + orders * rt_max;
    float need = SAMPLES_PER_PERIOD * opd * (lmax - lmin) / (lmin * lmin) + MIN_SAMPLES;
    int n = int(u_plan_grid.z + 0.5);
    int plans = int(u_plan_grid.y + 0.5);
    for (int p = 1; p < 16; p++) {
        if (p >= plans || float(n) >= need) break;
        n *= 2;
    }
    return n;
}

/* Is this slab state in the coherent regime (biref_coherent_plan)? */
bool coherent_regime(SlabState st)
{
    float k_lo = 2.0 * BIREF_PI / u_lut_band.z;
    bool coupled = false;
    for (int m = 0; m < 2; m++) {
        float im_d = st.od[m].y, im_u = st.ou[m].y;
        if ((im_d != 0.0 && exp(-k_lo * abs(im_d)) > EVANESCENT_COUPLING) ||
            (im_u != 0.0 && exp(-k_lo * abs(im_u)) > EVANESCENT_COUPLING))
            coupled = true;
    }
    float rt_min = 1e30;
    for (int x = 0; x < 2; x++)
        for (int y = 0; y < 2; y++) {
            vec2 rt = st.od[x] + st.ou[y];
            if (exp(-k_lo * abs(rt.y)) > EVANESCENT_COUPLING) rt_min = min(rt_min, abs(rt.x));
        }
    return coupled || rt_min < COHERENT_ROUND_TRIP_NM;
}

/* e^{2 pi i opl / lambda} for a complex optical path, the cycles reduced before cos/sin. */
vec2 leg_phase(vec2 opl, float lambda)
{
    return exp(-2.0 * BIREF_PI * opl.y / lambda) * cycles_exp(opl.x / lambda);
}

/* 2x2 complex products, row-vector convention ([from][to]). */
void c2mul(vec2 A[4], vec2 B[4], out vec2 O[4])
{
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 2; k++) O[2 * i + k] = cmul(A[2 * i], B[k]) + cmul(A[2 * i + 1], B[2 + k]);
}

/* sum_ij C_ij sum_o (J P)[i][o] conj((J P)[j][o]) */
float detected(vec2 J[4], vec3 C, vec4 P)
{
    vec2 JP[4];
    for (int i = 0; i < 2; i++) {
        JP[2 * i] = J[2 * i] * P.x + J[2 * i + 1] * P.z;
        JP[2 * i + 1] = J[2 * i] * P.y + J[2 * i + 1] * P.w;
    }
    return C.x * (cabs2(JP[0]) + cabs2(JP[1])) + C.z * (cabs2(JP[2]) + cabs2(JP[3])) +
           2.0 * C.y * (cmulc(JP[2], JP[0]).x + cmulc(JP[3], JP[1]).x);
}

/* The closed form (eq. 17 and its reflection analogue) for one direction at one wavelength:
 * the detected intensity. */
float coherent_detected(SlabState st, int which, vec3 C, vec4 P, float lambda)
{
    vec2 pd[2], pu[2];
    for (int m = 0; m < 2; m++) {
        pd[m] = leg_phase(st.od[m], lambda);
        pu[m] = leg_phase(st.ou[m], lambda);
    }
    /* down_r12 = P_down r12, up_r10 = P_up r10, D = down_r12 up_r10 */
    vec2 dr[4], ur[4], D[4];
    for (int x = 0; x < 2; x++)
        for (int y = 0; y < 2; y++) {
            dr[2 * x + y] = cmul(pd[x], st.bot.rd[2 * x + y]);
            ur[2 * x + y] = cmul(pu[x], st.top.ru[2 * x + y]);
        }
    c2mul(dr, ur, D);
    /* (I - D)^{-1} */
    vec2 a = vec2(1.0, 0.0) - D[0], b = -D[1], c = -D[2], d = vec2(1.0, 0.0) - D[3];
    vec2 idet = cinv(cmul(a, d) - cmul(b, c));
    vec2 inv[4], entry[4], J[4], tmp[4];
    inv[0] = cmul(d, idet);
    inv[1] = -cmul(b, idet);
    inv[2] = -cmul(c, idet);
    inv[3] = cmul(a, idet);
    c2mul(st.top.td, inv, entry);
    if (which == 0) {
        vec2 out_[4];
        for (int x = 0; x < 2; x++)
            for (int o = 0; o < 2; o++) out_[2 * x + o] = cmul(pd[x], st.bot.td[2 * x + o]);
        c2mul(entry, out_, J);
    } else {
        vec2 back[4], up_t10[4];
        for (int y = 0; y < 2; y++)
            for (int o = 0; o < 2; o++) up_t10[2 * y + o] = cmul(pu[y], st.top.tu[2 * y + o]);
        c2mul(dr, up_t10, back);
        c2mul(entry, back, tmp);
        for (int k = 0; k < 4; k++) J[k] = st.top.rd[k] + tmp[k];
    }
    return detected(J, C, P);
}

/* The first texel of the plan of this many samples in the plans' texture layout. */
int plan_base(int samples)
{
    int first = samples / int(u_plan_grid.z + 0.5) - 1; /* 48 (2^i - 1) */
    return int(u_plan_grid.z + 0.5) * first;
}

ivec2 plan_texel(int t)
{
    int width = int(u_plan_grid.x + 0.5);
    return ivec2(t - (t / width) * width, t / width);
}

/* One slab state's colour for light in direction `which` (0 transmission, 1 reflection), as the
 * C library's integrator: the coherent regime exactly; else eq. 26 kept physical, which for the
 * paper's light model needs both directions (the energy balance) and the four s/p pairs, and for
 * world-fixed polarizers moves a negative result towards the incoherent path energy E. */
vec3 slab_colour_phases(SlabState st, int which, vec3 C, vec4 P, bool paper_model, TransPhases tp, ReflPhases rp)
{
    vec3 E, H;
    if (!paper_model) {
        if (which == 0)
            transmission_terms(st, tp, rp.pair, C, P, E, H);
        else
            reflection_terms(st, rp, C, P, E, H);
        vec3 X = E + 2.0 * H;
        float t = 1.0;
        for (int j = 0; j < 3; j++)
            if (X[j] < 0.0) t = min(t, E[j] > 0.0 ? E[j] / (E[j] - X[j]) : 0.0);
        return E + t * (X - E);
    }
    vec3 Es[8], Xs[8];
    /* One loop over the eight (direction, input, output) forms. Its bound comes from a uniform
     * (u_lut_band.w is 0) so that compilers keep it rolled: one copy of each term function. */
    int forms = 8 + int(u_lut_band.w);
    for (int n = 0; n < forms; n++) {
        int d = n / 4, i = (n / 2) % 2, o = n % 2;
        vec3 Ci = i == 0 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 0.0, 1.0);
        vec4 Po = o == 0 ? vec4(1.0, 0.0, 0.0, 0.0) : vec4(0.0, 0.0, 0.0, 1.0);
        if (d == 0)
            transmission_terms(st, tp, rp.pair, Ci, Po, E, H);
        else
            reflection_terms(st, rp, Ci, Po, E, H);
        Es[n] = E;
        Xs[n] = E + 2.0 * H; /* eqs. 25-26 */
    }
    physical_limit(Es, Xs);
    /* biref_spectrum_mix: sum_i w_i sum_o mask_o X[i][o] (C = diag(w), P = diag(sqrt(mask))). */
    vec3 r = vec3(0.0);
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++) r += (i == 0 ? C.x : C.z) * (o == 0 ? P.x * P.x : P.w * P.w) * Xs[4 * which + 2 * i + o];
    return r;
}

/* ------------------------------------------------------------------------------------------ */
/* Entry point for other renderers (world space)                                               */
/* ------------------------------------------------------------------------------------------ */
/* Transmitted and reflected band integrals (CIE XYZ relative to white E) of a thin uniaxial slab
 * at one hit point, for the paper's light model or world-fixed polarizers:
 *   view:    unit direction from the eye to the hit point
 *   normal:  unit slab normal (either side)
 *   axis:    unit optic axis in world space
 *   eta:     (eta_o, eta_e, thickness in nm), eta_i the surrounding index
 *   pol:     x: 0 = s/p fractions (pol_w), 1 = linear polarizer along pol_dir (world space)
 *   filter:  x: 0 = s/p mask (mask: the power fractions passed, as biref_light_sp), 1 = linear
 *            analyzer along filter_dir (world space)
 * T is the colour of light arriving from behind along view, R of light arriving along the
 * mirror direction. Returns false when an interface solve failed (grazing breakdown). */
struct BirefLight {
    float pol_linear, filter_linear;
    vec2 pol_w, mask;
    vec3 pol_dir, filter_dir;
};

/* Coherency matrix (C00, C01, C11) of the light in the basis (s, p) of a wave. */
vec3 light_coherency(BirefLight L, vec3 s, vec3 p)
{
    if (L.pol_linear > 0.5) {
        vec2 e = vec2(dot(L.pol_dir, s), dot(L.pol_dir, p));
        return vec3(e.x * e.x, e.x * e.y, e.y * e.y);
    }
    return vec3(L.pol_w.x, 0.0, L.pol_w.y);
}

/* Analyzer (P00, P01, P10, P11) in the basis (s, p) of the outgoing wave: P = a_t (a_t / |a_t|)^T. */
vec4 analyzer(BirefLight L, vec3 s, vec3 p)
{
    if (L.filter_linear > 0.5) {
        vec2 a = vec2(dot(L.filter_dir, s), dot(L.filter_dir, p));
        float l = length(a);
        vec2 u = l > 0.0 ? a / l : vec2(0.0);
        return vec4(a.x * u.x, a.x * u.y, a.y * u.x, a.y * u.y);
    }
    /* mask is a power fraction (biref_light_sp): the analyzer acts on amplitudes with its root. */
    return vec4(sqrt(L.mask.x), 0.0, 0.0, sqrt(L.mask.y));
}

/* sum_ijk C_ij P_ik P_jk: the light passed unchanged through the analyzer. */
float passthrough(vec3 C, vec4 P)
{
    return C.x * (P.x * P.x + P.y * P.y) + 2.0 * C.y * (P.x * P.z + P.y * P.w) + C.z * (P.z * P.z + P.w * P.w);
}

/* The frames of one hit (docs/SCENES.md): the optic axis in the transmission frame, the light
 * and the analyzer in each direction's wave bases. */
struct HitFrame {
    float sin_t;
    vec3 A;
    vec3 CT, CR;
    vec4 PT, PR;
    bool paper_model;
};

HitFrame hit_frame(vec3 view, vec3 normal, vec3 tangent, vec3 axis, BirefLight L)
{
    HitFrame f;
    float dn = dot(view, normal);
    float cos_t = min(1.0, abs(dn));
    /* theta <= 90 deg - 1e-7 rad, as the C renderer clamps grazing rays */
    f.sin_t = min(sqrt(max(0.0, 1.0 - cos_t * cos_t)), 1.0 - 5e-15);
    /* Paper frame of this ray (docs/SCENES.md): transmission y = normal away from the camera,
     * z = tangential part of the view ray, x = y x z; the reflection frame has x_R = -x_T. */
    vec3 yT = dn < 0.0 ? -normal : normal;
    vec3 z = view - dn * normal;
    float zl = length(z);
    z = zl < 1e-9 ? tangent : z / zl;
    vec3 xT = cross(yT, z), xR = -xT;
    vec3 mirror = view - 2.0 * dn * normal;
    vec3 k_view = -view, k_refl_in = -mirror;
    f.A = vec3(dot(axis, xT), dot(axis, yT), dot(axis, z));
    /* s = x of each frame for both waves, p = k x s. */
    f.CT = light_coherency(L, xT, cross(k_view, xT));
    f.PT = analyzer(L, xT, cross(k_view, xT));
    f.CR = light_coherency(L, xR, cross(k_refl_in, xR));
    f.PR = analyzer(L, xR, cross(k_view, xR));
    f.paper_model = L.pol_linear < 0.5 && L.filter_linear < 0.5;
    return f;
}

/* A failed solve or a non-finite colour: a perfect mirror seen through the filter, as the C
 * renderer's fallback. */
bool hit_result(bool ok, HitFrame f, inout vec3 T, inout vec3 R)
{
    bool finite = !(any(isnan(T)) || any(isinf(T)) || any(isnan(R)) || any(isinf(R)));
    if (!ok || !finite) {
        T = vec3(0.0);
        R = vec3(passthrough(f.CR, f.PR));
        return false;
    }
    return true;
}

/* ------------------------------------------------------------------------------------------ */
/* Dispersive materials (docs/PHYSICS.md §7; src/spectral/analytic_dispersive.c,               */
/* leg_dispersion.c): per band the modes and Fresnel coefficients at the band's centroid, each  */
/* lag's phase on sub-band tangents                                                             */
/* ------------------------------------------------------------------------------------------ */
/* biref_gl_subband_table: table t = 2^L - 2 + b (level L, sub-band b) band j in row 3 t + j.
 * biref_gl_scene_materials: per slab u_plan_grid.w rows, first the indices (n_o, n_e, dn_o/dλ,
 * dn_e/dλ) at the plans' samples (texel for texel as u_plans), then one row with the same at the
 * sub-band points (texels 0-64), at the three band centroids (65-67) and at band j's Gauss node i
 * (68 + 2 j + i). */
#if defined(BIREF_SCENE) || defined(BIREF_MATERIALS)
uniform highp sampler2D u_subbands;
uniform highp sampler2D u_material;
#define BIREF_MATERIAL_TEXEL(xy) texelFetch(u_material, xy, 0)
#define BIREF_SUBBAND_TEXEL(xy) texelFetch(u_subbands, xy, 0)
#else
/* Constant indices only (an embedder without BIREF_MATERIALS): no sampler to bind. */
#define BIREF_MATERIAL_TEXEL(xy) vec4(0.0)
#define BIREF_SUBBAND_TEXEL(xy) vec4(0.0)
#endif
const int SUBBAND_LEVELS = 5;         /* BIREF_SUBBAND_LEVELS */
const int SUBBAND_POINTS = 65;        /* BIREF_SUBBAND_POINTS: 2 * 2^levels + 1 */
const float SUBBAND_PHASE_TOL = 0.005; /* rad, BIREF_SUBBAND_PHASE_TOL */
const float TANGENT_BREAK_RAD = 0.25;  /* analytic_dispersive.c: BREAK_RAD */

/* Pairs (value, d/dλ). */
vec2 dmul(vec2 a, vec2 b) { return vec2(a.x * b.x, a.x * b.y + a.y * b.x); }
vec2 ddiv(vec2 a, vec2 b) { return vec2(a.x / b.x, (a.y * b.x - a.x * b.y) / (b.x * b.x)); }
vec2 dsqrt(vec2 a)
{
    float r = sqrt(a.x);
    return vec2(r, r > 0.0 ? 0.5 * a.y / r : 0.0);
}

/* The real parts of the legs' optical paths at one wavelength and their derivatives in λ, from
 * the indices n = (n_o, n_e, dn_o/dλ, dn_e/dλ): the o leg (down and up alike), and e - o down
 * and up, the latter from q_e^2 - q_o^2 as uniaxial_modes (no cancellation). */
void leg_paths(vec4 n, vec3 A, float K, float d, out vec2 Lo, out vec2 Dd, out vec2 Du)
{
    float al = A.x, be = A.y, ga = A.z;
    vec2 eo = vec2(n.x * n.x, 2.0 * n.x * n.z), ee = vec2(n.y * n.y, 2.0 * n.y * n.w), de = ee - eo;
    bool o_prop = eo.x > K * K;
    vec2 qo = o_prop ? dsqrt(eo - vec2(K * K, 0.0)) : vec2(0.0);
    vec2 a = eo + be * be * de;
    vec2 lin = be * ga * K * de;
    vec2 disc = dmul(ee, a) + K * K * (al * al * de - ee);
    vec2 root = disc.x > 0.0 ? dsqrt(dmul(eo, disc)) : vec2(0.0);
    vec2 qed = ddiv(lin - root, a), qeu = ddiv(lin + root, a); /* Re q_e down, up */
    Lo = d * qo;
    if (o_prop && disc.x > 0.0) {
        vec2 base = (1.0 - be * be) * eo + vec2(K * K * (be * be - ga * ga), 0.0);
        vec2 numd = ddiv(dmul(de, 2.0 * be * ga * K * qed + base), a);
        vec2 numu = ddiv(dmul(de, 2.0 * be * ga * K * qeu + base), a);
        Dd = -d * ddiv(numd, qed - qo); /* q_o down = -qo */
        Du = d * ddiv(numu, qeu + qo);
    } else {
        Dd = -d * qed - Lo;
        Du = d * qeu - Lo;
    }
}

/* Per sample point p of the hit's legs: group paths opl - λ dopl/dλ and dopl/dλ of (o, e - o
 * down, e - o up). A lag with leg counts (down o, down e, up o, up e) weighs them by
 * w = (all legs, down e, up e). */
vec3 g_group[SUBBAND_POINTS], g_slope[SUBBAND_POINTS];

float subband_k(int p)
{
    float klo = 2.0 * BIREF_PI / u_lut_band.z, khi = 2.0 * BIREF_PI / u_lut_band.y;
    return sqrt(klo * klo + (khi * khi - klo * klo) * float(p) / float(SUBBAND_POINTS - 1));
}

/* The number of sample points, from a uniform (u_lut_band.w is 0) so that compilers keep the
 * loops over them rolled. */
int subband_points() { return SUBBAND_POINTS + int(u_lut_band.w); }

void sample_legs(int row, vec3 A, float K, float d)
{
    for (int p = 0; p < subband_points(); p++) {
        float lambda = 2.0 * BIREF_PI / subband_k(p);
        vec2 Lo, Dd, Du;
        leg_paths(BIREF_MATERIAL_TEXEL(ivec2(p, row)), A, K, d, Lo, Dd, Du);
        g_slope[p] = vec3(Lo.y, Dd.y, Du.y);
        g_group[p] = vec3(Lo.x, Dd.x, Du.x) - lambda * g_slope[p];
    }
}

/* The largest distance of the lag's phase Φ = k G + ψ from its tangents at the sub-bands'
 * midpoints, at their edges (leg_dispersion.c: level_residual). */
float level_residual(float G[SUBBAND_POINTS], float psi[SUBBAND_POINTS], int level)
{
    int span = (SUBBAND_POINTS - 1) >> level;
    float worst = 0.0;
    for (int a = 0; a + span < SUBBAND_POINTS; a += span) {
        int m = a + span / 2, e = a + span;
        worst = max(worst, abs(subband_k(a) * (G[a] - G[m]) + psi[a] - psi[m]));
        worst = max(worst, abs(subband_k(e) * (G[e] - G[m]) + psi[e] - psi[m]));
    }
    return worst;
}

/* Table t of the sub-bands (t < 0: the band's own, u_lut) at D (|D| <= d_max), the three bands
 * as (re, im), and its first moment in k likewise (k real: both conjugate for D < 0). */
void subband_eval(int t, float D, out vec3 re, out vec3 im, out vec3 kre, out vec3 kim)
{
    float a = abs(D);
    TableNodes tn = table_nodes(a);
    for (int j = 0; j < 3; j++) {
        vec4 A, B;
        if (t < 0) {
            A = texelFetch(u_lut, ivec2(tn.m, j), 0);
            B = texelFetch(u_lut, ivec2(tn.m + 1, j), 0);
        } else {
            A = BIREF_SUBBAND_TEXEL(ivec2(tn.m, 3 * t + j));
            B = BIREF_SUBBAND_TEXEL(ivec2(tn.m + 1, 3 * t + j));
        }
        vec2 v = table_value(tn, A, B), vk = table_moment(tn, a, A, B);
        float sg = D < 0.0 ? -1.0 : 1.0; /* S(e^{-ikD}) = conj S(e^{ikD}) */
        re[j] = v.x;
        im[j] = sg * v.y;
        kre[j] = vk.x;
        kim[j] = sg * vk.y;
    }
}

/* The amplitudes' wavenumbers (docs/PHYSICS.md §7): band j's two Gauss nodes k[j][i] and their
 * masses S(ℓ_i, Λ_j), ℓ_i the linear weight that is 1 at node i and 0 at the other
 * (biref_gl_scene_uniforms, from biref_band_nodes). */
uniform vec3 u_band_node_k[2];
uniform vec3 u_band_node_mass[2];

/* The lag's integrals under node i's weight, S(ℓ_i e^{iΦ}) / S(ℓ_i), from m0 = S(e^{iΦ}) and
 * m1 = S(k e^{iΦ}); beyond the tables (m1 unknown) the band's mean (biref_lag_node_integrals). */
void node_integrals(int i, vec3 c0, vec3 s0, vec3 c1, vec3 s1, bool beyond, out vec3 c, out vec3 s)
{
    vec3 w = u_band_node_mass[i], wo = u_band_node_mass[1 - i], total = w + wo;
    vec3 ko = u_band_node_k[1 - i], den = (u_band_node_k[i] - ko) * w;
    for (int j = 0; j < 3; j++) {
        if (!(w[j] > 0.0)) {
            c[j] = 0.0;
            s[j] = 0.0;
        } else if (beyond || !(wo[j] > 0.0)) {
            c[j] = c0[j] / total[j];
            s[j] = s0[j] / total[j];
        } else {
            c[j] = (c1[j] - ko[j] * c0[j]) / den[j];
            s[j] = (s1[j] - ko[j] * s0[j]) / den[j];
        }
    }
}

/* The lags' integrals under the nodes' weights: lag n, node i at index 2 n + i. */
vec3 g_lag_c[30], g_lag_s[30];

/* The lag weighted by w (biref_lag_integrals) into lag slot n; res: the largest phase error of
 * the tangents at the level used. */
void lag_integrals(vec3 w, int n, out float res)
{
    float G[SUBBAND_POINTS], psi[SUBBAND_POINTS]; /* psi in cycles: Φ - k G = 2 pi psi */
    float psi_rad[SUBBAND_POINTS];
    for (int p = 0; p < subband_points(); p++) {
        G[p] = dot(w, g_group[p]);
        psi[p] = dot(w, g_slope[p]);
        psi_rad[p] = 2.0 * BIREF_PI * psi[p];
    }
    const int mid = (SUBBAND_POINTS - 1) / 2;
    int level = 0;
    res = level_residual(G, psi_rad, 0);
    bool inside = res > SUBBAND_PHASE_TOL && abs(G[mid]) <= u_lut_grid.z;
    for (int p = 1; p < subband_points() - 1; p++) inside = inside && abs(G[p]) <= u_lut_grid.z;
    if (inside)
        for (int l = 1; l <= SUBBAND_LEVELS + int(u_lut_band.w); l++) {
            if (!(res > SUBBAND_PHASE_TOL)) break;
            level = l;
            res = level_residual(G, psi_rad, l);
        }
    /* m0 = S(e^{iΦ}), m1 = S(k e^{iΦ}) as (c, s) pairs. Level 0: the band's own table, which
     * also covers the lags beyond the sub-band tables (there without m1). */
    bool beyond = level == 0 && !(abs(G[mid]) <= u_lut_grid.z);
    vec3 c0 = vec3(0.0), s0 = vec3(0.0), c1 = vec3(0.0), s1 = vec3(0.0), re, im, kre, kim;
    int span = (SUBBAND_POINTS - 1) >> level;
    for (int b = 0; b < (1 << level); b++) {
        int m = b * span + span / 2;
        if (beyond) {
            biref_phase_integrals(G[m], re, im);
            kre = vec3(0.0);
            kim = vec3(0.0);
        } else {
            subband_eval(level == 0 ? -1 : (1 << level) - 2 + b, G[m], re, im, kre, kim);
        }
        vec2 rot = cycles_exp(psi[m]); /* the tangent's offset */
        c0 += rot.x * re - rot.y * im;
        s0 += rot.y * re + rot.x * im;
        c1 += rot.x * kre - rot.y * kim;
        s1 += rot.y * kre + rot.x * kim;
    }
    for (int i = 0; i < 2; i++) node_integrals(i, c0, s0, c1, s1, beyond, g_lag_c[2 * n + i], g_lag_s[2 * n + i]);
}

/* The lags of both faces' states (transmission-frame legs): 0 e - o down, 1 e - o up, 2 their
 * sum, 3 their difference, 4 + 2 x + y the round trip (down x, up y), 8 = -(lag 3); the siblings'
 * entry pairs: 10 + m twice e - o down plus m times e - o up (the state's, m = -1, 0, 1), 13 + m the
 * same with down and up exchanged (the flip's). */

vec3 lag_weights(int i)
{
    if (i == 0) return vec3(0.0, 1.0, 0.0);
    if (i == 1) return vec3(0.0, 0.0, 1.0);
    if (i == 2) return vec3(0.0, 1.0, 1.0);
    if (i == 3) return vec3(0.0, 1.0, -1.0);
    if (i >= 12) return vec3(0.0, float(i - 13), 2.0);
    if (i >= 9) return vec3(0.0, 2.0, float(i - 10));
    return vec3(2.0, float((i - 4) / 2), float((i - 4) % 2));
}

/* The run's node, whose weight the lags are taken under. */
int g_node;

PhaseInt lag_phase(int i, float im_opd)
{
    PhaseInt p;
    p.c = g_lag_c[2 * i + g_node];
    p.s = g_lag_s[2 * i + g_node];
    p.att = im_opd != 0.0 ? exp(-u_k_centroid * im_opd) : vec3(1.0);
    return p;
}

/* transmission_phases and reflection_phases from the lags; flip: the state lit from the other
 * face, whose down and up legs are the transmission frame's up and down legs. */
TransPhases transmission_lags(SlabState st, bool flip)
{
    TransPhases ph;
    ph.h0 = lag_phase(flip ? 1 : 0, st.od[1].y + st.od[0].y);
    for (int y = 0; y < 2; y++)
        for (int x2 = 0; x2 < 2; x2++) {
            vec2 trip = st.ou[y] + st.od[x2];
            ph.trip[2 * y + x2] = lag_phase(flip ? 4 + 2 * y + x2 : 4 + 2 * x2 + y, trip.y);
        }
    for (int m = 0; m < 3; m++) ph.e2[m] = lag_phase(flip ? 12 + m : 9 + m, 0.0); /* attenuation per pair */
    return ph;
}

ReflPhases reflection_lags(SlabState st, bool flip)
{
    ReflPhases ph;
    for (int a = 0; a < 4; a++) {
        int x = a / 2, y = a - 2 * x;
        vec2 opl = st.od[x] + st.ou[y];
        ph.p1[a] = lag_phase(flip ? 4 + 2 * y + x : a + 4, opl.y);
    }
    /* pairs (0,1) (0,2) (0,3) (1,2) (1,3) (2,3) */
    int k = 0;
    for (int a = 0; a < 4; a++)
        for (int b = a + 1; b < 4; b++) {
            int xa = a / 2, ya = a - 2 * xa, xb = b / 2, yb = b - 2 * xb;
            float im = st.od[xb].y + st.od[xa].y + st.ou[yb].y + st.ou[ya].y;
            int lag = xa == xb ? 1 : ya == yb ? 0 : ya == yb - 1 ? 2 : 3; /* up, down, both, difference */
            if (flip) lag = lag == 0 ? 1 : lag == 1 ? 0 : lag == 3 ? 8 : 2;
            ph.pair[k++] = lag_phase(lag, im);
        }
    return ph;
}

/* A dispersive state at one sample wavelength for the exact integral: the legs' optical paths
 * with the material's indices there (eq. 2, complex where evanescent), the interfaces linear in
 * k through the band states of the green and blue bands (the CPU prepares every sample's state
 * anew; llvmpipe stops a shader's loops after 65535 iterations in all, which a 4x4 solve per
 * sample exceeds: docs/GPU.md). */
SlabState sample_state(SlabState st[9], vec2 n, float k, vec3 A, float K, float d)
{
    SlabState s = st[1];
    float t = (k - u_k_centroid.y) / (u_k_centroid.z - u_k_centroid.y);
    for (int i = 0; i < 4; i++) {
        s.top.rd[i] += t * (st[2].top.rd[i] - st[1].top.rd[i]);
        s.top.td[i] += t * (st[2].top.td[i] - st[1].top.td[i]);
        s.top.ru[i] += t * (st[2].top.ru[i] - st[1].top.ru[i]);
        s.top.tu[i] += t * (st[2].top.tu[i] - st[1].top.tu[i]);
        s.bot.rd[i] += t * (st[2].bot.rd[i] - st[1].bot.rd[i]);
        s.bot.td[i] += t * (st[2].bot.td[i] - st[1].bot.td[i]);
        s.bot.ru[i] += t * (st[2].bot.ru[i] - st[1].bot.ru[i]);
        s.bot.tu[i] += t * (st[2].bot.tu[i] - st[1].bot.tu[i]);
    }
    float al = A.x, be = A.y, ga = A.z;
    float eo = n.x * n.x, ee = n.y * n.y, de = ee - eo;
    vec2 r = csqrt_real(eo - K * K);
    float a = eo + be * be * de;
    vec2 root = csqrt_real(eo * (ee * a + K * K * (al * al * de - ee)));
    vec2 lin = vec2(be * ga * K * de, 0.0);
    s.od[0] = d * r;
    s.ou[0] = d * r;
    s.od[1] = -d * (lin - root) / a;
    s.ou[1] = d * (lin + root) / a;
    return s;
}

/* The closed form integrated with a plan of this many samples for one direction: the coherent
 * regime, and for a dispersive material also the states whose lags' tangents break, then with
 * n(λ) at every sample (biref_spectrum_numeric_dispersive). */
vec3 sample_integral(SlabState st[9], bool dispersive, int row, HitFrame f, float d, float eta_i, int which,
                     int samples)
{
    int base = plan_base(samples);
    vec3 acc = vec3(0.0);
    for (int n = 0; n < samples; n++) {
        ivec2 tx = plan_texel(base + n);
        vec4 s = texelFetch(u_plans, tx, 0);
        SlabState st0 = st[0];
        if (dispersive)
            st0 = sample_state(st, BIREF_MATERIAL_TEXEL(ivec2(tx.x, row + tx.y)).xy, 2.0 * BIREF_PI / s.x, f.A,
                               eta_i * f.sin_t, d);
        if (which == 1) st0 = slab_flip(st0);
        acc += s.yzw * coherent_detected(st0, which, which == 0 ? f.CT : f.CR, which == 0 ? f.PT : f.PR, s.x);
    }
    return acc;
}

/* State idx of the prepared states, flipped for reflection. */
SlabState state_at(SlabState st[9], int idx, bool flip)
{
    SlabState s = st[0]; /* WebGL allows no ?: on structures */
    for (int i = 1; i < 9; i++)
        if (i == idx) s = st[i];
    if (flip) s = slab_flip(s);
    return s;
}

/* One hit: a slab of constant indices eta = (eta_o, eta_e, d nm), or (dispersive) of the
 * material whose data start at row `row` of u_material (thickness eta.z). One function for both,
 * called once by the scene shader, so that compilers keep one copy of every part. */
bool shade_hit(vec3 view, vec3 normal, vec3 tangent, vec3 axis, vec3 eta, bool dispersive, int row, float eta_i,
               BirefLight L, out vec3 T, out vec3 R)
{
    HitFrame f = hit_frame(view, normal, tangent, axis, L);
    float d = eta.z;
    int points_row = row + int(u_plan_grid.w + 0.5) - 1;
    /* The slab states: for constant indices one; for a dispersive material (analytic_dispersive.c)
     * 0-2 at the band centroids (the coherent regime and the plan where tangents break), 3 + 2 j + i
     * at band j's Gauss node i (the runs: modes and Fresnel coefficients there). */
    SlabState st[9];
    bool ok = true;
    int states = (dispersive ? 9 : 1) + int(u_lut_band.w); /* bounds from a uniform: loops stay rolled */
    for (int j = 0; j < states; j++) {
        vec2 n = dispersive ? BIREF_MATERIAL_TEXEL(ivec2(SUBBAND_POINTS + j, points_row)).xy : eta.xy;
        ok = slab_prepare(n.x, n.y, f.A, d, eta_i, f.sin_t, st[j]) && ok;
    }
    /* Which directions are integrated exactly, with which plan: the densest plan of the centroid
     * states in the coherent regime; else, for a material whose birefringent lags' tangents break,
     * band 0's; else the densest of the node states in the regime. q = 2 state + direction. */
    bool exact = false, broken = false;
    int ns[2];
    ns[0] = 0;
    ns[1] = 0;
    for (int pass = 0; pass < 2 && !exact; pass++) {
        if (pass == 1) {
            if (!dispersive) break;
            sample_legs(points_row, f.A, eta_i * f.sin_t, d);
            float worst = 0.0, residual;
            for (int i = 0; i < 15; i++) {
                if (i == 8) {
                    for (int k = 0; k < 2; k++) {
                        g_lag_c[16 + k] = g_lag_c[6 + k];
                        g_lag_s[16 + k] = -g_lag_s[6 + k];
                    }
                } else {
                    lag_integrals(lag_weights(i), i, residual);
                    if (i < 3) worst = max(worst, residual);
                }
                if (i == 2 && worst > TANGENT_BREAK_RAD) break;
            }
            broken = worst > TANGENT_BREAK_RAD;
        }
        int first = pass == 0 ? 0 : 3, last = pass == 0 ? min(states, 3) : states;
        for (int q = 2 * first; q < 2 * last; q++) {
            int idx = q / 2, j = (idx - 3) / 2, i = (idx - 3) % 2;
            if (pass == 1 && !broken && !(u_band_node_mass[i][j] > 0.0)) continue;
            SlabState s = state_at(st, broken ? 0 : idx, q % 2 == 1);
            if (broken ? idx != 3 : !coherent_regime(s)) continue;
            exact = true;
            ns[q % 2] = max(ns[q % 2], plan_samples(s));
        }
    }
    vec3 res[2];
    int dirs = 2 + int(u_lut_band.w);
    for (int w = 0; w < dirs; w++) {
        res[w] = vec3(0.0);
        if (exact) res[w] = sample_integral(st, dispersive, row, f, d, eta_i, w, ns[w]);
    }
    /* Elsewhere eq. 26 kept physical, per (state, direction); a material's run at band j's node
     * i gives band j of the colour, weighted by the node's share, its phase integrals the lags'
     * under the node's weight. */
    int runs = exact ? 0 : dispersive ? 12 : 2;
    for (int q = 0; q < runs; q++) {
        int idx = dispersive ? 3 + q / 2 : 0, which = q % 2, j = (idx - 3) / 2, i = (idx - 3) % 2;
        float share = 1.0;
        if (dispersive) {
            float w = u_band_node_mass[i][j];
            if (!(w > 0.0)) continue;
            share = w / (u_band_node_mass[0][j] + u_band_node_mass[1][j]);
            g_node = i;
        }
        bool flip = which == 1;
        SlabState s = state_at(st, idx, flip);
        TransPhases tp;
        ReflPhases rp;
        if (dispersive) {
            tp = transmission_lags(s, flip);
            rp = reflection_lags(s, flip);
        } else {
            tp = transmission_phases(s);
            rp = reflection_phases(s);
        }
        vec3 c = slab_colour_phases(s, which, flip ? f.CR : f.CT, flip ? f.PR : f.PT, f.paper_model, tp, rp);
        if (dispersive)
            res[which][j] += share * c[j];
        else
            res[which] = c;
    }
    T = res[0];
    R = res[1];
    return hit_result(ok, f, T, R);
}

/* Transmitted and reflected band integrals at one hit (the entry point described above). */
bool biref_shade_slab(vec3 view, vec3 normal, vec3 tangent, vec3 axis, vec3 eta, float eta_i, BirefLight L,
                      out vec3 T, out vec3 R)
{
    return shade_hit(view, normal, tangent, axis, eta, false, 0, eta_i, L, T, R);
}

#if defined(BIREF_SCENE) || defined(BIREF_MATERIALS)
/* The same for a slab of a dispersive material, thickness d_nm, whose data (u_material) start at
 * row `row` (slab i of biref_gl_scene_materials: i * u_plan_grid.w); needs u_subbands too. */
bool biref_shade_material(vec3 view, vec3 normal, vec3 tangent, vec3 axis, int row, float d_nm, float eta_i,
                          BirefLight L, out vec3 T, out vec3 R)
{
    return shade_hit(view, normal, tangent, axis, vec3(0.0, 0.0, d_nm), true, row, eta_i, L, T, R);
}
#endif

#ifdef BIREF_SCENE
/* ------------------------------------------------------------------------------------------ */
/* The scene ray caster of `biref render` (docs/SCENES.md)                                     */
/* ------------------------------------------------------------------------------------------ */
uniform vec2 u_resolution;
uniform vec3 u_cam_origin, u_cam_forward, u_cam_right, u_cam_up;
uniform vec2 u_cam_tan_half; /* horizontal, vertical */
uniform float u_exposure;
uniform float u_eta_medium;

uniform float u_n_slabs;
uniform vec3 u_slab_center[BIREF_MAX_SLABS];
uniform vec3 u_slab_normal[BIREF_MAX_SLABS];
uniform vec3 u_slab_tangent[BIREF_MAX_SLABS];
uniform vec3 u_slab_bitangent[BIREF_MAX_SLABS];
uniform vec2 u_slab_half[BIREF_MAX_SLABS];
uniform vec3 u_slab_axis[BIREF_MAX_SLABS];   /* world, unit */
uniform vec3 u_slab_optics[BIREF_MAX_SLABS]; /* eta_o, eta_e, thickness nm */
uniform float u_slab_material[BIREF_MAX_SLABS]; /* 1: a dispersive material (u_material) */

uniform float u_n_panels;
uniform vec3 u_panel_center[BIREF_MAX_PANELS];
uniform vec3 u_panel_normal[BIREF_MAX_PANELS];
uniform vec3 u_panel_tangent[BIREF_MAX_PANELS];
uniform vec3 u_panel_bitangent[BIREF_MAX_PANELS];
uniform vec2 u_panel_half[BIREF_MAX_PANELS];
uniform vec3 u_panel_radiance[BIREF_MAX_PANELS]; /* XYZ */

uniform float u_env_checker;
uniform vec3 u_env_up, u_env_e1, u_env_e2;
uniform vec3 u_env_zenith, u_env_horizon, u_env_ground, u_env_check_a, u_env_check_b; /* XYZ */
uniform float u_env_check_size;

uniform vec4 u_pol;    /* linear?, s fraction, p fraction, filter linear? */
uniform vec2 u_mask;   /* s/p analyzer mask, power fractions */
uniform vec3 u_pol_dir, u_filter_dir;
uniform vec3 u_rgb_from_xyz[3]; /* rows of the XYZ (white E) -> linear sRGB matrix */

const float RAY_EPS = 1e-6;

vec3 env_radiance(vec3 d)
{
    float el = dot(d, u_env_up);
    if (el >= 0.0) return mix(u_env_horizon, u_env_zenith, sqrt(min(el, 1.0)));
    float g = min(1.0, -el * 8.0);
    vec3 ground = u_env_ground;
    if (u_env_checker > 0.5 && g > 1e-3) {
        float s = 1.0 / (-el * u_env_check_size);
        float u = floor(dot(d, u_env_e1) * s), w = floor(dot(d, u_env_e2) * s);
        ground = abs(mod(u + w, 2.0)) >= 1.0 ? u_env_check_b : u_env_check_a;
    }
    return mix(u_env_horizon, ground, g);
}

vec3 radiance(vec3 from, vec3 dir)
{
    float best = 1e30;
    int hit = -1;
    int n = int(u_n_panels + 0.5);
    for (int i = 0; i < BIREF_MAX_PANELS; i++) {
        if (i >= n) break;
        float dn = dot(dir, u_panel_normal[i]);
        if (abs(dn) < 1e-12) continue;
        float t = dot(u_panel_center[i] - from, u_panel_normal[i]) / dn;
        if (!(t > RAY_EPS) || t >= best) continue;
        vec3 q = from + t * dir - u_panel_center[i];
        if (abs(dot(q, u_panel_tangent[i])) <= u_panel_half[i].x && abs(dot(q, u_panel_bitangent[i])) <= u_panel_half[i].y) {
            best = t;
            hit = i;
        }
    }
    vec3 L = env_radiance(dir);
    for (int i = 0; i < BIREF_MAX_PANELS; i++)
        if (i == hit) L = u_panel_radiance[i];
    return L;
}

/* Returns XYZ (exposure applied); flag: 0 background, 1 slab, 2 slab with the fallback. */
vec3 shade_pixel(vec3 dir, out float flag)
{
    BirefLight L;
    L.pol_linear = u_pol.x;
    L.pol_w = u_pol.yz;
    L.filter_linear = u_pol.w;
    L.mask = u_mask;
    L.pol_dir = u_pol_dir;
    L.filter_dir = u_filter_dir;
    vec3 o = u_cam_origin;
    float best = 1e30;
    int hit = -1;
    int n = int(u_n_slabs + 0.5);
    for (int i = 0; i < BIREF_MAX_SLABS; i++) {
        if (i >= n) break;
        float dn = dot(dir, u_slab_normal[i]);
        if (abs(dn) < 1e-12) continue;
        float t = dot(u_slab_center[i] - o, u_slab_normal[i]) / dn;
        if (!(t > RAY_EPS) || t >= best) continue;
        vec3 q = o + t * dir - u_slab_center[i];
        if (abs(dot(q, u_slab_tangent[i])) <= u_slab_half[i].x && abs(dot(q, u_slab_bitangent[i])) <= u_slab_half[i].y) {
            best = t;
            hit = i;
        }
    }
    vec3 k_view = -dir;
    if (hit < 0) {
        /* Background: the polarizers in the plane of the view ray and the first slab's normal. */
        vec3 nrm = u_slab_normal[0];
        vec3 s = cross(k_view, nrm);
        float sl = length(s);
        if (sl < 1e-6) {
            vec3 t = u_slab_tangent[0] - dot(u_slab_tangent[0], k_view) * k_view;
            s = normalize(t);
        } else {
            s /= sl;
        }
        vec3 p = cross(k_view, s);
        flag = 0.0;
        return radiance(o, dir) * passthrough(light_coherency(L, s, p), analyzer(L, s, p));
    }
    vec3 nrm = vec3(0.0), tan_ = vec3(0.0), ax = vec3(0.0), eta = vec3(0.0);
    float dispersive = 0.0;
    for (int i = 0; i < BIREF_MAX_SLABS; i++)
        if (i == hit) {
            nrm = u_slab_normal[i];
            tan_ = u_slab_tangent[i];
            ax = u_slab_axis[i];
            eta = u_slab_optics[i];
            dispersive = u_slab_material[i];
        }
    vec3 hp = o + best * dir;
    vec3 T, R;
    bool ok = shade_hit(dir, nrm, tan_, ax, eta, dispersive > 0.5, hit * int(u_plan_grid.w + 0.5), u_eta_medium, L, T, R);
    flag = ok ? 1.0 : 2.0;
    vec3 mirror = dir - 2.0 * dot(dir, nrm) * nrm;
    return T * radiance(hp, dir) + R * radiance(hp, mirror);
}

float srgb_encode(float v)
{
    float a = abs(v);
    float e = a <= 0.0031306684425006340 ? 12.92 * a : 1.055 * pow(a, 1.0 / 2.4) - 0.055;
    return v < 0.0 ? -e : e;
}

out vec4 frag;
void main()
{
    float x = floor(gl_FragCoord.x), y = u_resolution.y - 1.0 - floor(gl_FragCoord.y); /* y = 0 at the top */
    float sx = (2.0 * (x + 0.5) / u_resolution.x - 1.0) * u_cam_tan_half.x;
    float sy = (1.0 - 2.0 * (y + 0.5) / u_resolution.y) * u_cam_tan_half.y;
    vec3 dir = normalize(u_cam_forward + sx * u_cam_right + sy * u_cam_up);
    float flag;
    vec3 xyz = shade_pixel(dir, flag) * u_exposure;
    if (any(isnan(xyz)) || any(isinf(xyz))) xyz = vec3(0.0);
#ifdef BIREF_OUTPUT_SRGB
    vec3 rgb = vec3(dot(u_rgb_from_xyz[0], xyz), dot(u_rgb_from_xyz[1], xyz), dot(u_rgb_from_xyz[2], xyz));
    frag = vec4(clamp(vec3(srgb_encode(rgb.x), srgb_encode(rgb.y), srgb_encode(rgb.z)), 0.0, 1.0), 1.0);
#else
    frag = vec4(xyz, flag);
#endif
}
#endif /* BIREF_SCENE */
#endif /* BIREF_VERTEX */
