/* biref photoelastic: a stressed plate in a plane or circular polariscope, as a picture (PNG)
 * and/or as a profile of intensity, retardation and fringe order along a line
 * (docs/PHOTOELASTICITY.md). The command line: photoelastic_args.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_render.h"
#include "commands.h"
#include "json_out.h"
#include "photoelastic_args.h"

static const char *const CMD = "photoelastic";

/* Scales a monochromatic colour to a displayable tint: band-normalised XYZ of the spectral line,
 * negative linear sRGB clipped (spectral colours lie outside the gamut) and the largest
 * component raised to 1. */
static int mono_tint(double lambda, double tint[3])
{
    biref_cmf_band band;
    if (biref_cmf_band_init(&band, BIREF_CMF_CIE1931, 380.0, 780.0, NULL, 0) != BIREF_OK) return -1;
    double lam[3], rgb[3];
    biref_cmf_band_eval(&band, lambda, lam);
    biref_xyz_to_linear_srgb(lam, rgb);
    double mx = 0;
    for (int i = 0; i < 3; i++) {
        rgb[i] = fmax(rgb[i], 0.0);
        mx = fmax(mx, rgb[i]);
    }
    if (!(mx > 0)) return -1;
    for (int i = 0; i < 3; i++) rgb[i] /= mx;
    biref_linear_srgb_to_xyz(rgb, tint);
    return 0;
}

static cJSON *material_json(const pe_args *a, const biref_pe_material *m, double lambda_for_f)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "name", m->name);
    cJSON_AddBoolToObject(o, "default", !a->material_given && !strcmp(m->name, "polycarbonate"));
    if (!isnan(a->fringe_value)) {
        cJSON_AddNumberToObject(o, "fringe_value_N_per_mm", a->fringe_value);
        cJSON_AddNumberToObject(o, "fringe_value_lambda_nm", a->fringe_value_nm);
    }
    cJSON_AddNumberToObject(o, "n0", m->n0);
    cJSON_AddNumberToObject(o, "C_brewster", m->C_per_Pa / BIREF_BREWSTER);
    cJSON_AddNumberToObject(o, "C_lambda_nm", m->lambda_ref_nm > 0 ? m->lambda_ref_nm : BIREF_PE_LAMBDA_REF_NM);
    cJSON_AddNumberToObject(o, "dispersion_alpha", m->dispersion_alpha);
    cJSON_AddNumberToObject(o, "fringe_constant_N_per_m", biref_pe_fringe_constant(m, lambda_for_f));
    cJSON_AddNumberToObject(o, "fringe_constant_lambda_nm", lambda_for_f);
    cJSON_AddStringToObject(o, "source", m->source);
    return o;
}

/* Everything one run computes before it writes: the polariscope, the stress field, the picture's
 * options and the JSON report under construction. */
typedef struct {
    biref_pe_setup setup;
    biref_pe_field field;
    biref_pe_grid *grid;
    biref_spectral *sp;
    biref_pe_image_opts io;
    double h, lambda_N, tint_rgb[3];
    cJSON *root;
} pe_run;

/* The material with --n0/--C-brewster/--fringe-value applied. Returns a CLI exit code. */
static int make_material(const pe_args *a, biref_pe_material *m)
{
    (void)biref_pe_material_preset(a->material_name, m);
    if (!isnan(a->n0) || !isnan(a->c_brew) || !isnan(a->fringe_value)) {
        m->name = "custom";
        m->source = !isnan(a->fringe_value) ? "--fringe-value" : "user";
        if (!isnan(a->n0)) m->n0 = a->n0;
        if (!isnan(a->c_brew)) m->C_per_Pa = a->c_brew * BIREF_BREWSTER;
        /* f = lambda / C (N/m per fringe); F N/mm = 1e3 F N/m. */
        if (!isnan(a->fringe_value)) {
            m->C_per_Pa = a->fringe_value_nm * 1e-9 / (a->fringe_value * 1e3);
            m->lambda_ref_nm = a->fringe_value_nm; /* C holds there: dispersion scales from it */
        }
    }
    if (!isnan(a->dispersion_alpha)) m->dispersion_alpha = a->dispersion_alpha;
    char msg[256];
    if (biref_pe_material_check(m, msg, sizeof msg) != BIREF_OK) return cli_error(CMD, "material: %s", msg), CLI_EXIT_USAGE;
    return CLI_EXIT_OK;
}

