/* biref spectrum: band-normalised XYZ of one slab at one angle (paper §5), by the analytic
 * approximation (eq. 26), by N-sample numeric integration of eq. 17, by the ground truth, or by
 * the exact integral of the path-group expansion; any incident polarisation and analyzer. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "cli_common.h"
#include "cli_light.h"
#include "cli_polarizer.h"
#include "commands.h"
#include "json_out.h"

static const char *const CMD = "spectrum";
static const char *const SP[2] = {"s", "p"};

enum {
    DEFAULT_NUMERIC_SAMPLES = 64,
    /* The numeric plan allocates two arrays of this many entries; beyond it a run would take
     * minutes per evaluation and say nothing the ground truth does not. */
    MAX_SAMPLES = 1 << 24
};

static void help(void)
{
    printf("usage: biref spectrum [OPTIONS]\n\n"
           "Colour of the light transmitted (T) and reflected (R) by a uniaxial slab at one angle:\n"
           "band-normalised CIE XYZ (a flat spectrum gives 1,1,1; white E) for each input/output\n"
           "polarisation pair, and the mixed colour for a given incident light and analyzer.\n\n"
           "Options:\n" CLI_SLAB_HELP
           "  --method M           analytic (default; paper eq. 26), numeric (N samples of eq. 17),\n"
           "                       ground-truth (numeric, 16384 samples) or expansion (exact integral\n"
           "                       of the path-group expansion, docs/PHYSICS.md §5)\n"
           "  --samples N          samples of the numeric method, N >= 1 (default 64; numeric only)\n"
           "  --order N            expansion: every pair of path groups up to order N interferes,\n"
           "                       the rest adds incoherently, 0-8 (default adaptive)\n"
           "  --tolerance E        expansion: adaptive orders' target relative error (default 1e-3;\n"
           "                       docs/PHYSICS.md section 5)\n"
           "  --cmf C              cie1931 (default, tabulated) or wyman2013 (analytic fit)\n"
           "  --range-nm MIN,MAX   integration band in nm (default 380,700)\n"
           "  --polarization P     incident light: s, p, unpolarized (default) or S,P weights\n"
           "                       (normalised to sum 1, e.g. 0.75,0.25)\n"
           "  --polarizer P        fully polarised input: linear:DEG (from s towards p) or\n"
           "                       circular:+1|-1 (sign of S3); replaces --polarization\n"
           "  --stokes S0,S1,S2,S3 any (partially) polarised input in the s/p basis\n"
           "  --analyzer A         none (default), s, p, linear:DEG or circular:+1|-1\n"
           "                       (linear/circular/--polarizer/--stokes need numeric, ground-truth\n"
           "                       or expansion: the paper's method handles s/p only)\n"
           "  --json               machine-readable output\n"
           "  -h, --help           this help\n\n"
           "sRGB values are encoded (non-linear) and not clamped: out-of-gamut colours fall outside\n"
           "[0, 1]. Only the terminal swatch is clamped.\n\n"
           "Example:\n  biref spectrum --eta-o 1.775 --eta-e 1.231 --axis 0.084,0.979,-0.187 \\\n"
           "                --thickness-um 20 --theta-deg 30 --polarization 0.02,0.98 --analyzer s\n");
}

enum {
    OPT_METHOD = OPT_SLAB_LAST + 1,
    OPT_SAMPLES,
    OPT_CMF,
    OPT_RANGE,
    OPT_POL,
    OPT_ANALYZER,
    OPT_JSON,
    OPT_ORDER,
    OPT_TOLERANCE,
    OPT_POLARIZER,
    OPT_STOKES
};

static cJSON *xyz_pairs_json(const double X[2][2][3])
{
    cJSON *o = cJSON_CreateObject();
    for (int i = 0; i < 2; i++) {
        cJSON *row = cJSON_AddObjectToObject(o, SP[i]);
        for (int j = 0; j < 2; j++) cJSON_AddItemToObject(row, SP[j], json_vec3(X[i][j]));
    }
    return o;
}

