/* biref accuracy: the command line of the accuracy study (tools/accuracy/accuracy.h), which
 * compares the spectral integration methods with an alias-free reference (docs/ACCURACY.md). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accuracy.h"
#include "cli_common.h"
#include "cli_light.h"
#include "commands.h"

static const char *const CMD = "accuracy";

/* "v1,v2,..." (1..MAX_SWEEP finite numbers) or "none". */
static int parse_sweep(const char *text, double *out, int *n)
{
    *n = 0;
    if (!strcmp(text, "none")) return 0;
    const char *p = text;
    for (;;) {
        if (*n == MAX_SWEEP) return cli_error(CMD, "--sweep-delta-eps: at most %d values", MAX_SWEEP), -1;
        char *end = NULL;
        errno = 0;
        double v = strtod(p, &end);
        if (end == p || errno == ERANGE || !isfinite(v) || (*end != ',' && *end != '\0'))
            return cli_error(CMD, "--sweep-delta-eps: expected comma-separated finite numbers or none, got '%s'",
                             text),
                   -1;
        out[(*n)++] = v;
        if (*end == '\0') return 0;
        p = end + 1;
    }
}

static void help(void)
{
    printf("usage: biref accuracy [OPTIONS]\n\n"
           "CIEDE2000 difference between spectral integration methods and a reference, as a function of\n"
           "the angle of incidence, for the paper's fig. 9 materials with their light. Methods: the\n"
           "paper's analytic approximation (eq. 26), the exact integral of the path-group expansion\n"
           "(default options), numeric integration with 3, 8, 16, 32, 64 and 128 samples, and the\n"
           "paper's ground truth (numeric, 16384 samples). Reference: numeric integration with\n"
           "--reference-samples samples, itself tested against 4x as many on a subset. Each angle is\n"
           "evaluated at several azimuths of the optic axis about the slab normal, as for the pixels of a\n"
           "rendered slab; two more sample sets aim at the directions close to the optic axis, where\n"
           "mm-thick slabs show their colours. Tables on stdout (markdown) unless --json. Method and\n"
           "results: docs/ACCURACY.md.\n\n"
           "Options:\n"
           "  --materials M          fig9 (default: the three materials of fig. 9 with their light)\n"
           "                         or a JSON file: [{\"name\", \"eta_o\", \"eta_e\", \"axis\": [a,b,c],\n"
           "                         \"thickness_mm\" (or _um, _nm), \"eta_i\", \"polarization\": \"0.75,0.25\",\n"
           "                         \"analyzer\": \"none\"|\"s\"|\"p\"}, ...]\n"
           "  --sweep-delta-eps L    comma-separated eps_e - eps_o values applied to every material\n"
           "                         (eta_o kept, eta_e varied), or none (default none)\n"
           "  --theta-max-deg A      largest angle of incidence, 0 <= A < 90 (default 89)\n"
           "  --theta-step-deg S     angle step, > 0 (default 1)\n"
           "  --azimuths N           azimuths of the optic axis per angle, and directions around the\n"
           "                         axis per ring of the near-axis sets (default 16)\n"
           "  --reference-samples N  samples of the reference integration (default %d)\n"
           "  --samples-ref N        the same (older name)\n"
           "  --check-samples N      denser integration to test the reference, 0 = off (default 4x the\n"
           "                         reference; base materials, every --check-step-deg of the grid, the\n"
           "                         largest angle, and every %dth near-axis sample)\n"
           "  --samples-check N      the same as --check-samples (older name)\n"
           "  --check-step-deg S     angle step of that test (default 5)\n"
           "  --cost                 also measure the cost per shading sample of every method, on one\n"
           "                         thread, before the sweep, on the grid's states up to 85 deg (adds\n"
           "                         about a minute); needed for the expansion criteria\n"
           "  --cost-only            only that measurement, no accuracy sweep\n"
           "  --cost-min-time S      seconds per timed run (default 0.3)\n"
           "  --cost-runs N          timed runs per method, median reported (default 5)\n"
           "  --cost-iterations N    one run of exactly N samples per method, no calibration: for\n"
           "                         valgrind --tool=callgrind --toggle-collect=acc_cost_loop\n"
           "                         --dump-after=acc_cost_loop (one dump per loop, order in --json;\n"
           "                         scripts/accuracy_callgrind.sh does this)\n"
           "  --plot-dir DIR         write DIR/accuracy_vs_theta.png and, with --cost,\n"
           "                         DIR/accuracy_vs_cost.png\n"
           "  --cmf C                cie1931 (default) or wyman2013\n"
           "  --range-nm MIN,MAX     integration band (default 380,700)\n"
           "  --threads T            OpenMP threads (default: all cores)\n"
           "  --progress             progress from the start, also when stderr is not a terminal\n"
           "                         (default: a bar on a terminal, otherwise a line every few seconds\n"
           "                         once the job has run 2 s)\n"
           "  -q, --quiet            no progress on stderr\n"
           "  --csv FILE             per-angle statistics of every method and material\n"
           "  --markdown FILE        write the tables to FILE\n"
           "  --json                 machine-readable output on stdout\n"
           "  -h, --help             this help\n",
           DEFAULT_REFERENCE_SAMPLES, AXIS_CHECK_STRIDE);
}

