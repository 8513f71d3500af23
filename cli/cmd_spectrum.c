/* biref spectrum: band-normalised XYZ of one slab at one angle (paper §5), by the analytic
 * approximation (eq. 26), by N-sample numeric integration of eq. 17, by the ground truth, or by
 * the exact integral of the path-group expansion; any incident polarisation and analyzer. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "cli_common.h"
#include "cli_light.h"
#include "cli_polarizer.h"
#include "commands.h"
#include "json_out.h"
#include "spectrum_stack.h"

static const char *const CMD = "spectrum";
static const char *const SP[2] = {"s", "p"};

enum {
    DEFAULT_NUMERIC_SAMPLES = 64,
    /* The numeric plan allocates two arrays of this many entries; beyond it a run would take
     * minutes per evaluation and say nothing the ground truth does not. */
    MAX_SAMPLES = 1 << 24
};

enum {
    OPT_METHOD = OPT_SLAB_LAST + 1,
    OPT_CMF,
    OPT_RANGE,
    OPT_POL,
    OPT_ANALYZER,
    OPT_ORDER,
    OPT_TOLERANCE,
    OPT_POLARIZER,
    OPT_STOKES
};

static int all_finite(const biref_spectrum *s)
{
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++)
            for (int j = 0; j < 3; j++)
                if (!isfinite(s->T[i][o][j]) || !isfinite(s->R[i][o][j])) return 0;
    return 1;
}

/* The command line, parsed. */
typedef struct {
    cli_slab_opts so;
    biref_spectral_config cfg;
    biref_method method;
    long samples; /* 0: not given */
    cli_light light;
    int json;
    biref_expansion_opts eopts;
    int have_order, have_tol;
    /* General polarisation: Stokes input and/or an analyzer projector. */
    int general_in, general_an;
    double stokes[4];
    double complex P_an[2][2];
    char pol_text[64], an_text[64];
    const char *stack_file; /* --stack: a stack file instead of the slab options */
} spectrum_args;

/* What is printed. */
typedef struct {
    int n_samples; /* numeric methods, else 0 */
    biref_slab_state st;
    biref_spectrum spec;
    double T_xyz[3], R_xyz[3], T_rgb[3], R_rgb[3];
    int order_used[2];
} spectrum_result;

/* One option of the command. Returns 0, or -1 after one error line. */
static int handle(void *args, int c, const char *arg)
{
    spectrum_args *a = args;
    int r = cli_slab_opts_handle(CMD, &a->so, c, arg);
    if (r) return r < 0 ? -1 : 0;
    switch (c) {
    case OPT_METHOD:
        if (biref_method_from_name(arg, &a->method) != BIREF_OK)
            return cli_error(CMD,
                             "--method: expected analytic, analytic-pairs, numeric, ground-truth or expansion, got '%s'",
                             arg),
                   -1;
        return 0;
    case OPT_CMF:
        if (biref_cmf_kind_from_name(arg, &a->cfg.cmf) != BIREF_OK)
            return cli_error(CMD, "--cmf: expected cie1931 or wyman2013, got '%s'", arg), -1;
        return 0;
    case OPT_RANGE: {
        double r2[2];
        if (cli_parse_range_nm(CMD, "--range-nm", arg, r2)) return -1;
        a->cfg.lambda_min_nm = r2[0];
        a->cfg.lambda_max_nm = r2[1];
        return 0;
    }
    case OPT_POL: return cli_parse_polarization(CMD, "--polarization", arg, a->light.w_in) ? -1 : 0;
    case OPT_ANALYZER: {
        int g = cli_parse_general_analyzer(CMD, "--analyzer", arg, a->P_an);
        if (g < 0) return -1;
        if (g > 0) {
            a->general_an = 1;
            snprintf(a->an_text, sizeof a->an_text, "%s", arg);
        } else if (cli_parse_analyzer(CMD, "--analyzer", arg, a->light.mask)) {
            return -1;
        }
        return 0;
    }
    case OPT_POLARIZER:
        if (cli_parse_polarizer_state(CMD, "--polarizer", arg, a->stokes)) return -1;
        a->general_in = 1;
        snprintf(a->pol_text, sizeof a->pol_text, "%s", arg);
        return 0;
    case OPT_STOKES:
        if (cli_parse_stokes(CMD, "--stokes", arg, a->stokes)) return -1;
        a->general_in = 1;
        snprintf(a->pol_text, sizeof a->pol_text, "stokes:%s", arg);
        return 0;
    case OPT_ORDER:
        if (cli_parse_expansion_order(CMD, arg, &a->eopts)) return -1;
        a->have_order = 1;
        return 0;
    case OPT_TOLERANCE:
        if (cli_parse_expansion_tolerance(CMD, arg, &a->eopts)) return -1;
        a->have_tol = 1;
        return 0;
    default: return -1;
    }
}

