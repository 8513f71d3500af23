/* The dispersive-material options of the slab commands: --material NAME, a Sellmeier or Cauchy
 * formula per index, or a CSV table; the checks of a material at a wavelength or over a band. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"

/* Up to max comma-separated finite numbers, no empty field. Returns the count or -1 (error printed). */
static int parse_numbers(const char *cmd, const char *opt, const char *text, double *out, int max)
{
    int n = 0;
    for (const char *p = text;;) {
        char *end;
        errno = 0;
        const double v = strtod(p, &end);
        if (end == p || errno == ERANGE || !isfinite(v) || n == max || (*end && *end != ','))
            return cli_error(cmd, "%s: expected up to %d comma-separated finite numbers, got '%s'", opt, max, text), -1;
        out[n++] = v;
        if (!*end) return n;
        p = end + 1;
    }
}

/* --sellmeier-X B1,C1,... (n^2 = 1 + sum) or --cauchy-X A,B,... into formula f. */
static int parse_formula(const char *cmd, const char *opt, int sellmeier, const char *text, biref_index_formula *f)
{
    double v[2 * BIREF_FORMULA_MAX_TERMS + 1];
    const int n = parse_numbers(cmd, opt, text, v, sellmeier ? 2 * BIREF_FORMULA_MAX_TERMS : BIREF_FORMULA_MAX_TERMS + 1);
    if (n < 0) return -1;
    memset(f, 0, sizeof *f);
    if (sellmeier) {
        if (n % 2) return cli_error(cmd, "%s: expected pairs B,C (got %d numbers)", opt, n), -1;
        f->kind = BIREF_FORMULA_SELLMEIER;
        f->a = 1.0;
        f->n_terms = n / 2;
        for (int i = 0; i < f->n_terms; i++) {
            f->b[i] = v[2 * i];
            f->c[i] = v[2 * i + 1];
        }
        return 0;
    }
    if (n < 2) return cli_error(cmd, "%s: expected A,B[,C...] (at least 2 numbers)", opt), -1;
    f->kind = BIREF_FORMULA_CAUCHY;
    f->a = v[0];
    f->n_terms = n - 1;
    for (int i = 1; i < n; i++) f->b[i - 1] = v[i];
    return 0;
}

/* Records that option `name` gives index c (0 = o, 1 = e, 2 = both); a second source is an error. */
static int claim(const char *cmd, cli_slab_opts *o, int c, const char *name)
{
    for (int k = 0; k < 2; k++) {
        if (c != 2 && k != c) continue;
        if (o->index_source[k])
            return cli_error(cmd, "%s: %s already given by %s", name, k ? "n_e" : "n_o", o->index_source[k]), -1;
    }
    for (int k = 0; k < 2; k++)
        if (c == 2 || k == c) o->index_source[k] = name;
    return 0;
}

int cli_dispersion_handle(const char *cmd, cli_slab_opts *o, int code, const char *arg)
{
    switch (code) {
    case OPT_SLAB_MATERIAL:
        if (claim(cmd, o, 2, "--material")) return -1;
        o->material_name = arg;
        return 1;
    case OPT_DISPERSION_CSV:
        if (claim(cmd, o, 2, "--dispersion-csv")) return -1;
        o->dispersion_csv = arg;
        return 1;
    case OPT_SELLMEIER_O:
    case OPT_SELLMEIER_E:
    case OPT_CAUCHY_O:
    case OPT_CAUCHY_E: {
        const int e = code == OPT_SELLMEIER_E || code == OPT_CAUCHY_E;
        const int sellmeier = code == OPT_SELLMEIER_O || code == OPT_SELLMEIER_E;
        const char *name = sellmeier ? (e ? "--sellmeier-e" : "--sellmeier-o") : (e ? "--cauchy-e" : "--cauchy-o");
        if (claim(cmd, o, e, name) || parse_formula(cmd, name, sellmeier, arg, &o->formula[e])) return -1;
        o->have_formula[e] = 1;
        return 1;
    }
    default: return 0;
    }
}