enum {
    OPT_MATERIALS = 2000,
    OPT_SWEEP,
    OPT_THETA_MAX,
    OPT_THETA_STEP,
    OPT_AZIMUTHS,
    OPT_SAMPLES_REF,
    OPT_SAMPLES_CHECK,
    OPT_CHECK_STEP,
    OPT_COST,
    OPT_COST_ONLY,
    OPT_COST_MIN_TIME,
    OPT_COST_RUNS,
    OPT_COST_ITERS,
    OPT_PLOT_DIR,
    OPT_CMF,
    OPT_RANGE,
    OPT_THREADS,
    OPT_PROGRESS,
    OPT_CSV,
    OPT_MARKDOWN,
    OPT_JSON
};

/* Returns 0 to run the study, 1 after --help, -1 on bad usage (one error line printed). */
static int parse(int argc, char **argv, acc_options *o)
{
    static const struct option longopts[] = {{"materials", required_argument, 0, OPT_MATERIALS},
                                             {"sweep-delta-eps", required_argument, 0, OPT_SWEEP},
                                             {"theta-max-deg", required_argument, 0, OPT_THETA_MAX},
                                             {"theta-step-deg", required_argument, 0, OPT_THETA_STEP},
                                             {"azimuths", required_argument, 0, OPT_AZIMUTHS},
                                             {"reference-samples", required_argument, 0, OPT_SAMPLES_REF},
                                             {"samples-ref", required_argument, 0, OPT_SAMPLES_REF},
                                             {"check-samples", required_argument, 0, OPT_SAMPLES_CHECK},
                                             {"samples-check", required_argument, 0, OPT_SAMPLES_CHECK}, /* old name */
                                             {"check-step-deg", required_argument, 0, OPT_CHECK_STEP},
                                             {"cost", no_argument, 0, OPT_COST},
                                             {"cost-only", no_argument, 0, OPT_COST_ONLY},
                                             {"cost-min-time", required_argument, 0, OPT_COST_MIN_TIME},
                                             {"cost-runs", required_argument, 0, OPT_COST_RUNS},
                                             {"cost-iterations", required_argument, 0, OPT_COST_ITERS},
                                             {"plot-dir", required_argument, 0, OPT_PLOT_DIR},
                                             {"cmf", required_argument, 0, OPT_CMF},
                                             {"range-nm", required_argument, 0, OPT_RANGE},
                                             {"threads", required_argument, 0, OPT_THREADS},
                                             {"progress", no_argument, 0, OPT_PROGRESS},
                                             {"csv", required_argument, 0, OPT_CSV},
                                             {"markdown", required_argument, 0, OPT_MARKDOWN},
                                             {"json", no_argument, 0, OPT_JSON},
                                             {"help", no_argument, 0, 'h'},
                                             {0, 0, 0, 0}};
    opterr = 0;
    optind = 1;
    int c;
    long v;
    while ((c = getopt_long(argc, argv, ":h", longopts, NULL)) != -1) {
        switch (c) {
        case 'h': help(); return 1;
        case OPT_MATERIALS: o->materials = optarg; break;
        case OPT_SWEEP:
            if (parse_sweep(optarg, o->sweep, &o->nsweep)) return -1;
            break;
        case OPT_THETA_MAX:
            if (cli_parse_double(CMD, "--theta-max-deg", optarg, &o->theta_max_deg)) return -1;
            if (o->theta_max_deg < 0.0 || o->theta_max_deg >= 90.0)
                return cli_error(CMD, "--theta-max-deg: need 0 <= A < 90, got %g", o->theta_max_deg), -1;
            break;
        case OPT_THETA_STEP:
            if (cli_parse_double(CMD, "--theta-step-deg", optarg, &o->theta_step_deg)) return -1;
            if (o->theta_step_deg <= 0.0)
                return cli_error(CMD, "--theta-step-deg: must be positive, got %g", o->theta_step_deg), -1;
            break;
        case OPT_CHECK_STEP:
            if (cli_parse_double(CMD, "--check-step-deg", optarg, &o->check_step_deg)) return -1;
            if (o->check_step_deg <= 0.0)
                return cli_error(CMD, "--check-step-deg: must be positive, got %g", o->check_step_deg), -1;
            break;
        case OPT_AZIMUTHS:
            if (cli_parse_int(CMD, "--azimuths", optarg, 1, 3600, &v)) return -1;
            o->nphi = (int)v;
            break;
        case OPT_SAMPLES_REF:
            if (cli_parse_int(CMD, "--reference-samples", optarg, 1, MAX_SAMPLES, &v)) return -1;
            o->samples_ref = (int)v;
            break;
        case OPT_SAMPLES_CHECK:
            if (cli_parse_int(CMD, "--check-samples", optarg, 0, MAX_SAMPLES, &v)) return -1;
            o->samples_check = (int)v;
            break;
        case OPT_COST: o->cost = 1; break;
        case OPT_COST_ONLY: o->cost = o->cost_only = 1; break;
        case OPT_COST_MIN_TIME:
            if (cli_parse_double(CMD, "--cost-min-time", optarg, &o->cost_opts.min_time)) return -1;
            if (o->cost_opts.min_time <= 0.0 || o->cost_opts.min_time > 60.0)
                return cli_error(CMD, "--cost-min-time: need 0 < S <= 60, got %g", o->cost_opts.min_time), -1;
            break;
        case OPT_COST_RUNS:
            if (cli_parse_int(CMD, "--cost-runs", optarg, 1, 64, &v)) return -1;
            o->cost_opts.runs = (int)v;
            break;
        case OPT_COST_ITERS:
            if (cli_parse_int(CMD, "--cost-iterations", optarg, 1, 1000000000L, &v)) return -1;
            o->cost_opts.fixed_iters = v;
            break;
        case OPT_PLOT_DIR: o->plot_dir = optarg; break;
        case OPT_CMF:
            if (biref_cmf_kind_from_name(optarg, &o->scfg.cmf) != BIREF_OK)
                return cli_error(CMD, "--cmf: expected cie1931 or wyman2013, got '%s'", optarg), -1;
            break;
        case OPT_RANGE: {
            double r2[2];
            if (cli_parse_range_nm(CMD, "--range-nm", optarg, r2)) return -1;
            o->scfg.lambda_min_nm = r2[0];
            o->scfg.lambda_max_nm = r2[1];
            break;
        }
        case OPT_THREADS:
            if (cli_parse_int(CMD, "--threads", optarg, 1, 1024, &o->threads)) return -1;
            break;
        case OPT_PROGRESS: o->progress = 1; break;
        case OPT_CSV: o->csv_path = optarg; break;
        case OPT_MARKDOWN: o->md_path = optarg; break;
        case OPT_JSON: o->json = 1; break;
        default: cli_getopt_error(CMD, c, argv); return -1;
        }
    }
    if (optind < argc) return cli_error(CMD, "unexpected argument '%s'", argv[optind]), -1;
    return 0;
}

int cmd_accuracy(int argc, char **argv)
{
    acc_options o;
    acc_options_default(&o);
    const int p = parse(argc, argv, &o);
    if (p) return p > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    if (acc_options_finish(&o)) return CLI_EXIT_USAGE;
    return acc_study(&o);
}
