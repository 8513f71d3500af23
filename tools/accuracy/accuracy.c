/* The accuracy study from options to reports: materials, integration plans, the cost measurement,
 * the sweep, then the outputs. */
#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli_common.h"
#include "cli_mpi.h"
#include "cli_files.h"
#include "outfile.h"
#include "json_out.h"
#include "study.h"

void acc_options_default(acc_options *o)
{
    memset(o, 0, sizeof *o);
    o->materials = "fig9";
    o->theta_max_deg = 89.0;
    o->theta_step_deg = 1.0;
    o->check_step_deg = 5.0;
    o->nphi = 16;
    o->samples_ref = DEFAULT_REFERENCE_SAMPLES;
    o->samples_check = -1; /* 4x the reference unless given */
    o->cost_opts = (acc_cost_opts){0.3, 5, 0, NULL};
    biref_spectral_config_default(&o->scfg);
}

/* --material: the options of the other study are refused, the grid defaults to 0-85° in 2° steps. */
static int finish_dispersion(acc_options *o)
{
    acc_options d;
    acc_options_default(&d);
    if (strcmp(o->materials, "fig9") || o->nsweep || o->cost || o->nphi != d.nphi || o->samples_ref != d.samples_ref ||
        o->samples_check != d.samples_check || o->plot_dir || o->check_step_deg != d.check_step_deg)
        return cli_error(ACC_CMD, "--material: takes only --thickness-um, --theta-max-deg, --theta-step-deg, --cmf, "
                                  "--range-nm, --threads, --csv, --markdown and --json"),
               -1;
    if (!(o->thickness_um > 0.0) && !(acc_dispersion_default_thickness_um(o->material) > 0.0))
        return cli_error(ACC_CMD, "--material %s: needs --thickness-um (the study has no plate of it)", o->material), -1;
    if (!o->theta_max_given) o->theta_max_deg = 85.0;
    if (!o->theta_step_given) o->theta_step_deg = 2.0;
    return 0;
}

