/* biref spectrum: band-normalised XYZ of one slab at one angle (paper §5), by the analytic
 * approximation (eq. 26), by N-sample numeric integration of eq. 17, or by the ground truth. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "cli_common.h"
#include "cli_light.h"
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
           "  --method M           analytic (default; paper eq. 26), numeric (N samples of eq. 17)\n"
           "                       or ground-truth (numeric, 16384 samples)\n"
           "  --samples N          samples of the numeric method, N >= 1 (default 64; numeric only)\n"
           "  --cmf C              cie1931 (default, tabulated) or wyman2013 (analytic fit)\n"
           "  --range-nm MIN,MAX   integration band in nm (default 380,700)\n"
           "  --polarization P     incident light: s, p, unpolarized (default) or S,P weights\n"
           "                       (normalised to sum 1, e.g. 0.75,0.25)\n"
           "  --analyzer A         none (default), s or p: polarisation passed to the detector\n"
           "  --json               machine-readable output\n"
           "  -h, --help           this help\n\n"
           "sRGB values are encoded (non-linear) and not clamped: out-of-gamut colours fall outside\n"
           "[0, 1]. Only the terminal swatch is clamped.\n\n"
           "Example:\n  biref spectrum --eta-o 1.775 --eta-e 1.231 --axis 0.084,0.979,-0.187 \\\n"
           "                --thickness-um 20 --theta-deg 30 --polarization 0.02,0.98 --analyzer s\n");
}

enum { OPT_METHOD = OPT_SLAB_LAST + 1, OPT_SAMPLES, OPT_CMF, OPT_RANGE, OPT_POL, OPT_ANALYZER, OPT_JSON };

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
    static const struct option longopts[] = {CLI_SLAB_LONG_OPTIONS,
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
                return cli_error(CMD, "--method: expected analytic, numeric or ground-truth, got '%s'", optarg),
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
        case OPT_ANALYZER:
            if (cli_parse_analyzer(CMD, "--analyzer", optarg, light.mask)) return CLI_EXIT_USAGE;
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
    if (n_samples) {
        biref_numeric_plan *plan = NULL;
        s = biref_numeric_plan_create(sp, n_samples, &plan);
        if (s != BIREF_OK) {
            biref_spectral_destroy(sp);
            return cli_error(CMD, "numeric plan: %s", biref_status_string(s)), CLI_EXIT_FAIL;
        }
        biref_spectrum_numeric(plan, &st, &spec);
        biref_numeric_plan_destroy(plan);
    } else {
        biref_spectrum_analytic(sp, &st, &spec);
    }
    biref_spectral_destroy(sp);
    if (!all_finite(&spec)) return cli_error(CMD, "numerical failure (non-finite result)"), CLI_EXIT_FAIL;

    double T_xyz[3], R_xyz[3], T_rgb[3], R_rgb[3];
    biref_spectrum_mix(spec.T, light.w_in, light.mask, T_xyz);
    biref_spectrum_mix(spec.R, light.w_in, light.mask, R_xyz);
    biref_xyz_to_srgb(T_xyz, T_rgb);
    biref_xyz_to_srgb(R_xyz, R_rgb);
    char polbuf[48];
    const char *pol_name = cli_polarization_name(light.w_in, polbuf, sizeof polbuf);
    const char *an_name = cli_analyzer_name(light.mask);
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
        cJSON_AddNumberToObject(pol, "s", light.w_in[0]);
        cJSON_AddNumberToObject(pol, "p", light.w_in[1]);
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