static int all_finite(const biref_spectrum *s)
{
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++)
            for (int j = 0; j < 3; j++)
                if (!isfinite(s->T[i][o][j]) || !isfinite(s->R[i][o][j])) return 0;
    return 1;
}

int cmd_spectrum(int argc, char **argv)
{
    cli_slab_opts so;
    cli_slab_opts_init(&so);
    biref_spectral_config cfg;
    biref_spectral_config_default(&cfg);
    biref_method method = BIREF_METHOD_ANALYTIC;
    long samples = 0; /* 0: not given */
    cli_light light;
    cli_light_default(&light);
    int json = 0;
    biref_expansion_opts eopts;
    biref_expansion_opts_default(&eopts);
    int have_order = 0, have_tol = 0;
    /* General polarisation: Stokes input and/or an analyzer projector (NULL-able). */
    int general_in = 0, general_an = 0;
    double stokes[4] = {1, 0, 0, 0};
    double complex P_an[2][2];
    char pol_text[64] = "", an_text[64] = "";
    static const struct option longopts[] = {CLI_SLAB_LONG_OPTIONS,
                                             {"order", required_argument, 0, OPT_ORDER},
                                             {"tolerance", required_argument, 0, OPT_TOLERANCE},
                                             {"polarizer", required_argument, 0, OPT_POLARIZER},
                                             {"stokes", required_argument, 0, OPT_STOKES},
                                             {"method", required_argument, 0, OPT_METHOD},
                                             {"samples", required_argument, 0, OPT_SAMPLES},
                                             {"cmf", required_argument, 0, OPT_CMF},
                                             {"range-nm", required_argument, 0, OPT_RANGE},
                                             {"polarization", required_argument, 0, OPT_POL},
                                             {"analyzer", required_argument, 0, OPT_ANALYZER},
                                             {"json", no_argument, 0, OPT_JSON},
                                             {"help", no_argument, 0, 'h'},
                                             {0, 0, 0, 0}};
    opterr = 0;
    optind = 1;
    int c;
    while ((c = getopt_long(argc, argv, ":h", longopts, NULL)) != -1) {
        int r = cli_slab_opts_handle(CMD, &so, c, optarg);
        if (r < 0) return CLI_EXIT_USAGE;
        if (r > 0) continue;
        switch (c) {
        case 'h': help(); return CLI_EXIT_OK;
        case OPT_METHOD:
            if (biref_method_from_name(optarg, &method) != BIREF_OK)
                return cli_error(CMD, "--method: expected analytic, numeric, ground-truth or expansion, got '%s'",
                                 optarg),
                       CLI_EXIT_USAGE;
            break;
        case OPT_SAMPLES:
            if (cli_parse_int(CMD, "--samples", optarg, 1, MAX_SAMPLES, &samples)) return CLI_EXIT_USAGE;
            break;
        case OPT_CMF:
            if (biref_cmf_kind_from_name(optarg, &cfg.cmf) != BIREF_OK)
                return cli_error(CMD, "--cmf: expected cie1931 or wyman2013, got '%s'", optarg), CLI_EXIT_USAGE;
            break;
        case OPT_RANGE: {
            double r2[2];
            if (cli_parse_range_nm(CMD, "--range-nm", optarg, r2)) return CLI_EXIT_USAGE;
            cfg.lambda_min_nm = r2[0];
            cfg.lambda_max_nm = r2[1];
            break;
        }
        case OPT_POL:
            if (cli_parse_polarization(CMD, "--polarization", optarg, light.w_in)) return CLI_EXIT_USAGE;
            break;
        case OPT_ANALYZER: {
            int g = cli_parse_general_analyzer(CMD, "--analyzer", optarg, P_an);
            if (g < 0) return CLI_EXIT_USAGE;
            if (g > 0) {
                general_an = 1;
                snprintf(an_text, sizeof an_text, "%s", optarg);
            } else if (cli_parse_analyzer(CMD, "--analyzer", optarg, light.mask)) {
                return CLI_EXIT_USAGE;
            }
            break;
        }
        case OPT_POLARIZER:
            if (cli_parse_polarizer_state(CMD, "--polarizer", optarg, stokes)) return CLI_EXIT_USAGE;
            general_in = 1;
            snprintf(pol_text, sizeof pol_text, "%s", optarg);
            break;
        case OPT_STOKES:
            if (cli_parse_stokes(CMD, "--stokes", optarg, stokes)) return CLI_EXIT_USAGE;
            general_in = 1;
            snprintf(pol_text, sizeof pol_text, "stokes:%s", optarg);
            break;
        case OPT_ORDER:
            if (cli_parse_expansion_order(CMD, optarg, &eopts)) return CLI_EXIT_USAGE;
            have_order = 1;
            break;
        case OPT_TOLERANCE:
            if (cli_parse_expansion_tolerance(CMD, optarg, &eopts)) return CLI_EXIT_USAGE;
            have_tol = 1;
            break;
        case OPT_JSON: json = 1; break;
        default: cli_getopt_error(CMD, c, argv); return CLI_EXIT_USAGE;
        }
    }
    if (optind < argc) return cli_error(CMD, "unexpected argument '%s'", argv[optind]), CLI_EXIT_USAGE;
    /* --samples with another method would be silently ignored; refuse it so a typo in --method
     * cannot masquerade as a numeric run. */
    if (samples && method != BIREF_METHOD_NUMERIC)
        return cli_error(CMD, "--samples: only valid with --method numeric (method is %s)", biref_method_name(method)),
               CLI_EXIT_USAGE;
    if ((have_order || have_tol) && method != BIREF_METHOD_EXPANSION)
        return cli_error(CMD, "%s: only valid with --method expansion", have_order ? "--order" : "--tolerance"),
               CLI_EXIT_USAGE;
    if (have_order && have_tol) return cli_error(CMD, "--order and --tolerance exclude each other"), CLI_EXIT_USAGE;
    const int general = general_in || general_an;
    if (general && method == BIREF_METHOD_ANALYTIC)
        return cli_error(CMD, "%s needs --method numeric, ground-truth or expansion (the paper's method handles s/p only)",
                         general_in ? "--polarizer/--stokes" : "--analyzer linear/circular"),
               CLI_EXIT_USAGE;
    if (!general_in) {
        /* The s/p fractions as a (diagonal) Stokes vector, for the general path. */
        stokes[0] = 1.0;
        stokes[1] = light.w_in[0] - light.w_in[1];
    }
    if (!general_an) {
        memset(P_an, 0, sizeof P_an);
        P_an[0][0] = light.mask[0];
        P_an[1][1] = light.mask[1];
    }
    if (cli_slab_opts_finish(CMD, &so)) return CLI_EXIT_USAGE;
    int n_samples = method == BIREF_METHOD_NUMERIC ? (samples ? (int)samples : DEFAULT_NUMERIC_SAMPLES)
                    : method == BIREF_METHOD_GROUND_TRUTH ? BIREF_GROUND_TRUTH_SAMPLES : 0;

    const double theta = so.theta_deg * M_PI / 180.0;
    biref_slab_state st;
    biref_status s = biref_slab_prepare(&so.slab, theta, &st);
    if (s != BIREF_OK) return cli_error(CMD, "%s", biref_status_string(s)), CLI_EXIT_FAIL;

    biref_spectral *sp = NULL;
    s = biref_spectral_create(&cfg, &sp);
    /* The range passed its own checks, so INVALID here means the CMFs vanish on the band. */
    if (s == BIREF_ERR_INVALID)
        return cli_error(CMD, "--range-nm: the colour-matching functions are zero on %g-%g nm", cfg.lambda_min_nm,
                         cfg.lambda_max_nm),
               CLI_EXIT_USAGE;
    if (s != BIREF_OK) return cli_error(CMD, "spectral context: %s", biref_status_string(s)), CLI_EXIT_FAIL;

    biref_spectrum spec;
    double T_xyz[3], R_xyz[3], T_rgb[3], R_rgb[3];
    double complex C_in[2][2];
    biref_stokes_to_coherency(stokes, C_in); /* validated when parsed */
    int order_used[2] = {-1, -1};
    if (n_samples) {
        biref_numeric_plan *plan = NULL;
        s = biref_numeric_plan_create(sp, n_samples, &plan);
        if (s != BIREF_OK) {
            biref_spectral_destroy(sp);
            return cli_error(CMD, "numeric plan: %s", biref_status_string(s)), CLI_EXIT_FAIL;
        }
        biref_spectrum_numeric(plan, &st, &spec);
        if (general) {
            biref_spectrum_numeric_polarized(plan, &st, BIREF_TRANSMISSION, (const double complex(*)[2])C_in,
                                             (const double complex(*)[2])P_an, T_xyz);
            biref_spectrum_numeric_polarized(plan, &st, BIREF_REFLECTION, (const double complex(*)[2])C_in,
                                             (const double complex(*)[2])P_an, R_xyz);
        }
        biref_numeric_plan_destroy(plan);
    } else if (method == BIREF_METHOD_EXPANSION) {
        s = biref_spectrum_expansion(sp, &st, &eopts, &spec);
        for (int w = 0; w < 2 && s == BIREF_OK; w++)
            s = biref_spectrum_expansion_polarized(sp, &st, w, (const double complex(*)[2])C_in,
                                                   (const double complex(*)[2])P_an, &eopts, w ? R_xyz : T_xyz,
                                                   &order_used[w]);
        if (s != BIREF_OK) {
            biref_spectral_destroy(sp);
            return cli_error(CMD, "expansion: %s", biref_status_string(s)), CLI_EXIT_FAIL;
        }
    } else {
        biref_spectrum_analytic(sp, &st, &spec);
    }
    biref_spectral_destroy(sp);
    if (!all_finite(&spec)) return cli_error(CMD, "numerical failure (non-finite result)"), CLI_EXIT_FAIL;

    if (!general && method != BIREF_METHOD_EXPANSION) {
        biref_spectrum_mix(spec.T, light.w_in, light.mask, T_xyz);
        biref_spectrum_mix(spec.R, light.w_in, light.mask, R_xyz);
    }
    biref_xyz_to_srgb(T_xyz, T_rgb);
    biref_xyz_to_srgb(R_xyz, R_rgb);
    char polbuf[48];
    const char *pol_name = general_in ? pol_text : cli_polarization_name(light.w_in, polbuf, sizeof polbuf);
    const char *an_name = general_an ? an_text : cli_analyzer_name(light.mask);
    const char *cmf_name = biref_cmf_kind_name(cfg.cmf);

    if (json) {
        cJSON *root = cJSON_CreateObject();
        cJSON_AddStringToObject(root, "method", biref_method_name(method));
        if (n_samples)
            cJSON_AddNumberToObject(root, "samples", n_samples);
        else
            cJSON_AddNullToObject(root, "samples");
        cJSON_AddStringToObject(root, "cmf", cmf_name);
        double range[2] = {cfg.lambda_min_nm, cfg.lambda_max_nm};
        cJSON_AddItemToObject(root, "range_nm", cJSON_CreateDoubleArray(range, 2));
        cJSON *in = cJSON_AddObjectToObject(root, "input");
        cJSON_AddNumberToObject(in, "eta_o", so.slab.eta_o);
        cJSON_AddNumberToObject(in, "eta_e", so.slab.eta_e);
        cJSON_AddItemToObject(in, "axis", json_vec3(so.slab.axis));
        cJSON_AddNumberToObject(in, "thickness_nm", so.slab.thickness_nm);
        cJSON_AddNumberToObject(in, "theta_deg", so.theta_deg);
        cJSON_AddNumberToObject(in, "eta_i", so.slab.eta_i);
        cJSON_AddBoolToObject(root, "total_reflection", st.total_reflection);
        cJSON_AddItemToObject(root, "T", xyz_pairs_json(spec.T));
        cJSON_AddItemToObject(root, "R", xyz_pairs_json(spec.R));
        cJSON *mx = cJSON_AddObjectToObject(root, "mixed");
        cJSON *pol = cJSON_AddObjectToObject(mx, "polarization");
        if (!general_in) {
            cJSON_AddNumberToObject(pol, "s", light.w_in[0]);
            cJSON_AddNumberToObject(pol, "p", light.w_in[1]);
        } else {
            cJSON_AddStringToObject(pol, "state", pol_text);
        }
        cJSON_AddItemToObject(pol, "stokes", cJSON_CreateDoubleArray(stokes, 4));
        if (method == BIREF_METHOD_EXPANSION) {
            cJSON *ord = cJSON_AddObjectToObject(root, "expansion_order");
            cJSON_AddNumberToObject(ord, "T", order_used[0]);
            cJSON_AddNumberToObject(ord, "R", order_used[1]);
        }
        cJSON_AddStringToObject(mx, "analyzer", an_name);
        cJSON_AddItemToObject(mx, "T_xyz", json_vec3(T_xyz));
        cJSON_AddItemToObject(mx, "R_xyz", json_vec3(R_xyz));
        cJSON_AddItemToObject(mx, "T_srgb", json_vec3(T_rgb));
        cJSON_AddItemToObject(mx, "R_srgb", json_vec3(R_rgb));
        cJSON_AddStringToObject(mx, "srgb_note", "encoded sRGB (IEC 61966-2-1), white E -> (1,1,1), not clamped");
        return json_print_and_free(root) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
    }

    printf("slab: eta_o %.6g, eta_e %.6g, axis (%.4f, %.4f, %.4f), d %.6g um, eta_i %.4g, theta %.4g deg%s\n",
           so.slab.eta_o, so.slab.eta_e, so.slab.axis[0], so.slab.axis[1], so.slab.axis[2],
           so.slab.thickness_nm / 1e3, so.slab.eta_i, so.theta_deg,
           st.total_reflection ? "  (total reflection inside)" : "");
    if (n_samples)
        printf("method %s (%d samples), cmf %s, band %g-%g nm\n\n", biref_method_name(method), n_samples, cmf_name,
               cfg.lambda_min_nm, cfg.lambda_max_nm);
    else
        printf("method %s, cmf %s, band %g-%g nm\n\n", biref_method_name(method), cmf_name, cfg.lambda_min_nm,
               cfg.lambda_max_nm);
    printf("Band-normalised XYZ (flat spectrum = 1,1,1), input -> output:\n");
    printf("  %-8s %-30s %-30s\n", "", "transmission X Y Z", "reflection X Y Z");
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++) {
            char t[64], r[64];
            snprintf(t, sizeof t, "%.6f %.6f %.6f", spec.T[i][o][0], spec.T[i][o][1], spec.T[i][o][2]);
            snprintf(r, sizeof r, "%.6f %.6f %.6f", spec.R[i][o][0], spec.R[i][o][1], spec.R[i][o][2]);
            printf("  %s -> %s   %-30s %-30s\n", SP[i], SP[o], t, r);
        }
    if (general_in)
        printf("\nMixed: polarization %s (Stokes %.4g, %.4g, %.4g, %.4g), analyzer %s\n", pol_name, stokes[0],
               stokes[1], stokes[2], stokes[3], an_name);
    else
        printf("\nMixed: polarization %s (s %.4g, p %.4g), analyzer %s\n", pol_name, light.w_in[0], light.w_in[1],
               an_name);
    const int tty = isatty(STDOUT_FILENO);
    const char *lbl[2] = {"T", "R"};
    const double *xyz[2] = {T_xyz, R_xyz}, *rgb[2] = {T_rgb, R_rgb};
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
