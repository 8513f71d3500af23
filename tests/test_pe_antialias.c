/* Spatial anti-aliasing of photoelastic pictures: the footprint-averaged shading against a direct
 * average of the point shading over the same range of retardation, and the disk below a load,
 * where the prefiltered picture must be much closer to a super-sampled reference than the plain
 * one. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"
#include "photoelastic/pe_footprint.h"
#include "test_cases.h"

static biref_spectral *sp;
static biref_phase_prefilter *pf;

/* The defaults of `biref photoelastic --preset disk`: polycarbonate, 6 mm, dark-field circular. */
static biref_pe_setup disk_setup(biref_pe_light_kind light)
{
    biref_pe_setup s;
    memset(&s, 0, sizeof s);
    (void)biref_pe_material_preset("polycarbonate", &s.material);
    s.thickness = 6e-3;
    s.eta_i = 1.0;
    s.light = light;
    s.lambda_nm = 589.0;
    biref_pe_polariscope_make(BIREF_PE_CIRCULAR, BIREF_PE_DARK, 0.0, &s.pol);
    return s;
}

/* Principal stresses giving retardation delta_nm, first principal direction phi. */
static biref_pe_principal principal(const biref_pe_setup *s, double delta_nm, double phi)
{
    biref_pe_principal p = {delta_nm / (s->material.C_per_Pa * s->thickness * 1e9), 0.0, phi, cos(2 * phi), sin(2 * phi)};
    return p;
}

/* Box average of the point shading over [delta - w/2, delta + w/2] by a fine midpoint rule, in a
 * plane polariscope (where the principal direction matters too). */
static void check_against_quadrature(biref_pe_light_kind light)
{
    biref_pe_setup s = disk_setup(light);
    biref_pe_polariscope_make(BIREF_PE_PLANE, BIREF_PE_DARK, 0.3, &s.pol);
    static const double cases[][2] = {{150.0, 40.0}, {800.0, 300.0}, {2500.0, 1200.0}, {20.0, 60.0}, {6000.0, 5000.0}};
    double worst = 0.0;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        const double d = cases[c][0], w = cases[c][1];
        double q[3] = {0, 0, 0}, box[3];
        const int n = 4000;
        for (int i = 0; i < n; i++) {
            biref_pe_principal p = principal(&s, d - 0.5 * w + (i + 0.5) * w / n, 0.4);
            double v[3];
            biref_pe_shade(&s, sp, &p, v);
            for (int j = 0; j < 3; j++) q[j] += v[j] / n;
        }
        biref_pe_principal p = principal(&s, d, 0.4);
        biref_pe_shade_footprint(&s, sp, light == BIREF_PE_WHITE ? pf : NULL, w, &p, box);
        for (int j = 0; j < 3; j++) worst = fmax(worst, fabs(box[j] - q[j]));
    }
    printf("%s: largest difference from the quadrature %.2e\n", light == BIREF_PE_WHITE ? "white" : "mono", worst);
    CHECK(worst < 1e-6);
}

static void white_box_matches_quadrature(void) { check_against_quadrature(BIREF_PE_WHITE); }
static void mono_box_matches_quadrature(void) { check_against_quadrature(BIREF_PE_MONO); }

/* Width 0 is the point shading, bit for bit. */
static void zero_width_is_the_point_shading(void)
{
    for (int light = 0; light < 2; light++) {
        biref_pe_setup s = disk_setup((biref_pe_light_kind)light);
        biref_pe_principal p = principal(&s, 737.0, 0.2);
        double a[3], b[3];
        biref_pe_shade(&s, sp, &p, a);
        biref_pe_shade_footprint(&s, sp, light == BIREF_PE_WHITE ? pf : NULL, 0.0, &p, b);
        CHECK(memcmp(a, b, sizeof a) == 0);
    }
}

/* The window below the upper load point of the 25 mm disk under 500 N (its top edge 1 mm below
 * the load), W x W pixels at `scale` times the pixel pitch of the default 512-pixel picture. */