#define F(field) offsetof(spectrum_args, field)
static const cli_opt OPTS[] = {
    CLI_SLAB_OPTIONS,
    CLI_CUSTOM("method", "M", OPT_METHOD,
               "analytic (default; paper eq. 26), analytic-pairs (eq. 26 plus\n"
               "transmission's sibling and entry pairs, beyond the paper),\n"
               "numeric (N samples of eq. 17),\n"
               "ground-truth (numeric, 16384 samples) or expansion (exact integral\n"
               "of the path-group expansion, docs/PHYSICS.md §5)"),
    CLI_INT("spectral-samples", "N", F(samples), 1, MAX_SAMPLES,
            "samples of the numeric method, N >= 1 (default 64; numeric only)"),
    CLI_EXPANSION_OPTIONS(OPT_ORDER, OPT_TOLERANCE),
    CLI_CUSTOM("cmf", "C", OPT_CMF, "cie1931 (default, tabulated) or wyman2013 (analytic fit)"),
    CLI_CUSTOM("range-nm", "MIN,MAX", OPT_RANGE, "integration band in nm (default 380,700)"),
    CLI_CUSTOM("polarization", "P", OPT_POL,
               "incident light: s, p, unpolarized (default) or S,P weights\n"
               "(normalised to sum 1, e.g. 0.75,0.25)"),
    CLI_CUSTOM("polarizer", "P", OPT_POLARIZER,
               "fully polarised input: linear:DEG (from s towards p) or\n"
               "circular:+1|-1 (sign of S3); replaces --polarization"),
    CLI_CUSTOM("stokes", "S0,S1,S2,S3", OPT_STOKES, "any (partially) polarised input in the s/p basis"),
    CLI_CUSTOM("analyzer", "A", OPT_ANALYZER,
               "none (default), s, p, linear:DEG or circular:+1|-1"),
    CLI_STRING("stack", 0, "FILE", F(stack_file),
               "a stack of layers (docs/STACKS.md) instead of the slab options:\n"
               "methods expansion (default), numeric, ground-truth"),
    CLI_FLAG("json", 0, F(json), "machine-readable output"),
    {.name = "samples", .kind = CLI_OPT_INT, .value = "N", .offset = F(samples), .lo = 1, .hi = MAX_SAMPLES,
     .old_of = "spectral-samples"},
};
#undef F

static const char *const EXCLUSIVE[] = {CLI_SLAB_EXCLUSIVE, "polarization polarizer stokes", NULL};

const cli_command_spec CLI_SPECTRUM = {
    "spectrum",
    "usage: biref spectrum [OPTIONS]\n\n"
    "Colour of the light transmitted (T) and reflected (R) by a uniaxial slab at one angle:\n"
    "band-normalised CIE XYZ (a flat spectrum gives 1,1,1; white E) for each input/output\n"
    "polarisation pair, and the mixed colour for a given incident light and analyzer.\n\n"
    "Options:\n",
    OPTS,
    CLI_OPTS_COUNT(OPTS),
    "sRGB values are encoded (non-linear) and not clamped: out-of-gamut colours fall outside\n"
    "[0, 1]. Only the terminal swatch is clamped.\n\n"
    "Example:\n  biref spectrum --eta-o 1.775 --eta-e 1.231 --axis 0.084,0.979,-0.187 \\\n"
    "                --thickness-um 20 --theta-deg 30 --polarization 0.02,0.98 --analyzer s\n",
    0,
    handle,
    0,
    EXCLUSIVE,
};