/* The material as one line: what was used and where it came from. */
static void print_material(const pe_args *a, const biref_pe_material *m)
{
    const double lam = isnan(a->fringe_value_nm) ? 546.1 : a->fringe_value_nm;
    const int dflt = !a->material_given && !strcmp(m->name, "polycarbonate");
    printf("%smaterial: %s%s, n0 %.4g, C %.4g Br = fringe value %.4g N/mm at %g nm\n", a->have_profile ? "# " : "",
           m->name, dflt ? " (the default; --material, --C-brewster or --fringe-value to change)" : "", m->n0,
           m->C_per_Pa / BIREF_BREWSTER, biref_pe_fringe_constant(m, lam) * 1e-3, lam);
}

/* The picture's frame: the window, else the part with the margin; a window off the part is
 * refused. Returns a CLI exit code. */
static int make_frame(const pe_args *a, biref_pe_field *f)
{
    const double mm = 1e-3, *fr = f->frame;
    if (a->have_view) {
        if (a->view[1] * mm < fr[0] || a->view[0] * mm > fr[1] || a->view[3] * mm < fr[2] || a->view[2] * mm > fr[3])
            return cli_error(CMD, "--window-mm: x %g..%g, y %g..%g does not overlap the part (x %g..%g, y %g..%g mm)",
                             a->view[0], a->view[1], a->view[2], a->view[3], fr[0] / mm, fr[1] / mm, fr[2] / mm,
                             fr[3] / mm),
                   CLI_EXIT_USAGE;
        for (int i = 0; i < 4; i++) f->frame[i] = a->view[i] * mm;
        return CLI_EXIT_OK;
    }
    const int fe = a->kind == BIREF_PE_NODES;
    const double pct = isnan(a->margin_pct) ? (fe ? 5.0 : 0.0) : a->margin_pct;
    const double d = pct / 100.0 * fmax(fr[1] - fr[0], fr[3] - fr[2]);
    f->frame[0] -= d, f->frame[1] += d, f->frame[2] -= d, f->frame[3] += d;
    return CLI_EXIT_OK;
}

/* The stress field of the specimen, SI units. Returns a CLI exit code. */
static int make_field(pe_args *a, pe_run *run)
{
    const double mm = 1e-3, h = run->h;
    char msg[256];
    biref_status st = BIREF_OK;
    switch (a->kind) {
    case BIREF_PE_DISK:
        st = biref_pe_field_disk(&run->field, pe_geo_or(a, PE_RADIUS, 25.0) * mm, h, pe_geo_or(a, PE_LOAD, 500.0), msg,
                                 sizeof msg);
        break;
    case BIREF_PE_HOLE: {
        double w = pe_geo_or(a, PE_WIDTH, 60.0);
        st = biref_pe_field_hole(&run->field, pe_geo_or(a, PE_RADIUS, 5.0) * mm, w * mm, pe_geo_or(a, PE_HEIGHT, w) * mm,
                                 h, pe_geo_or(a, PE_STRESS, 4.0) * 1e6, pe_geo_or(a, PE_TENSION, 0.0) * M_PI / 180.0,
                                 msg, sizeof msg);
        break;
    }
    case BIREF_PE_BEAM:
        st = biref_pe_field_beam(&run->field, pe_geo_or(a, PE_LENGTH, 100.0) * mm, pe_geo_or(a, PE_DEPTH, 20.0) * mm, h,
                                 pe_geo_or(a, PE_MOMENT, 2000.0) * 1e-3, msg, sizeof msg);
        break;
    case BIREF_PE_NODES: {
        int rc = pe_ext_nodes_field(&a->ext, &run->field, h);
        if (rc) return rc;
        break;
    }
    default:
        st = biref_pe_grid_load(a->grid_path, &run->grid, msg, sizeof msg);
        if (st != BIREF_OK) {
            cli_error(CMD, "%s: %s", a->grid_path, msg);
            return st == BIREF_ERR_NOMEM ? CLI_EXIT_FAIL : CLI_EXIT_USAGE;
        }
        st = biref_pe_field_grid(&run->field, run->grid, h, msg, sizeof msg);
        break;
    }
    if (st != BIREF_OK) return cli_error(CMD, "%s: %s", pe_kind_name(a->kind), msg), CLI_EXIT_USAGE;
    return make_frame(a, &run->field);
}

