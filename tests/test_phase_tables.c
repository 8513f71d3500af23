/* The phase tables compiled in at build time (tools/phase_tables/gen_phase_tables.c) are the
 * same to the bit as the library's run-time quadrature, a context and a prefilter of the default
 * band use them, and any other band is built at run time. */
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"
#include "spectral/phase_prefilter.h"
#include "spectral/phase_tables.h"
#include "spectral/spectral_internal.h"
#include "spectral/table_build.h"
#include "test_cases.h"

static biref_spectral *context(biref_cmf_kind cmf, double lo, double hi)
{
    biref_spectral_config cfg;
    biref_spectral_config_default(&cfg);
    cfg.cmf = cmf;
    cfg.lambda_min_nm = lo;
    cfg.lambda_max_nm = hi;
    biref_spectral *sp = NULL;
    CHECK(biref_spectral_create(&cfg, &sp, NULL, 0) == BIREF_OK);
    return sp;
}

/* The table of a context's band by the run-time quadrature (prefilter != 0: the antiderivative's). */
static double *computed(const biref_spectral *sp, int prefilter)
{
    biref_phase_grid g;
    biref_phase_grid_init(&g, &sp->band, sp->cfg.lambda_min_nm, sp->cfg.lambda_max_nm);
    double *t = calloc((size_t)g.nodes * BIREF_TABLE_ROW, sizeof *t);
    CHECK(t != NULL);
    if (!t) return NULL;
    CHECK((prefilter ? biref_phase_table_prefilter(&g, t) : biref_phase_table_point(&g, t)) == BIREF_OK);
    return t;
}

static size_t table_bytes(const biref_spectral *sp) { return (size_t)sp->nodes * BIREF_TABLE_ROW * sizeof(double); }

static void generated_tables_are_present_in_this_build(void)
{
#ifdef BIREF_EXPECT_GENERATED_TABLES
    CHECK(biref_phase_tables_generated.nodes > 0);
#else
    CHECK(biref_phase_tables_generated.nodes == 0);
#endif
}

static void default_point_table_is_the_generated_one_and_equals_the_quadrature(void)
{
    biref_spectral *sp = context(BIREF_CMF_CIE1931, BIREF_CMF_DEFAULT_LMIN_NM, BIREF_CMF_DEFAULT_LMAX_NM);
    if (!sp) return;
    const biref_phase_tables_builtin *gen = biref_phase_tables_builtin_for(&sp->cfg, sp->nodes);
    CHECK((gen != NULL) == (biref_phase_tables_generated.nodes > 0));
    double *t = computed(sp, 0);
    if (t) {
        CHECK(memcmp(t, sp->table, table_bytes(sp)) == 0);
        if (gen) CHECK(memcmp(t, gen->point, table_bytes(sp)) == 0);
    }
    free(t);
    biref_spectral_destroy(sp);
}

static void default_prefilter_table_is_the_generated_one_and_equals_the_quadrature(void)
{
    biref_spectral *sp = context(BIREF_CMF_CIE1931, BIREF_CMF_DEFAULT_LMIN_NM, BIREF_CMF_DEFAULT_LMAX_NM);
    if (!sp) return;
    const biref_phase_tables_builtin *gen = biref_phase_tables_builtin_for(&sp->cfg, sp->nodes);
    double *t = computed(sp, 1);
    biref_phase_prefilter *pf = NULL;
    CHECK(biref_phase_prefilter_create(sp, &pf) == BIREF_OK);
    const size_t packet = (size_t)sp->nodes * BIREF_PACKET_TABLE_STRIDE;
    double *layout = malloc(packet * sizeof *layout);
    if (t && pf && layout) {
        if (gen) CHECK(memcmp(t, gen->prefilter, table_bytes(sp)) == 0);
        /* The prefilter's kernel copy is laid out from the same numbers. */
        biref_table_packet_layout(t, sp->carrier, sp->nodes, layout);
        CHECK(memcmp(layout, biref_phase_prefilter_packet_table(pf), packet * sizeof *layout) == 0);
    }
    free(layout);
    biref_phase_prefilter_destroy(pf);
    free(t);
    biref_spectral_destroy(sp);
}

/* Another band or another set of colour-matching functions is never given the default tables
 * (and, outside the quick run, such a context's table is the quadrature's). */
static void other_bands_are_built_at_run_time(void)
{
    biref_spectral_config cfg;
    biref_spectral_config_default(&cfg);
    const int nodes = biref_phase_tables_generated.nodes;
    CHECK((biref_phase_tables_builtin_for(&cfg, nodes) != NULL) == (nodes > 0));
    CHECK(biref_phase_tables_builtin_for(&cfg, nodes + 1) == NULL);
    cfg.cmf = BIREF_CMF_WYMAN2013;
    CHECK(biref_phase_tables_builtin_for(&cfg, nodes) == NULL);
    biref_spectral_config_default(&cfg);
    cfg.lambda_min_nm = 400.0;
    CHECK(biref_phase_tables_builtin_for(&cfg, nodes) == NULL);
    biref_spectral_config_default(&cfg);
    cfg.lambda_max_nm = 699.0;
    CHECK(biref_phase_tables_builtin_for(&cfg, nodes) == NULL);
    if (test_quick()) return;
    biref_spectral *sp = context(BIREF_CMF_CIE1931, 400.0, BIREF_CMF_DEFAULT_LMAX_NM);
    if (!sp) return;
    double *t = computed(sp, 0);
    if (t) CHECK(memcmp(t, sp->table, table_bytes(sp)) == 0);
    free(t);
    biref_spectral_destroy(sp);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"generated_tables_are_present_in_this_build", generated_tables_are_present_in_this_build},
        {"default_point_table_is_the_generated_one_and_equals_the_quadrature",
         default_point_table_is_the_generated_one_and_equals_the_quadrature},
        {"default_prefilter_table_is_the_generated_one_and_equals_the_quadrature",
         default_prefilter_table_is_the_generated_one_and_equals_the_quadrature},
        {"other_bands_are_built_at_run_time", other_bands_are_built_at_run_time},
    };
    return test_run_cases("test_phase_tables", cases, TEST_COUNT(cases), argc, argv);
}