/* Options that only make sense together. Returns 0 or -1 (one error line printed). */
static int check_args(spectrum_args *a)
{
    /* --spectral-samples with another method would be silently ignored; refuse it so a typo in --method
     * cannot masquerade as a numeric run. */
    if (a->samples && a->method != BIREF_METHOD_NUMERIC)
        return cli_error(CMD, "--spectral-samples: only valid with --method numeric (method is %s)",
                         biref_method_name(a->method)),
               -1;
    if ((a->have_order || a->have_tol) && a->method != BIREF_METHOD_EXPANSION)
        return cli_error(CMD, "%s: only valid with --method expansion", a->have_order ? "--order" : "--tolerance"), -1;
    if (a->have_order && a->have_tol) return cli_error(CMD, "--order and --tolerance exclude each other"), -1;
    if (!a->general_in) {
        /* The s/p fractions as a (diagonal) Stokes vector, for the output. */
        a->stokes[0] = 1.0;
        a->stokes[1] = a->light.w_in[0] - a->light.w_in[1];
    }
    if (!a->general_an) {
        memset(a->P_an, 0, sizeof a->P_an);
        a->P_an[0][0] = a->light.mask[0];
        a->P_an[1][1] = a->light.mask[1];
    }
    if (a->stack_file) {
        char msg[200];
        if (biref_theta_check(a->so.theta_deg * M_PI / 180.0, msg, sizeof msg) != BIREF_OK)
            return cli_error(CMD, "--theta-deg: %s", msg), -1;
        return 0;
    }
    return cli_slab_opts_finish(CMD, &a->so);
}

/* --stack replaces the slab options, and its default method is the expansion (the paper's
 * analytic method is for one slab). Returns 0 or -1 (one error line printed). */
static int check_stack_args(spectrum_args *a, const cli_parsed *p)
{
    static const char *const slab_opts[] = {"eta-o",        "eta-e",        "axis",       "thickness-um",
                                            "thickness-mm", "thickness-nm", "eta-i",      "material",
                                            "sellmeier-o",  "sellmeier-e",  "cauchy-o",   "cauchy-e",
                                            "dispersion-csv"};
    for (size_t k = 0; k < sizeof slab_opts / sizeof *slab_opts; k++)
        if (cli_opts_given(&CLI_SPECTRUM, p, slab_opts[k]))
            return cli_error(CMD, "--%s: not valid with --stack (the stack file gives the layers and eta_i)",
                             slab_opts[k]),
                   -1;
    if (!cli_opts_given(&CLI_SPECTRUM, p, "method")) a->method = BIREF_METHOD_EXPANSION;
    if (a->method == BIREF_METHOD_ANALYTIC || a->method == BIREF_METHOD_ANALYTIC_PAIRS)
        return cli_error(CMD, "--method %s: not valid with --stack (the paper's eq. 26 is for one slab; use "
                              "expansion, numeric or ground-truth)",
                         biref_method_name(a->method)),
               -1;
    if (a->have_order) return cli_error(CMD, "--order: not valid with --stack (the stack's expansion takes --tolerance)"), -1;
    return 0;
}

/* Returns 0 to go on, 1 after --help, -1 on bad usage (one error line printed). */
static int parse(int argc, char **argv, spectrum_args *a)
{
    memset(a, 0, sizeof *a);
    cli_slab_opts_init(&a->so);
    biref_spectral_config_default(&a->cfg);
    a->method = BIREF_METHOD_ANALYTIC;
    cli_light_default(&a->light);
    biref_expansion_opts_default(&a->eopts);
    a->stokes[0] = 1.0;
    cli_parsed p;
    int r = cli_opts_parse(&CLI_SPECTRUM, a, argc, argv, &p);
    if (r) return r;
    if (p.n_args) return cli_error(CMD, "unexpected argument '%s'", argv[p.first_arg]), -1;
    if (a->stack_file && check_stack_args(a, &p)) return -1;
    return check_args(a);
}

/* The light of the mixed colour: the paper's s/p model unless a general state or analyzer was
 * asked for. */
static void make_light(const spectrum_args *a, biref_light *l)
{
    if (!a->general_in && !a->general_an) {
        biref_light_sp(a->light.w_in, a->light.mask, l); /* validated when parsed */
        return;
    }
    biref_light_stokes(a->stokes, l); /* validated when parsed */
    biref_light_set_analyzer(l, (const double complex(*)[2])a->P_an);
}