/* Material, field, polariscope, picture size and spectral tables. Returns a CLI exit code. */
static int prepare(pe_args *a, pe_run *run)
{
    int rc = make_material(a, &run->setup.material);
    if (rc) return rc;
    run->h = (isnan(a->thickness_mm) ? (a->kind == BIREF_PE_HOLE ? 3.0 : 6.0) : a->thickness_mm) * 1e-3;
    if ((rc = make_field(a, run))) return rc;
    biref_pe_setup *setup = &run->setup;
    setup->thickness = run->h;
    setup->eta_i = a->eta_i;
    setup->light = a->light;
    setup->lambda_nm = a->lambda;
    biref_pe_polariscope_make(a->pk, a->ft, a->polarizer_deg * M_PI / 180.0, &setup->pol);
    biref_pe_image_opts *io = &run->io;
    *io = (biref_pe_image_opts){.supersample = (int)a->supersample,
                                .threads = (int)a->threads,
                                .tint = {1, 1, 1},
                                .tilt = a->tilt_deg * M_PI / 180.0};
    if (a->tint && mono_tint(a->lambda, io->tint))
        return cli_error(CMD, "--tint: %g nm has no visible colour (380-780 nm)", a->lambda), CLI_EXIT_USAGE;
    for (int i = 0; i < 3; i++) {
        run->tint_rgb[i] = io->tint[i];
        io->tint[i] *= a->exposure;
    }
    cli_files files;
    cli_files_init(&files);
    cli_files_read(&files, "--stress-grid", a->grid_path);
    pe_ext_files(&a->ext, a->out, &files);
    rc = cli_files_check(CMD, &files);
    cli_files_free(&files);
    if (rc) return rc;
    char why[BIREF_MSG_SIZE];
    if (a->light == BIREF_PE_WHITE && biref_spectral_create(NULL, &run->sp, why, sizeof why) != BIREF_OK)
        return cli_error(CMD, "cannot create the spectral tables: %s", why), CLI_EXIT_FAIL;
    if (a->json) run->root = cJSON_CreateObject();
    /* Square pixels: the longer side of the frame gets --size pixels. */
    const double *fr = run->field.frame;
    double fw = fr[1] - fr[0], fh = fr[3] - fr[2];
    fh *= cos(io->tilt); /* the tilted plate is foreshortened along y */
    io->width = fw >= fh ? (int)a->size : (int)fmax(1, lround(a->size * fw / fh));
    io->height = fw >= fh ? (int)fmax(1, lround(a->size * fh / fw)) : (int)a->size;
    run->lambda_N = a->light == BIREF_PE_MONO ? a->lambda : WHITE_FRINGE_LAMBDA_NM;
    return CLI_EXIT_OK;
}

/* The sRGB picture of the plate through the PNG writer of the extensions. Returns a CLI exit code. */
static int write_png(const pe_args *a, pe_run *run, const pe_ext_ctx *ectx)
{
    const biref_pe_image_opts *io = &run->io;
    size_t npx = (size_t)io->width * io->height;
    float *xyz = malloc(npx * 3 * sizeof *xyz);
    unsigned char *rgb = malloc(npx * 3);
    int rc = CLI_EXIT_OK;
    char why[BIREF_MSG_SIZE];
    double t0 = biref_wall_seconds();
    if (!xyz || !rgb) {
        cli_error(CMD, "out of memory for a %d x %d picture", io->width, io->height);
        rc = CLI_EXIT_FAIL;
    } else {
        biref_progress_bar bar;
        biref_progress_bar_init(&bar, stderr, 1, "photoelastic");
        biref_pe_image_opts with_bar = *io;
        with_bar.progress = biref_progress_bar_update;
        with_bar.progress_user = &bar;
        if ((a->prefilter ? biref_pe_render_prefiltered : biref_pe_render)(&run->setup, run->sp, &run->field, &with_bar,
                                                                          xyz, why, sizeof why) != BIREF_OK) {
            cli_error(CMD, "%s", why);
            rc = CLI_EXIT_FAIL;
        }
        biref_progress_bar_finish(&bar);
    }
    double ms = 1e3 * (biref_wall_seconds() - t0);
    if (!rc && a->light == BIREF_PE_WHITE && a->exposure != 1.0)
        for (size_t i = 0; i < npx * 3; i++) xyz[i] = (float)(xyz[i] * a->exposure);
    /* A non-finite colour is never an output (the loads are bounded where they enter). */
    for (size_t i = 0; !rc && i < npx * 3; i++)
        if (!isfinite(xyz[i])) {
            cli_error(CMD, "%s: the picture came out non-finite (no image written)", pe_kind_name(a->kind));
            rc = CLI_EXIT_FAIL;
        }
    if (!rc) {
        biref_xyz_image_to_srgb8(xyz, npx, rgb);
        rc = pe_ext_write_png(&a->ext, ectx, rgb);
    }
    free(xyz);
    free(rgb);
    if (rc) return rc;
    if (run->root) {
        cJSON_AddStringToObject(run->root, "output", a->out);
        cJSON_AddNumberToObject(run->root, "width", io->width);
        cJSON_AddNumberToObject(run->root, "height", io->height);
        cJSON_AddNumberToObject(run->root, "supersample", io->supersample);
        cJSON_AddStringToObject(run->root, "antialias", a->prefilter ? "prefilter" : "none");
        cJSON_AddNumberToObject(run->root, "ms", ms);
    } else if (!a->have_profile) {
        printf("wrote %s: %d x %d px, %d x %d samples per pixel, %.0f ms\n", a->out, io->width, io->height,
               io->supersample, io->supersample, ms);
    }
    return CLI_EXIT_OK;
}

