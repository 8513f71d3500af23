/* biref accuracy: the command line of the accuracy study (tools/accuracy/accuracy.h), which
 * compares the spectral integration methods with an alias-free reference (docs/ACCURACY.md). */
#include <errno.h>
#include <math.h>
#include <stddef.h>
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
        char field[64];
        snprintf(field, sizeof field, "%.*s", (int)(end - p), p);
        if (end == p || !cli_number_syntax_ok(field, 0) || errno == ERANGE || !isfinite(v) || (*end != ',' && *end != '\0'))
            return cli_error(CMD, "--sweep-delta-eps: expected comma-separated finite numbers or none, got '%s'",
                             text),
                   -1;
        out[(*n)++] = v;
        if (*end == '\0') return 0;
        p = end + 1;
    }
}

enum {
    OPT_SWEEP = 1,
    OPT_THETA_MAX,
    OPT_THETA_STEP,
    OPT_AZIMUTHS,
    OPT_SAMPLES_REF,
    OPT_SAMPLES_CHECK,
    OPT_CHECK_STEP,
    OPT_COST_ONLY,
    OPT_COST_MIN_TIME,
    OPT_COST_RUNS,
    OPT_COST_ITERS,
    OPT_CMF,
    OPT_RANGE,
    OPT_THICKNESS
};

/* A positive angle or time option; -1 after an error. */
static int positive(const char *opt, const char *arg, double *out)
{
    if (cli_parse_double(CMD, opt, arg, out)) return -1;
    if (*out <= 0.0) return cli_error(CMD, "%s: must be positive, got %g", opt, *out), -1;
    return 0;
}

static int handle_number(acc_options *o, int code, const char *arg)
{
    long v;
    switch (code) {
    case OPT_THICKNESS: return positive("--thickness-um", arg, &o->thickness_um);
    case OPT_THETA_MAX:
        o->theta_max_given = 1;
        if (cli_parse_double(CMD, "--theta-max-deg", arg, &o->theta_max_deg)) return -1;
        if (o->theta_max_deg < 0.0 || o->theta_max_deg >= 90.0)
            return cli_error(CMD, "--theta-max-deg: need 0 <= A < 90, got %g", o->theta_max_deg), -1;
        return 0;
    case OPT_THETA_STEP: o->theta_step_given = 1; return positive("--theta-step-deg", arg, &o->theta_step_deg);
    case OPT_CHECK_STEP: return positive("--check-step-deg", arg, &o->check_step_deg);
    case OPT_AZIMUTHS:
        if (cli_parse_int(CMD, "--azimuths", arg, 1, 3600, &v)) return -1;
        o->nphi = (int)v;
        return 0;
    case OPT_SAMPLES_REF:
        if (cli_parse_int(CMD, "--reference-samples", arg, 1, MAX_SAMPLES, &v)) return -1;
        o->samples_ref = (int)v;
        return 0;
    case OPT_SAMPLES_CHECK:
        if (cli_parse_int(CMD, "--check-samples", arg, 0, MAX_SAMPLES, &v)) return -1;
        o->samples_check = (int)v;
        return 0;
    case OPT_COST_MIN_TIME:
        if (cli_parse_double(CMD, "--cost-min-time", arg, &o->cost_opts.min_time)) return -1;
        if (o->cost_opts.min_time <= 0.0 || o->cost_opts.min_time > 60.0)
            return cli_error(CMD, "--cost-min-time: need 0 < S <= 60, got %g", o->cost_opts.min_time), -1;
        return 0;
    case OPT_COST_RUNS:
        if (cli_parse_int(CMD, "--cost-runs", arg, 1, 64, &v)) return -1;
        o->cost_opts.runs = (int)v;
        return 0;
    default:
        if (cli_parse_int(CMD, "--cost-iterations", arg, 1, 1000000000L, &v)) return -1;
        o->cost_opts.fixed_iters = v;
        return 0;
    }
}

static int handle(void *args, int code, const char *arg)
{
    acc_options *o = args;
    switch (code) {
    case OPT_SWEEP: return parse_sweep(arg, o->sweep, &o->nsweep);
    case OPT_COST_ONLY: o->cost = o->cost_only = 1; return 0;
    case OPT_CMF:
        if (biref_cmf_kind_from_name(arg, &o->scfg.cmf) != BIREF_OK)
            return cli_error(CMD, "--cmf: expected cie1931 or wyman2013, got '%s'", arg), -1;
        return 0;
    case OPT_RANGE: {
        double r2[2];
        if (cli_parse_range_nm(CMD, "--range-nm", arg, r2)) return -1;
        o->scfg.lambda_min_nm = r2[0];
        o->scfg.lambda_max_nm = r2[1];
        return 0;
    }
    default: return handle_number(o, code, arg);
    }
}