/* The detected colours of both sides into the result, XYZ and sRGB. */
static void store_mixed(const biref_integration *mixed, spectrum_result *res)
{
    memcpy(res->T_xyz, mixed->T, sizeof res->T_xyz);
    memcpy(res->R_xyz, mixed->R, sizeof res->R_xyz);
    memcpy(res->order_used, mixed->order_used, sizeof res->order_used);
    biref_xyz_to_srgb(res->T_xyz, res->T_rgb);
    biref_xyz_to_srgb(res->R_xyz, res->R_rgb);
}

/* A dispersive slab (material.h): the numeric methods sample n(λ), the closed-form ones linearise
 * each band's phases or integrate exactly where that fails. */
static int compute_dispersive(const spectrum_args *a, const biref_integrator *it, const biref_light *light,
                              spectrum_result *res)
{
    if (cli_slab_check_band(CMD, &a->so, a->cfg.lambda_min_nm, a->cfg.lambda_max_nm)) return CLI_EXIT_USAGE;
    const double theta = a->so.theta_deg * M_PI / 180.0;
    biref_integration mixed;
    biref_status s = biref_integrate_material_spectrum(it, a->so.material, &a->so.slab, theta, &res->spec);
    if (s == BIREF_OK)
        s = biref_integrate_material(it, a->so.material, &a->so.slab, theta, BIREF_SIDE_BOTH, light, &mixed);
    if (s == BIREF_ERR_ILLCOND) return cli_error(CMD, "numerical failure (non-finite result)"), CLI_EXIT_FAIL;
    if (s != BIREF_OK) return cli_error(CMD, "integration: %s", biref_status_string(s)), CLI_EXIT_FAIL;
    store_mixed(&mixed, res);
    return CLI_EXIT_OK;
}

/* The integration. Returns a CLI exit code (one error line printed unless OK). */
static int compute(const spectrum_args *a, spectrum_result *res)
{
    memset(res, 0, sizeof *res);
    res->n_samples = a->method == BIREF_METHOD_NUMERIC        ? (a->samples ? (int)a->samples : DEFAULT_NUMERIC_SAMPLES)
                     : a->method == BIREF_METHOD_GROUND_TRUTH ? BIREF_GROUND_TRUTH_SAMPLES
                                                              : 0;
    const double theta = a->so.theta_deg * M_PI / 180.0;
    /* A dispersive slab is prepared per sample (compute_dispersive); st stays unused. */
    biref_status s = a->so.material ? BIREF_OK : biref_slab_prepare(&a->so.slab, theta, &res->st);
    if (s != BIREF_OK) return cli_error(CMD, "%s", biref_status_string(s)), CLI_EXIT_FAIL;

    biref_spectral *sp = NULL;
    char why[BIREF_MSG_SIZE];
    s = biref_spectral_create(&a->cfg, &sp, why, sizeof why);
    if (s == BIREF_ERR_INVALID) return cli_error(CMD, "--range-nm: %s", why), CLI_EXIT_USAGE;
    if (s != BIREF_OK) return cli_error(CMD, "spectral context: %s", why), CLI_EXIT_FAIL;

    biref_integrator_options io;
    biref_integrator_options_default(&io);
    io.method = a->method;
    if (a->method == BIREF_METHOD_NUMERIC) io.samples = res->n_samples;
    io.expansion = a->eopts;
    biref_integrator *it = NULL;
    s = biref_integrator_create(sp, &io, &it, why, sizeof why);
    if (s != BIREF_OK) {
        biref_spectral_destroy(sp);
        return cli_error(CMD, "%s", why), CLI_EXIT_FAIL;
    }
    biref_light light;
    make_light(a, &light);
    if (a->so.material) {
        const int rc = compute_dispersive(a, it, &light, res);
        biref_integrator_destroy(it);
        biref_spectral_destroy(sp);
        return rc;
    }
    biref_integration mixed;
    s = biref_integrate_spectrum(it, &res->st, &res->spec);
    biref_status sm = s == BIREF_OK ? biref_integrate(it, &res->st, BIREF_SIDE_BOTH, &light, &mixed) : s;
    biref_integrator_destroy(it);
    biref_spectral_destroy(sp);
    if (s != BIREF_OK || (sm != BIREF_OK && sm != BIREF_ERR_ILLCOND))
        return cli_error(CMD, "expansion: %s", biref_status_string(s != BIREF_OK ? s : sm)), CLI_EXIT_FAIL;
    if (sm != BIREF_OK || !all_finite(&res->spec))
        return cli_error(CMD, "numerical failure (non-finite result)"), CLI_EXIT_FAIL;
    store_mixed(&mixed, res);
    return CLI_EXIT_OK;
}