/* The picture, a map or a phase-stepped set (-o). Returns a CLI exit code. */
static int write_output(const pe_args *a, pe_run *run)
{
    const pe_ext_ctx ectx = {&run->setup, run->sp,       &run->field, &run->io,
                             a->out,      a->exposure,   run->lambda_N, run->tint_rgb,
                             run->root,   a->polarizer_deg * M_PI / 180};
    if (pe_ext_owns_output(&a->ext)) return pe_ext_write(&a->ext, &ectx);
    return write_png(a, run, &ectx);
}

static void add_summary(const pe_args *a, const pe_run *run)
{
    cJSON *root = run->root;
    const double mm = 1e-3;
    cJSON_AddStringToObject(root, "specimen", pe_kind_name(a->kind));
    cJSON_AddItemToObject(root, "material", material_json(a, &run->setup.material, run->lambda_N));
    cJSON_AddNumberToObject(root, "thickness_mm", run->h / mm);
    cJSON_AddNumberToObject(root, "eta_i", a->eta_i);
    cJSON_AddStringToObject(root, "polariscope", a->pk == BIREF_PE_PLANE ? "plane" : "circular");
    cJSON_AddStringToObject(root, "field", a->ft == BIREF_PE_DARK ? "dark" : "light");
    cJSON_AddNumberToObject(root, "polarizer_deg", a->polarizer_deg);
    cJSON_AddNumberToObject(root, "tilt_deg", a->tilt_deg);
    cJSON_AddStringToObject(root, "light", a->light == BIREF_PE_MONO ? "mono" : "white");
    if (a->light == BIREF_PE_MONO) cJSON_AddNumberToObject(root, "lambda_nm", a->lambda);
    cJSON_AddNumberToObject(root, "fringe_order_lambda_nm", run->lambda_N);
    if (a->light == BIREF_PE_WHITE)
        cJSON_AddStringToObject(root, "fringe_order_note",
                                "white light has no single wavelength: N = retardation / 550 nm (mid-band)");
    const double *f = run->field.frame;
    double fr[4] = {f[0] / mm, f[1] / mm, f[2] / mm, f[3] / mm};
    cJSON_AddItemToObject(root, "frame_mm", cJSON_CreateDoubleArray(fr, 4));
}

/* One point of the profile as a JSON object. */
static cJSON *profile_point_json(double x, double y, int inside, const biref_pe_principal *p, double ret,
                                 double lambda_N, double intensity, const double col[3])
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "x_mm", x);
    cJSON_AddNumberToObject(o, "y_mm", y);
    cJSON_AddBoolToObject(o, "inside", inside);
    if (inside) {
        cJSON_AddNumberToObject(o, "sigma1_MPa", p->s1 / 1e6);
        cJSON_AddNumberToObject(o, "sigma2_MPa", p->s2 / 1e6);
        cJSON_AddNumberToObject(o, "phi_deg", p->phi * 180.0 / M_PI);
        cJSON_AddNumberToObject(o, "retardation_nm", ret);
        cJSON_AddNumberToObject(o, "fringe_order", ret / lambda_N);
    } else {
        cJSON_AddNullToObject(o, "sigma1_MPa");
        cJSON_AddNullToObject(o, "sigma2_MPa");
        cJSON_AddNullToObject(o, "phi_deg");
        cJSON_AddNullToObject(o, "retardation_nm");
        cJSON_AddNullToObject(o, "fringe_order");
    }
    cJSON_AddNumberToObject(o, "intensity", intensity);
    cJSON_AddItemToObject(o, "xyz", cJSON_CreateDoubleArray(col, 3));
    unsigned char c8[3];
    biref_xyz_to_srgb8(col, c8);
    int ci[3] = {c8[0], c8[1], c8[2]};
    cJSON_AddItemToObject(o, "srgb8", cJSON_CreateIntArray(ci, 3));
    return o;
}