static float *disk_picture(const biref_pe_setup *s, int W, double scale, int K, int prefilter, double tilt)
{
    biref_pe_field f;
    char msg[256];
    if (biref_pe_field_disk(&f, 25e-3, s->thickness, 500.0, msg, sizeof msg) != BIREF_OK) return NULL;
    const double pitch = scale * (f.frame[1] - f.frame[0]) / 512.0, top = 24e-3;
    f.frame[0] = -0.5 * W * pitch, f.frame[1] = 0.5 * W * pitch;
    f.frame[2] = top - W * pitch, f.frame[3] = top;
    biref_pe_image_opts io = {.width = W, .height = W, .supersample = K, .threads = 0, .tint = {1, 1, 1}, .tilt = tilt};
    float *xyz = malloc((size_t)W * W * 3 * sizeof *xyz);
    if (!xyz) return NULL;
    biref_status st = prefilter ? biref_pe_render_prefiltered(s, sp, &f, &io, xyz, NULL, 0) : biref_pe_render(s, sp, &f, &io, xyz, NULL, 0);
    if (st != BIREF_OK) {
        free(xyz);
        return NULL;
    }
    return xyz;
}

static double mean_de(const float *a, const float *b, size_t n)
{
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) {
        double x[3] = {a[3 * i], a[3 * i + 1], a[3 * i + 2]}, y[3] = {b[3 * i], b[3 * i + 1], b[3 * i + 2]};
        sum += biref_delta_e00_xyz(x, y);
    }
    return sum / (double)n;
}

/* BIREF_TEST_QUICK (the sanitizer run): a smaller window and reference. */
static void disk_below_load(biref_pe_light_kind light)
{
    const int quick = test_quick(), W = quick ? 24 : 48, K_ref = quick ? 8 : 12;
    const double scale = 128.0 / W; /* the same 13 mm window at any W */
    biref_pe_setup s = disk_setup(light);
    float *ref = disk_picture(&s, W, scale, K_ref, 0, 0.0);
    float *plain = disk_picture(&s, W, scale, 1, 0, 0.0);
    float *pre = disk_picture(&s, W, scale, 1, 1, 0.0);
    CHECK(ref && plain && pre);
    if (ref && plain && pre) {
        const size_t n = (size_t)W * W;
        double e_plain = mean_de(plain, ref, n), e_pre = mean_de(pre, ref, n);
        printf("%s disk %dx%d vs %dx%d supersampled: mean dE00 plain %.3f, prefiltered %.3f (%.1fx closer)\n",
               light == BIREF_PE_WHITE ? "white" : "mono", W, W, K_ref, K_ref, e_plain, e_pre, e_plain / e_pre);
        CHECK(e_plain > 1.0); /* the window does alias */
        CHECK(e_pre * 3.0 <= e_plain);
    }
    free(ref);
    free(plain);
    free(pre);
}

static void prefilter_reduces_disk_moire_white(void) { disk_below_load(BIREF_PE_WHITE); }
static void prefilter_reduces_disk_moire_mono(void) { disk_below_load(BIREF_PE_MONO); }

/* A tilted view goes through the general path, which the prefilter leaves alone. */
static void tilted_view_is_not_prefiltered(void)
{
    biref_pe_setup s = disk_setup(BIREF_PE_WHITE);
    float *a = disk_picture(&s, 6, 8.0, 1, 0, 0.3), *b = disk_picture(&s, 6, 8.0, 1, 1, 0.3);
    CHECK(a && b && memcmp(a, b, 6 * 6 * 3 * sizeof *a) == 0);
    free(a);
    free(b);
}

int main(int argc, char **argv)
{
    if (biref_spectral_create(NULL, &sp, NULL, 0) != BIREF_OK || biref_phase_prefilter_create(sp, &pf) != BIREF_OK) return 1;
    static const test_case cases[] = {
        {"zero_width_is_the_point_shading", zero_width_is_the_point_shading},
        {"white_box_matches_quadrature", white_box_matches_quadrature},
        {"mono_box_matches_quadrature", mono_box_matches_quadrature},
        {"prefilter_reduces_disk_moire_white", prefilter_reduces_disk_moire_white},
        {"prefilter_reduces_disk_moire_mono", prefilter_reduces_disk_moire_mono},
        {"tilted_view_is_not_prefiltered", tilted_view_is_not_prefiltered},
    };
    int rc = test_run_cases("test_pe_antialias", cases, TEST_COUNT(cases), argc, argv);
    biref_phase_prefilter_destroy(pf);
    biref_spectral_destroy(sp);
    return rc;
}