#define STR_(x) #x
#define STR(x) STR_(x)
#define F(field) offsetof(acc_options, field)
static const cli_opt OPTS[] = {
    CLI_STRING("materials", 0, "M", F(materials),
               "fig9 (default: the three materials of fig. 9 with their light)\n"
               "or a JSON file: [{\"name\", \"eta_o\", \"eta_e\", \"axis\": [a,b,c],\n"
               "\"thickness_mm\" (or _um, _nm), \"eta_i\", \"polarization\": \"0.75,0.25\",\n"
               "\"analyzer\": \"none\"|\"s\"|\"p\"}, ...]"),
    CLI_STRING("material", 0, "NAME", F(material),
               "instead: the closed-form methods with a dispersive material\n"
               "against the dispersive ground truth (docs/ACCURACY-DISPERSION.md),\n"
               "one plate of a catalogue material (biref material list), two optic\n"
               "axes, 0-85 deg in 2 deg steps unless given, four lights, T and R"),
    CLI_CUSTOM("thickness-um", "T", OPT_THICKNESS,
               "with --material: the plate's thickness (default: the study's plate,\n"
               "calcite 50, quartz 200, rutile 10, linbo3 20, sapphire 1000)"),
    CLI_CUSTOM("sweep-delta-eps", "L", OPT_SWEEP,
               "comma-separated eps_e - eps_o values applied to every material\n"
               "(eta_o kept, eta_e varied), or none (default none)"),
    CLI_CUSTOM("theta-max-deg", "A", OPT_THETA_MAX, "largest angle of incidence, 0 <= A < 90 (default 89)"),
    CLI_CUSTOM("theta-step-deg", "S", OPT_THETA_STEP, "angle step, > 0 (default 1)"),
    CLI_CUSTOM("azimuths", "N", OPT_AZIMUTHS,
               "azimuths of the optic axis per angle, and directions around the\n"
               "axis per ring of the near-axis sets (default 16)"),
    CLI_CUSTOM("reference-samples", "N", OPT_SAMPLES_REF,
               "samples of the reference integration (default " STR(DEFAULT_REFERENCE_SAMPLES) ")"),
    CLI_CUSTOM("check-samples", "N", OPT_SAMPLES_CHECK,
               "denser integration to test the reference, 0 = off (default 4x the\n"
               "reference; base materials, every --check-step-deg of the grid, the\n"
               "largest angle, and every " STR(AXIS_CHECK_STRIDE) "th near-axis sample)"),
    CLI_CUSTOM("check-step-deg", "S", OPT_CHECK_STEP, "angle step of that test (default 5)"),
    CLI_FLAG("cost", 0, F(cost),
             "also measure the cost per shading sample of every method, on one\n"
             "thread, before the sweep, on the grid's states up to 85 deg (adds\n"
             "about a minute); needed for the expansion criteria"),
    CLI_CUSTOM("cost-only", NULL, OPT_COST_ONLY, "only that measurement, no accuracy sweep"),
    CLI_CUSTOM("cost-min-time", "S", OPT_COST_MIN_TIME, "seconds per timed run (default 0.3)"),
    CLI_CUSTOM("cost-runs", "N", OPT_COST_RUNS, "timed runs per method, median reported (default 5)"),
    CLI_CUSTOM("cost-iterations", "N", OPT_COST_ITERS,
               "one run of exactly N samples per method, no calibration: for\n"
               "valgrind --tool=callgrind --toggle-collect=acc_cost_loop\n"
               "--dump-after=acc_cost_loop (one dump per loop, order in --json;\n"
               "scripts/accuracy_callgrind.sh does this)"),
    CLI_STRING("plot-dir", 0, "DIR", F(plot_dir),
               "write DIR/accuracy_vs_theta.png and, with --cost,\n"
               "DIR/accuracy_vs_cost.png"),
    CLI_CUSTOM("cmf", "C", OPT_CMF, "cie1931 (default) or wyman2013"),
    CLI_CUSTOM("range-nm", "MIN,MAX", OPT_RANGE, "integration band (default 380,700)"),
    CLI_INT("threads", "T", F(threads), 1, 1024, "OpenMP threads (default: all cores)"),
    CLI_STRING("csv", 0, "FILE", F(csv_path), "per-angle statistics of every method and material"),
    CLI_STRING("markdown", 0, "FILE", F(md_path), "write the tables to FILE"),
    CLI_FLAG("json", 0, F(json), "machine-readable output on stdout"),
    CLI_OLD("samples-ref", "N", OPT_SAMPLES_REF, "reference-samples", NULL),
    CLI_OLD("samples-check", "N", OPT_SAMPLES_CHECK, "check-samples", NULL),
};
#undef F

const cli_command_spec CLI_ACCURACY = {
    "accuracy",
    "usage: biref accuracy [OPTIONS]\n\n"
    "CIEDE2000 difference between spectral integration methods and a reference, as a function of\n"
    "the angle of incidence, for the paper's fig. 9 materials with their light. Methods: the\n"
    "paper's analytic approximation (eq. 26), analytic-pairs (eq. 26 plus transmission's sibling\n"
    "and entry pairs, beyond the paper), the exact integral of the path-group expansion\n"
    "(default options), numeric integration with 3, 8, 16, 32, 64 and 128 samples, and the\n"
    "paper's ground truth (numeric, 16384 samples). Reference: numeric integration with\n"
    "--reference-samples samples, itself tested against 4x as many on a subset. Each angle is\n"
    "evaluated at several azimuths of the optic axis about the slab normal, as for the pixels of a\n"
    "rendered slab; two more sample sets aim at the directions close to the optic axis, where\n"
    "mm-thick slabs show their colours. Tables on stdout (markdown) unless --json. Method and\n"
    "results: docs/ACCURACY.md.\n\n"
    "Options:\n",
    OPTS,
    CLI_OPTS_COUNT(OPTS),
    NULL,
    25,
    handle,
    1,
    NULL,
};

/* Returns 0 to run the study, 1 after --help, -1 on bad usage (one error line printed). */
static int parse(int argc, char **argv, acc_options *o)
{
    cli_parsed p;
    int r = cli_opts_parse(&CLI_ACCURACY, o, argc, argv, &p);
    if (r) return r;
    if (p.n_args) return cli_error(CMD, "unexpected argument '%s'", argv[p.first_arg]), -1;
    return 0;
}

int cmd_accuracy(int argc, char **argv)
{
    acc_options o;
    acc_options_default(&o);
    const int p = parse(argc, argv, &o);
    if (p) return p > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    if (acc_options_finish(&o)) return CLI_EXIT_USAGE;
    return o.material ? acc_dispersion_study(&o) : acc_study(&o);
}
