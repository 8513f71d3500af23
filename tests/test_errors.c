/* The error convention (include/biref/common.h): a function that can fail for several reasons
 * writes one line saying which into the caller's buffer, accepts NULL/0 for "not wanted",
 * truncates rather than overflows, and leaves the buffer alone on success. The same bad input
 * in two threads gives each its own message (no shared error state). */
#include <math.h>
#include <omp.h>
#include <string.h>

#include "biref/biref.h"
#include "test_cases.h"

#define UNTOUCHED "untouched"

/* One line: non-empty, no newline, NUL-terminated within the buffer. */
static int one_line(const char *msg, size_t cap)
{
    const size_t n = strnlen(msg, cap);
    return n > 0 && n < cap && !strchr(msg, '\n');
}

static void test_spectral_create_refuses_bad_ranges_in_one_line(void)
{
    char msg[BIREF_MSG_SIZE];
    biref_spectral *sp = NULL;
    biref_spectral_config cfg;
    biref_spectral_config_default(&cfg);
    cfg.lambda_min_nm = 700, cfg.lambda_max_nm = 380;
    CHECK(biref_spectral_create(&cfg, &sp, msg, sizeof msg) == BIREF_ERR_INVALID && !sp);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "700-380 nm"));
    cfg.lambda_min_nm = 300, cfg.lambda_max_nm = 700;
    CHECK(biref_spectral_create(&cfg, &sp, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "not covered") && strstr(msg, "380-780 nm"));
    cfg.cmf = (biref_cmf_kind)7;
    CHECK(biref_spectral_create(&cfg, &sp, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "colour-matching"));
    /* Not wanted: NULL or 0. */
    CHECK(biref_spectral_create(&cfg, &sp, NULL, 0) == BIREF_ERR_INVALID);
    strcpy(msg, UNTOUCHED);
    CHECK(biref_spectral_create(&cfg, &sp, msg, 0) == BIREF_ERR_INVALID && !strcmp(msg, UNTOUCHED));
    /* A short buffer gets the start of the line, terminated. */
    char tiny[8];
    memset(tiny, 'x', sizeof tiny);
    CHECK(biref_spectral_create(&cfg, &sp, tiny, sizeof tiny) == BIREF_ERR_INVALID);
    CHECK(strnlen(tiny, sizeof tiny) == sizeof tiny - 1);
    /* Success leaves the buffer alone. */
    strcpy(msg, UNTOUCHED);
    CHECK(biref_spectral_create(NULL, &sp, msg, sizeof msg) == BIREF_OK && sp && !strcmp(msg, UNTOUCHED));
    biref_spectral_destroy(sp);
}

static void test_integrator_and_plan_refuse_bad_options_in_one_line(void)
{
    char msg[BIREF_MSG_SIZE];
    biref_spectral *sp = NULL;
    CHECK(biref_spectral_create(NULL, &sp, NULL, 0) == BIREF_OK);
    biref_integrator_options o;
    biref_integrator_options_default(&o);
    biref_integrator *it = NULL;
    o.method = BIREF_METHOD_NUMERIC;
    o.samples = 0;
    CHECK(biref_integrator_create(sp, &o, &it, msg, sizeof msg) == BIREF_ERR_INVALID && !it);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "0 samples"));
    o.method = BIREF_METHOD_EXPANSION;
    o.expansion.order = 99;
    CHECK(biref_integrator_create(sp, &o, &it, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "order 99"));
    o.expansion.order = -1;
    o.expansion.tolerance = 2.0;
    CHECK(biref_integrator_create(sp, &o, &it, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "tolerance"));
    o.method = (biref_method)42;
    CHECK(biref_integrator_create(sp, &o, &it, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "method"));
    biref_numeric_plan *plan = NULL;
    CHECK(biref_numeric_plan_create(sp, -3, &plan, msg, sizeof msg) == BIREF_ERR_INVALID && !plan);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "-3 samples"));
    biref_spectral_destroy(sp);
}

static void test_cmf_band_refuses_empty_or_unknown_bands_in_one_line(void)
{
    char msg[BIREF_MSG_SIZE];
    biref_cmf_band band;
    double integral[3];
    CHECK(biref_cmf_band_integrals(BIREF_CMF_CIE1931, 500, 500, integral, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "500-500 nm"));
    CHECK(biref_cmf_band_integrals((biref_cmf_kind)5, 380, 700, integral, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "unknown"));
    /* Outside the table every function is zero: nothing to normalise by. */
    CHECK(biref_cmf_band_init(&band, BIREF_CMF_CIE1931, 800, 900, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "zero"));
}