/* Intensity, retardation and fringe order along the --profile line, as a table or into the JSON
 * report. */
static void print_profile(const pe_args *a, const pe_run *run)
{
    const double mm = 1e-3, *profile = a->profile, lambda_N = run->lambda_N, tilt = run->io.tilt;
    const int mono = a->light == BIREF_PE_MONO;
    cJSON *arr = run->root ? cJSON_AddArrayToObject(run->root, "profile") : NULL;
    if (!run->root) {
        printf("# profile from (%g, %g) to (%g, %g) mm, %s light%s; N = retardation / %g nm\n", profile[0], profile[1],
               profile[2], profile[3], mono ? "monochromatic" : "white", mono ? "" : " (intensity = luminance Y)",
               lambda_N);
        printf("# %10s %10s %6s %12s %12s %9s %14s %12s %10s\n", "x_mm", "y_mm", "inside", "sigma1_MPa", "sigma2_MPa",
               "phi_deg", "retardation_nm", "fringe_order", "intensity");
    }
    const double bg = biref_pe_polariscope_background(&run->setup.pol) * a->exposure;
    for (long i = 0; i < a->samples; i++) {
        double t = (double)i / (double)(a->samples - 1);
        double x = profile[0] + t * (profile[2] - profile[0]), y = profile[1] + t * (profile[3] - profile[1]);
        biref_pe_stress s;
        int inside = biref_pe_field_stress(&run->field, x * mm, y * mm, &s);
        double col[3] = {bg, bg, bg};
        biref_pe_principal p = {0, 0, 0, 1, 0};
        double ret = 0;
        if (inside) {
            biref_pe_principal_of(&s, &p);
            if (tilt > 0.0) {
                if (biref_pe_shade_oblique(&run->setup, run->sp, &p, tilt, col) != BIREF_OK)
                    col[0] = col[1] = col[2] = NAN;
            } else {
                biref_pe_shade(&run->setup, run->sp, &p, col);
            }
            for (int j = 0; j < 3; j++) col[j] *= a->exposure;
            ret = tilt > 0.0 ? biref_pe_retardation_oblique_nm(&run->setup, &p, tilt)
                             : biref_pe_retardation_at_nm(&run->setup, &p, lambda_N);
        }
        /* Mono: the grey level, shown through the tint; white: the luminance Y. */
        double intensity = col[1];
        if (mono)
            for (int j = 0; j < 3; j++) col[j] *= run->tint_rgb[j];
        if (arr)
            cJSON_AddItemToArray(arr, profile_point_json(x, y, inside, &p, ret, lambda_N, intensity, col));
        else if (inside)
            printf("  %10.4f %10.4f %6s %12.5g %12.5g %9.3f %14.3f %12.8f %10.8f\n", x, y, "yes", p.s1 / 1e6,
                   p.s2 / 1e6, p.phi * 180.0 / M_PI, ret, ret / lambda_N, intensity);
        else
            printf("  %10.4f %10.4f %6s %12s %12s %9s %14s %12s %10.8f\n", x, y, "no", "-", "-", "-", "-", "-",
                   intensity);
    }
}

int cmd_photoelastic(int argc, char **argv)
{
    if (argc > 1 && !strcmp(argv[1], "calibrate")) return cmd_photoelastic_calibrate(argc - 1, argv + 1);
    if (argc > 1 && !strcmp(argv[1], "demodulate")) {
        for (int i = 2; i < argc; i++)
            if (!strcmp(argv[i], "--tfp") || !strncmp(argv[i], "--tfp=", 6)) return cmd_photoelastic_tfp(argc - 1, argv + 1);
        return cmd_photoelastic_demodulate(argc - 1, argv + 1);
    }
    pe_args a;
    int r = pe_args_parse(argc, argv, &a);
    if (r) return r > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    pe_run run;
    memset(&run, 0, sizeof run);
    int rc = prepare(&a, &run);
    if (!rc && a.out) rc = write_output(&a, &run);
    if (!rc && run.root) add_summary(&a, &run);
    if (!rc && !run.root) print_material(&a, &run.setup.material);
    if (!rc && a.have_profile) print_profile(&a, &run);
    if (!rc && run.root) {
        if (json_print_and_free(run.root)) rc = CLI_EXIT_FAIL;
        run.root = NULL;
    }
    cJSON_Delete(run.root);
    biref_spectral_destroy(run.sp);
    biref_pe_grid_destroy(run.grid);
    pe_ext_free(&a.ext);
    return rc;
}