int acc_options_finish(acc_options *o)
{
    if (!o->material && o->thickness_um > 0.0) return cli_error(ACC_CMD, "--thickness-um: needs --material"), -1;
    if (o->material && finish_dispersion(o)) return -1;
    if (o->cost_only && (o->csv_path || o->plot_dir))
        return cli_error(ACC_CMD, "--cost-only: no accuracy sweep, so no --csv or --plot-dir"), -1;
    if ((o->cost_opts.fixed_iters > 0) && !o->cost)
        return cli_error(ACC_CMD, "--cost-iterations: needs --cost or --cost-only"), -1;
    if ((o->cost || o->cost_only) && cli_mpi_active())
        return cli_error(ACC_CMD, "--cost and --cost-only time one process: run them without mpirun -n N"), -1;
    /* In an MPI job rank 0 alone writes, on its own file system. */
    const int root = cli_mpi_rank() == 0;
    if (o->plot_dir && root) {
        struct stat sb;
        if (stat(o->plot_dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
            return cli_error(ACC_CMD, "--plot-dir: '%s' is not a directory", o->plot_dir), -1;
    }
    cli_files files; /* every report against the materials file and each other */
    cli_files_init(&files);
    if (strcmp(o->materials, "fig9")) cli_files_read(&files, "--materials", o->materials);
    cli_files_write(&files, "--csv", "csv", o->csv_path);
    cli_files_write(&files, "--markdown", "md", o->md_path);
    if (o->plot_dir) cli_files_write_in_dir(&files, "--plot-dir", "png", o->plot_dir, "accuracy_vs_theta.png");
    if (o->plot_dir && o->cost) cli_files_write_in_dir(&files, "--plot-dir", "png", o->plot_dir, "accuracy_vs_cost.png");
    const int rc = root ? cli_files_check(ACC_CMD, &files) : 0;
    cli_files_free(&files);
    if (rc) return -1;
    /* The check defaults to 4x the reference: a midpoint rule that has converged changes by far
     * less than the error it had when the samples are quadrupled. */
    if (o->samples_check < 0) o->samples_check = o->samples_ref <= MAX_SAMPLES / 4 ? 4 * o->samples_ref : 0;
    /* Counts are computed in double and range-checked before they become integers: a step of
     * 1e-300 makes a ratio far beyond any int. */
    const double ntheta = floor(o->theta_max_deg / o->theta_step_deg + 1e-9) + 1;
    if (!(ntheta <= 100000))
        return cli_error(ACC_CMD, "--theta-step-deg: %g gives more than 100000 angles", o->theta_step_deg), -1;
    o->ntheta = (int)ntheta;
    /* A check step beyond the grid checks the first angle alone. */
    o->kcheck = (int)lround(fmin(o->check_step_deg / o->theta_step_deg, ntheta));
    if (o->kcheck < 1) o->kcheck = 1;
    return 0;
}

/* Reports go through io/outfile.h: they appear complete at the end of a successful run or not at
 * all, so a usage error or an interrupt leaves an existing report as it was. */
static biref_outfile *open_out(const char *opt, const char *path)
{
    char msg[600];
    biref_outfile *o = biref_outfile_open(path, msg, sizeof msg);
    if (!o) cli_error(ACC_CMD, "%s: %s", opt, msg);
    return o;
}

static int close_out(const char *opt, biref_outfile *o)
{
    char msg[600];
    if (biref_outfile_close(o, 1, msg, sizeof msg) != BIREF_OK) return cli_error(ACC_CMD, "%s: %s", opt, msg), -1;
    return 0;
}

/* Materials: the bases, then one variant per (base, Δε). Returns a CLI exit code. */
static int make_materials(acc_run *run, const acc_options *o)
{
    acc_material base[MAX_BASE];
    if (!strcmp(o->materials, "fig9"))
        run->nbase = acc_builtin_fig9(base);
    else if (acc_load_materials(o->materials, base, MAX_BASE, &run->nbase))
        return CLI_EXIT_USAGE;
    run->nmat = run->nbase * (1 + o->nsweep);
    run->mat = calloc((size_t)run->nmat, sizeof *run->mat);
    run->res = calloc((size_t)run->nmat, sizeof *run->res);
    if (!run->mat || !run->res) return cli_error(ACC_CMD, "out of memory"), CLI_EXIT_FAIL;
    for (int i = 0; i < run->nbase; i++) {
        run->mat[i] = base[i];
        biref_axis_normalize(base[i].slab.axis, run->mat[i].slab.axis);
        run->mat[i].delta_eps = base[i].slab.eta_e * base[i].slab.eta_e - base[i].slab.eta_o * base[i].slab.eta_o;
    }
    for (int i = 0; i < run->nbase; i++)
        for (int k = 0; k < o->nsweep; k++) {
            acc_material *m = &run->mat[run->nbase + i * o->nsweep + k];
            *m = run->mat[i];
            m->base = i;
            m->delta_eps = o->sweep[k];
            double e2 = m->slab.eta_o * m->slab.eta_o + o->sweep[k];
            if (!(e2 > 0.0))
                return cli_error(ACC_CMD, "--sweep-delta-eps: %g makes eps_e <= 0 for material %s", o->sweep[k],
                                 m->name),
                       CLI_EXIT_USAGE;
            m->slab.eta_e = sqrt(e2);
            snprintf(m->name, sizeof m->name, "%.40s:de%+.3g", base[i].name, o->sweep[k]);
        }
    return CLI_EXIT_OK;
}

enum { NINTEGRATORS = NCMP + 2 }; /* the compared methods, the reference, the check */

/* The spectral context and an integrator per method. Returns a CLI exit code. */
static int make_plans(const acc_run *run, const acc_options *o, biref_spectral **sp,
                      biref_integrator *its[NINTEGRATORS], acc_plans *pl)
{
    char why[BIREF_MSG_SIZE];
    biref_status s = biref_spectral_create(&run->scfg, sp, why, sizeof why);
    if (s == BIREF_ERR_INVALID) return cli_error(ACC_CMD, "--range-nm: %s", why), CLI_EXIT_USAGE;
    if (s != BIREF_OK) return cli_error(ACC_CMD, "spectral context: %s", why), CLI_EXIT_FAIL;
    biref_integrator_options io[NINTEGRATORS];
    for (int k = 0; k < NINTEGRATORS; k++) {
        biref_integrator_options_default(&io[k]);
        io[k].method = BIREF_METHOD_NUMERIC;
        io[k].samples = 0; /* none */
    }
    io[M_ANALYTIC].method = BIREF_METHOD_ANALYTIC;
    io[M_PAIRS].method = BIREF_METHOD_ANALYTIC_PAIRS;
    io[M_EXPANSION].method = BIREF_METHOD_EXPANSION;
    for (int k = 0; k < NNUM; k++) io[M_N3 + k].samples = ACC_NUMERIC_N[k];
    io[M_GT].method = BIREF_METHOD_GROUND_TRUTH;
    io[NCMP].samples = o->cost_only ? 0 : run->samples_ref;
    io[NCMP + 1].samples = o->cost_only ? 0 : run->samples_check;
    for (int k = 0; k < NINTEGRATORS; k++) {
        if (io[k].method == BIREF_METHOD_NUMERIC && io[k].samples <= 0) continue;
        s = biref_integrator_create(*sp, &io[k], &its[k], why, sizeof why);
        if (s != BIREF_OK) return cli_error(ACC_CMD, "%s integrator: %s", biref_method_name(io[k].method), why), CLI_EXIT_FAIL;
    }
    memset(pl, 0, sizeof *pl);
    pl->sp = *sp;
    for (int k = 0; k < NCMP; k++) pl->method[k] = its[k];
    pl->ref = its[NCMP];
    pl->check = its[NCMP + 1];
    return CLI_EXIT_OK;
}

/* The cost measurement, then the sweep over every material. Returns 0 or -1. */
static int compute(acc_run *run, const acc_options *o, const acc_plans *pl)
{
    biref_progress_bar bar;
    biref_progress_bar_init(&bar, stderr, 1, "accuracy");
    run->cost_opts.progress = &bar;
    /* Cost first: on one thread, before any OpenMP team exists whose idle workers could spin on the
     * other core while it is timed. */
    if (o->cost && acc_measure_cost(run, pl)) return -1;

    if (o->threads > 0) omp_set_num_threads((int)o->threads);
    run->threads = omp_get_max_threads();
    acc_progress pg = {&bar, 0, (long)run->nmat * ((long)run->ntheta + AXIS_SETS * AXIS_NPSI) * run->nphi};
    const double t0 = omp_get_wtime();
    if (!o->cost_only) {
        for (int i = 0; i < run->nmat; i++) {
            char note[80];
            snprintf(note, sizeof note, "material %s", run->mat[i].name);
            biref_progress_bar_note(&bar, note);
            if (acc_run_material(run, pl, i, &pg)) {
                biref_progress_bar_finish(&bar);
                return -1;
            }
        }
        run->sweep_done = 1;
        biref_progress_bar_update(&bar, 1, 1);
    }
    run->total_s = omp_get_wtime() - t0 + run->cost_s;
    biref_progress_bar_finish(&bar);
    return 0;
}

/* The figures, the CSV, the Markdown file and stdout; closes (and clears) the open files. */
static int write_outputs(const acc_run *run, const acc_options *o, biref_outfile **csv, biref_outfile **md)
{
    if (o->plot_dir && acc_write_plots(run, o->plot_dir)) return -1;
    if (*csv) {
        acc_write_csv(biref_outfile_stream(*csv), run);
        int e = close_out("--csv", *csv);
        *csv = NULL;
        if (e) return -1;
    }
    if (*md) {
        fprintf(biref_outfile_stream(*md), "## biref accuracy\n\n");
        acc_write_markdown(biref_outfile_stream(*md), run);
        int e = close_out("--markdown", *md);
        *md = NULL;
        if (e) return -1;
    }
    if (o->json) {
        cJSON *root = acc_build_json(run);
        if (!root) return cli_error(ACC_CMD, "out of memory"), -1;
        if (json_print_and_free(root)) return -1;
    } else {
        acc_write_markdown(stdout, run);
    }
    return 0;
}

int acc_study(const acc_options *o)
{
    acc_run run;
    memset(&run, 0, sizeof run);
    run.theta_max_deg = o->theta_max_deg;
    run.theta_step_deg = o->theta_step_deg;
    run.check_step_deg = o->check_step_deg;
    run.ntheta = o->ntheta;
    run.kcheck = o->kcheck;
    run.nphi = o->nphi;
    run.samples_ref = o->samples_ref;
    run.samples_check = o->samples_check;
    run.scfg = o->scfg;
    run.materials_arg = o->materials;
    run.cost_opts = o->cost_opts;

    biref_spectral *sp = NULL;
    biref_integrator *its[NINTEGRATORS] = {0};
    biref_outfile *csv = NULL, *md = NULL;
    acc_plans pl;
    int rc = make_materials(&run, o);
    if (rc != CLI_EXIT_OK) goto done;
    rc = CLI_EXIT_USAGE;
    /* Open the outputs first: a bad path should fail now, not after minutes of computation. */
    const int root = cli_mpi_rank() == 0; /* alone, or rank 0 of an MPI job: the one that writes */
    if (root && o->csv_path && !(csv = open_out("--csv", o->csv_path))) goto done;
    if (root && o->md_path && !(md = open_out("--markdown", o->md_path))) goto done;
    rc = make_plans(&run, o, &sp, its, &pl);
    if (rc != CLI_EXIT_OK) goto done;
    /* In an MPI job: every process is ready, or all stop with the first failure's line. */
    if ((rc = cli_mpi_agree(CLI_EXIT_OK))) goto done;
    rc = CLI_EXIT_FAIL;
    if (compute(&run, o, &pl) || (root && write_outputs(&run, o, &csv, &md))) goto done;
    rc = CLI_EXIT_OK;

done:
    if (csv) biref_outfile_close(csv, 0, NULL, 0);
    if (md) biref_outfile_close(md, 0, NULL, 0);
    for (int k = 0; k < NINTEGRATORS; k++) biref_integrator_destroy(its[k]);
    biref_spectral_destroy(sp);
    if (run.res)
        for (int i = 0; i < run.nmat; i++) {
            free(run.res[i].theta);
            free(run.res[i].phi0);
        }
    free(run.mat);
    free(run.res);
    return rc;
}