static void test_photoelastic_render_refuses_bad_setups_in_one_line(void)
{
    char msg[BIREF_MSG_SIZE];
    biref_pe_setup s;
    memset(&s, 0, sizeof s);
    CHECK(biref_pe_material_preset("polycarbonate", &s.material) == BIREF_OK);
    s.thickness = 6e-3;
    s.eta_i = 1.0;
    s.light = BIREF_PE_MONO;
    s.lambda_nm = 589;
    biref_pe_polariscope_make(BIREF_PE_CIRCULAR, BIREF_PE_DARK, 0.0, &s.pol);
    biref_pe_field f;
    CHECK(biref_pe_field_disk(&f, 0.025, 6e-3, 500, msg, sizeof msg) == BIREF_OK);
    biref_pe_image_opts o = {.width = 4, .height = 4, .supersample = 1, .threads = 1, .tint = {1, 1, 1}, .tilt = 0.0};
    float img[4 * 4 * 3], map[4 * 4];
    o.supersample = BIREF_PE_MAX_SUPERSAMPLE + 1;
    CHECK(biref_pe_render(&s, NULL, &f, &o, img, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "supersampling"));
    o.supersample = 1;
    o.tilt = 1.6;
    CHECK(biref_pe_render(&s, NULL, &f, &o, img, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "tilt"));
    o.tilt = 0.0;
    s.light = BIREF_PE_WHITE;
    CHECK(biref_pe_render(&s, NULL, &f, &o, img, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "spectral context"));
    strcpy(msg, UNTOUCHED);
    s.light = BIREF_PE_MONO;
    CHECK(biref_pe_render(&s, NULL, &f, &o, img, msg, sizeof msg) == BIREF_OK && !strcmp(msg, UNTOUCHED));
    CHECK(biref_pe_render_map(&s, &f, BIREF_PE_MAP_FRINGE_ORDER, -1.0, 4, 4, 1, map, msg, sizeof msg) ==
          BIREF_ERR_INVALID);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "wavelength"));
    CHECK(biref_pe_render_map(&s, &f, BIREF_PE_MAP_FRINGE_ORDER, 589, 0, 4, 1, map, msg, sizeof msg) ==
          BIREF_ERR_INVALID);
    CHECK(one_line(msg, sizeof msg) && strstr(msg, "0 x 4"));
}

/* Each thread's buffer gets its own call's reason, whatever the others do meanwhile. */
static void test_messages_belong_to_their_call_across_threads(void)
{
    enum { N = 64 };
    static char msgs[N][BIREF_MSG_SIZE];
    int bad = 0;
#pragma omp parallel for num_threads(4) reduction(+ : bad)
    for (int i = 0; i < N; i++) {
        biref_spectral *sp = NULL;
        biref_spectral_config cfg;
        biref_spectral_config_default(&cfg);
        cfg.lambda_min_nm = 700 + i, cfg.lambda_max_nm = 380;
        char want[64];
        snprintf(want, sizeof want, "%d-380 nm", 700 + i);
        bad += biref_spectral_create(&cfg, &sp, msgs[i], sizeof msgs[i]) != BIREF_ERR_INVALID ||
               !strstr(msgs[i], want);
    }
    CHECK(bad == 0);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"spectral_create_refuses_bad_ranges_in_one_line", test_spectral_create_refuses_bad_ranges_in_one_line},
        {"integrator_and_plan_refuse_bad_options_in_one_line", test_integrator_and_plan_refuse_bad_options_in_one_line},
        {"cmf_band_refuses_empty_or_unknown_bands_in_one_line",
         test_cmf_band_refuses_empty_or_unknown_bands_in_one_line},
        {"photoelastic_render_refuses_bad_setups_in_one_line", test_photoelastic_render_refuses_bad_setups_in_one_line},
        {"messages_belong_to_their_call_across_threads", test_messages_belong_to_their_call_across_threads},
    };
    return test_run_cases("test_errors", cases, TEST_COUNT(cases), argc, argv);
}