static void names(const spectrum_args *a, char polbuf[48], const char **pol_name, const char **an_name)
{
    *pol_name = a->general_in ? a->pol_text : cli_polarization_name(a->light.w_in, polbuf, 48);
    *an_name = a->general_an ? a->an_text : cli_analyzer_name(a->light.mask);
}

static int print_json(const spectrum_args *a, const spectrum_result *res)
{
    char polbuf[48];
    const char *pol_name, *an_name;
    names(a, polbuf, &pol_name, &an_name);
    const biref_slab *slab = &a->so.slab;
    cJSON *root = json_spectrum_head(a->method, res->n_samples, &a->cfg);
    const double range[2] = {a->cfg.lambda_min_nm, a->cfg.lambda_max_nm};
    cJSON *in = cJSON_AddObjectToObject(root, "input");
    if (a->so.material) {
        cJSON_AddItemToObject(in, "material", json_dispersive_material(a->so.material, range[0], range[1]));
        cJSON_AddNullToObject(in, "eta_o"); /* n(λ), sampled */
        cJSON_AddNullToObject(in, "eta_e");
    } else {
        cJSON_AddNullToObject(in, "material");
        cJSON_AddNumberToObject(in, "eta_o", slab->eta_o);
        cJSON_AddNumberToObject(in, "eta_e", slab->eta_e);
    }
    cJSON_AddItemToObject(in, "axis", json_vec3(slab->axis));
    cJSON_AddNumberToObject(in, "thickness_nm", slab->thickness_nm);
    cJSON_AddNumberToObject(in, "theta_deg", a->so.theta_deg);
    cJSON_AddNumberToObject(in, "eta_i", slab->eta_i);
    if (a->so.material)
        cJSON_AddNullToObject(root, "total_reflection"); /* per sample */
    else
        cJSON_AddBoolToObject(root, "total_reflection", res->st.total_reflection);
    cJSON_AddItemToObject(root, "T", json_sp_xyz_pairs(res->spec.T));
    cJSON_AddItemToObject(root, "R", json_sp_xyz_pairs(res->spec.R));
    cJSON *mx = cJSON_AddObjectToObject(root, "mixed");
    cJSON *pol = cJSON_AddObjectToObject(mx, "polarization");
    if (!a->general_in) {
        cJSON_AddNumberToObject(pol, "s", a->light.w_in[0]);
        cJSON_AddNumberToObject(pol, "p", a->light.w_in[1]);
    } else {
        cJSON_AddStringToObject(pol, "state", a->pol_text);
    }
    cJSON_AddItemToObject(pol, "stokes", cJSON_CreateDoubleArray(a->stokes, 4));
    if (a->method == BIREF_METHOD_EXPANSION) {
        cJSON *ord = cJSON_AddObjectToObject(root, "expansion_order");
        cJSON_AddNumberToObject(ord, "T", res->order_used[0]);
        cJSON_AddNumberToObject(ord, "R", res->order_used[1]);
    }
    cJSON_AddStringToObject(mx, "analyzer", an_name);
    cJSON_AddItemToObject(mx, "T_xyz", json_vec3(res->T_xyz));
    cJSON_AddItemToObject(mx, "R_xyz", json_vec3(res->R_xyz));
    cJSON_AddItemToObject(mx, "T_srgb", json_vec3(res->T_rgb));
    cJSON_AddItemToObject(mx, "R_srgb", json_vec3(res->R_rgb));
    cJSON_AddStringToObject(mx, "srgb_note", "encoded sRGB (IEC 61966-2-1), white E -> (1,1,1), not clamped");
    return json_print_and_free(root) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

static int print_text(const spectrum_args *a, const spectrum_result *res)
{
    char polbuf[48];
    const char *pol_name, *an_name;
    names(a, polbuf, &pol_name, &an_name);
    const biref_slab *slab = &a->so.slab;
    const char *cmf_name = biref_cmf_kind_name(a->cfg.cmf);
    if (a->so.material) {
        biref_material_info info;
        biref_material_get_info(a->so.material, &info);
        printf("slab: material %s (n_o, n_e at every sample), axis (%.4f, %.4f, %.4f), d %.6g um, eta_i %.4g, "
               "theta %.4g deg\n",
               info.name, slab->axis[0], slab->axis[1], slab->axis[2], slab->thickness_nm / 1e3, slab->eta_i,
               a->so.theta_deg);
    } else {
        printf("slab: eta_o %.6g, eta_e %.6g, axis (%.4f, %.4f, %.4f), d %.6g um, eta_i %.4g, theta %.4g deg%s\n",
               slab->eta_o, slab->eta_e, slab->axis[0], slab->axis[1], slab->axis[2], slab->thickness_nm / 1e3,
               slab->eta_i, a->so.theta_deg, res->st.total_reflection ? "  (total reflection inside)" : "");
    }
    if (res->n_samples)
        printf("method %s (%d samples), cmf %s, band %g-%g nm\n\n", biref_method_name(a->method), res->n_samples,
               cmf_name, a->cfg.lambda_min_nm, a->cfg.lambda_max_nm);
    else
        printf("method %s, cmf %s, band %g-%g nm\n\n", biref_method_name(a->method), cmf_name, a->cfg.lambda_min_nm,
               a->cfg.lambda_max_nm);
    printf("Band-normalised XYZ (flat spectrum = 1,1,1), input -> output:\n");
    printf("  %-8s %-30s %-30s\n", "", "transmission X Y Z", "reflection X Y Z");
    const biref_spectrum *spec = &res->spec;
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++) {
            char t[64], r[64];
            snprintf(t, sizeof t, "%.6f %.6f %.6f", spec->T[i][o][0], spec->T[i][o][1], spec->T[i][o][2]);
            snprintf(r, sizeof r, "%.6f %.6f %.6f", spec->R[i][o][0], spec->R[i][o][1], spec->R[i][o][2]);
            printf("  %s -> %s   %-30s %-30s\n", SP[i], SP[o], t, r);
        }
    if (a->general_in)
        printf("\nMixed: polarization %s (Stokes %.4g, %.4g, %.4g, %.4g), analyzer %s\n", pol_name, a->stokes[0],
               a->stokes[1], a->stokes[2], a->stokes[3], an_name);
    else
        printf("\nMixed: polarization %s (s %.4g, p %.4g), analyzer %s\n", pol_name, a->light.w_in[0],
               a->light.w_in[1], an_name);
    const int tty = isatty(STDOUT_FILENO);
    const char *lbl[2] = {"T", "R"};
    const double *xyz[2] = {res->T_xyz, res->R_xyz}, *rgb[2] = {res->T_rgb, res->R_rgb};
    for (int k = 0; k < 2; k++) {
        printf("  %s  XYZ %.6f %.6f %.6f   sRGB %.4f %.4f %.4f", lbl[k], xyz[k][0], xyz[k][1], xyz[k][2], rgb[k][0],
               rgb[k][1], rgb[k][2]);
        if (tty) {
            printf("  ");
            cli_print_swatch(stdout, rgb[k]);
        }
        printf("\n");
    }
    printf("  (sRGB encoded, unclamped%s)\n", tty ? "; swatch clamped to [0,1]" : "");
    return CLI_EXIT_OK;
}