const char *cli_slab_dispersion_option(const cli_slab_opts *o)
{
    for (int c = 0; c < 2; c++)
        if (o->index_source[c] && strcmp(o->index_source[c], c ? "--eta-e" : "--eta-o")) return o->index_source[c];
    return NULL;
}

int cli_dispersion_finish(const char *cmd, cli_slab_opts *o)
{
    char why[BIREF_MSG_SIZE];
    biref_status s = BIREF_OK;
    if (o->material_name) {
        o->material = biref_material_find(o->material_name);
        if (!o->material)
            return cli_error(cmd, "--material: unknown material '%s' (biref material list names them)", o->material_name),
                   -1;
    } else if (o->dispersion_csv) {
        s = biref_material_load_csv(o->dispersion_csv, &o->owned_material, why, sizeof why);
        if (s != BIREF_OK) return cli_error(cmd, "--dispersion-csv: %s", why), -1;
        o->material = o->owned_material;
    } else if (o->have_formula[0] || o->have_formula[1]) {
        if (!o->index_source[0] || !o->index_source[1])
            return cli_error(cmd, "missing %s (or --sellmeier-%c, --cauchy-%c)", o->index_source[0] ? "--eta-e" : "--eta-o",
                             o->index_source[0] ? 'e' : 'o', o->index_source[0] ? 'e' : 'o'),
                   -1;
        /* A constant index beside a formula is the formula n = eta. */
        biref_index_formula f[2];
        for (int c = 0; c < 2; c++)
            f[c] = o->have_formula[c] ? o->formula[c]
                                      : (biref_index_formula){.kind = BIREF_FORMULA_CAUCHY,
                                                              .a = c ? o->slab.eta_e : o->slab.eta_o};
        s = biref_material_from_formulas("user formula", &f[0], &f[1], NULL, &o->owned_material, why, sizeof why);
        if (s != BIREF_OK) return cli_error(cmd, "%s", why), -1;
        o->material = o->owned_material;
    }
    if (o->material) o->slab.eta_o = o->slab.eta_e = 1.5; /* stand-ins for the geometry's check */
    return 0;
}

/* Warns about the part of [lo, hi] outside the material's valid range. */
static void warn_extrapolated(const char *cmd, const biref_material *m, double lo, double hi)
{
    double ex[2][2];
    const int n = biref_material_extrapolated(m, lo, hi, ex);
    biref_material_info info;
    biref_material_get_info(m, &info);
    for (int i = 0; i < n; i++) {
        if (ex[i][0] == ex[i][1])
            fprintf(stderr, "biref %s: warning: %s: %g nm is outside the valid range %g-%g nm (extrapolated)\n", cmd,
                    info.name, ex[i][0], info.range_nm[0], info.range_nm[1]);
        else
            fprintf(stderr, "biref %s: warning: %s: %g-%g nm is outside the valid range %g-%g nm (extrapolated)\n", cmd,
                    info.name, ex[i][0], ex[i][1], info.range_nm[0], info.range_nm[1]);
    }
}

int cli_slab_check_band(const char *cmd, const cli_slab_opts *o, double lo_nm, double hi_nm)
{
    if (!o->material) return 0;
    char why[BIREF_MSG_SIZE];
    if (biref_material_check_band(o->material, lo_nm, hi_nm, why, sizeof why) != BIREF_OK)
        return cli_error(cmd, "%s", why), -1;
    warn_extrapolated(cmd, o->material, lo_nm, hi_nm);
    return 0;
}

int cli_slab_at(const char *cmd, const cli_slab_opts *o, double lambda_nm, biref_slab *out)
{
    if (!o->material) {
        *out = o->slab;
        return 0;
    }
    if (cli_slab_check_band(cmd, o, lambda_nm, lambda_nm)) return -1;
    biref_material_slab_at(o->material, &o->slab, lambda_nm, out); /* physical there: checked */
    return 0;
}