/* --stack: the stack's colours under the same light (cli/spectrum_stack.c). */
static int run_stack(const spectrum_args *a)
{
    spectrum_stack_args sa;
    memset(&sa, 0, sizeof sa);
    sa.file = a->stack_file;
    sa.theta_deg = a->so.theta_deg;
    sa.cfg = a->cfg;
    biref_stack_spectrum_opts_default(&sa.opts);
    sa.opts.method = a->method;
    if (a->samples) sa.opts.samples = (int)a->samples;
    if (a->have_tol) sa.opts.tolerance = a->eopts.tolerance;
    make_light(a, &sa.light);
    memcpy(sa.stokes, a->stokes, sizeof sa.stokes);
    char polbuf[48];
    names(a, polbuf, &sa.pol_name, &sa.an_name);
    sa.json = a->json;
    return spectrum_stack_run(&sa);
}

int cmd_spectrum(int argc, char **argv)
{
    spectrum_args a;
    const int p = parse(argc, argv, &a);
    if (p) return p > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    if (a.stack_file) return run_stack(&a);
    spectrum_result res;
    int rc = compute(&a, &res);
    if (rc == CLI_EXIT_OK) rc = a.json ? print_json(&a, &res) : print_text(&a, &res);
    cli_slab_opts_free(&a.so);
    return rc;
}
