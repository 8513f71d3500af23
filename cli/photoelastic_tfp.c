/* biref photoelastic calibrate / demodulate --tfp: fringe orders from one white-light colour
 * picture (RGB or three-fringe photoelasticity; docs/PHOTOELASTICITY.md, "Fringe orders from one
 * colour picture"). calibrate writes the colour-versus-order table of a polariscope, light and
 * camera; demodulate --tfp matches a photo's colours against it from a seed pixel. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_opts.h"
#include "cli_render.h"
#include "json_out.h"
#include "outfile.h"
#include "pe_image_io.h"
#include "photoelastic_args.h"
#include "photoelastic_ext.h"

static const char *const CAL = "photoelastic calibrate";
static const char *const TFP = "photoelastic demodulate --tfp";

/* ------------------------------------------------------------------------ */
/* Tables                                                                    */
/* ------------------------------------------------------------------------ */

/* A CSV of four numeric columns after a header (and '#' comments): the table (N, r, g, b) or a
 * camera's sensitivities (lambda_nm, r, g, b). Returns a CLI exit code. */
static int read_columns4(const char *cmd, const char *path, const char *what, double **col0, double **rgb, size_t *n,
                         int *linear)
{
    FILE *f = fopen(path, "rb");
    if (!f) return cli_error(cmd, "%s: cannot read", path), CLI_EXIT_USAGE;
    char line[512];
    size_t cap = 0;
    long ln = 0;
    int header = 0, rc = CLI_EXIT_OK;
    *n = 0;
    *col0 = *rgb = NULL;
    if (linear) *linear = 0;
    while (!rc && fgets(line, sizeof line, f)) {
        ln++;
        if (!strchr(line, '\n') && !feof(f)) rc = (cli_error(cmd, "%s: line %ld: longer than 511 characters", path, ln), CLI_EXIT_USAGE);
        if (linear && strstr(line, "# encoding: linear")) *linear = 1;
        char *p = line;
        while (*p == ' ' || *p == '\t') p++;
        if (rc || *p == '#' || *p == '\n' || *p == '\r' || !*p) continue;
        if (!header) { /* the header names the columns */
            header = 1;
            continue;
        }
        double v[4];
        char *end = p;
        for (int c = 0; c < 4 && !rc; c++) {
            v[c] = strtod(end, &end);
            while (*end == ' ' || *end == '\t') end++;
            if ((c < 3 && *end != ',') || !isfinite(v[c]))
                rc = (cli_error(cmd, "%s: line %ld: expected four numbers %s", path, ln, what), CLI_EXIT_USAGE);
            if (c < 3) end++;
        }
        if (rc) break;
        if (*n == cap) {
            cap = cap ? 2 * cap : 256;
            double *a = realloc(*col0, cap * sizeof *a), *b = a ? realloc(*rgb, cap * 3 * sizeof *b) : NULL;
            if (a) *col0 = a;
            if (b) *rgb = b;
            if (!a || !b) rc = (cli_error(cmd, "out of memory"), CLI_EXIT_FAIL);
            if (rc) break;
        }
        (*col0)[*n] = v[0];
        memcpy(*rgb + 3 * *n, v + 1, 3 * sizeof *v);
        ++*n;
    }
    fclose(f);
    if (!rc && *n < 3) rc = (cli_error(cmd, "%s: %zu rows; expected a header and at least 3 rows %s", path, *n, what), CLI_EXIT_USAGE);
    return rc;
}

/* ------------------------------------------------------------------------ */
/* calibrate                                                                 */
/* ------------------------------------------------------------------------ */

enum { OPT_POLARISCOPE = 1, OPT_FIELD, OPT_MATERIAL };

typedef struct {
    const char *out, *camera, *material;
    double max_order, step, eta_i, n0;
    int json, circular, light_field;
} cal_args;

static int cal_handle(void *args, int code, const char *arg)
{
    cal_args *a = args;
    biref_pe_material m;
    switch (code) {
    case OPT_POLARISCOPE:
        if (strcmp(arg, "plane") && strcmp(arg, "circular"))
            return cli_error(CAL, "--polariscope: expected plane or circular, got '%s'", arg), -1;
        a->circular = !strcmp(arg, "circular");
        return 0;
    case OPT_FIELD:
        if (strcmp(arg, "dark") && strcmp(arg, "light")) return cli_error(CAL, "--field: expected dark or light, got '%s'", arg), -1;
        a->light_field = !strcmp(arg, "light");
        return 0;
    default:
        if (biref_pe_material_preset(arg, &m) != BIREF_OK)
            return cli_error(CAL, "--material: expected polycarbonate, epoxy, pmma or glass, got '%s'", arg), -1;
        a->material = arg;
        return 0;
    }
}

#define F(field) offsetof(cal_args, field)
static const cli_opt CAL_OPTS[] = {
    CLI_STRING("output", 'o', "FILE.csv", F(out), "the table: fringe_order,r,g,b (0..1), one row per step"),
    CLI_STRING("camera", 0, "srgb|FILE.csv", F(camera),
               "srgb (default): the CIE 1931 observer and encoded sRGB, as biref's\n"
               "pictures and an 8-bit camera's sRGB output; FILE.csv: the camera's\n"
               "spectral sensitivities lambda_nm,r,g,b (linear camera RGB)"),
    CLI_DOUBLE("max-order", "N", F(max_order), 0.1, 50, "largest fringe order in the table (default 6)"),
    CLI_DOUBLE("step", "S", F(step), 0.001, 0.1, "fringe-order step (default 0.01)"),
    CLI_CUSTOM("polariscope", "P", OPT_POLARISCOPE, "plane (at 45 deg to the stress) or circular (default)"),
    CLI_CUSTOM("field", "F", OPT_FIELD, "dark (default) or light"),
    CLI_CUSTOM("material", "M", OPT_MATERIAL, "its index sets the surface reflections: polycarbonate (default), ..."),
    CLI_DOUBLE("eta-i", "N", F(eta_i), 1, 5, "index around the plate (default 1)"),
    CLI_FLAG("json", 0, F(json), "machine-readable report"),
};
#undef F

const cli_command_spec CLI_PHOTOELASTIC_CALIBRATE = {
    "photoelastic calibrate",
    "usage: biref photoelastic calibrate -o TABLE.csv [OPTIONS]\n\n"
    "The colour a camera records through a polariscope in white light (illuminant E) at each\n"
    "fringe order N (N at 550 nm, as biref's white-light maps), from biref's spectral integration\n"
    "of the plate: the calibration of 'biref photoelastic demodulate --tfp'.\n\n",
    CAL_OPTS,
    CLI_OPTS_COUNT(CAL_OPTS),
    "Exit status: 0 success, 1 runtime failure, 2 bad usage or input.\n\n"
    "Example:\n"
    "  biref photoelastic calibrate -o table.csv\n"
    "  biref photoelastic demodulate --tfp photo.png --calibration table.csv --seed 160,20,0 -o N.csv\n",
    0,
    cal_handle,
    0,
};

/* Writes the table with comment lines that say what it is. Returns a CLI exit code. */
static int write_table(const cal_args *a, size_t n, const double *orders, const double *rgb, int linear)
{
    char msg[600];
    biref_outfile *o = biref_outfile_open(a->out, msg, sizeof msg);
    if (!o) return cli_error(CAL, "%s", msg), CLI_EXIT_FAIL;
    FILE *f = biref_outfile_stream(o);
    int ok = fprintf(f, "# biref photoelastic calibrate: %s %s-field polariscope, white light (illuminant E), camera %s\n"
                        "# fringe_order: N = retardation / 550 nm\n# encoding: %s\nfringe_order,r,g,b\n",
                     a->circular ? "circular" : "plane", a->light_field ? "light" : "dark",
                     a->camera ? a->camera : "srgb", linear ? "linear (camera RGB)" : "srgb (encoded, 0..1)") > 0;
    for (size_t k = 0; ok && k < n; k++)
        ok = fprintf(f, "%.4f,%.6f,%.6f,%.6f\n", orders[k], rgb[3 * k], rgb[3 * k + 1], rgb[3 * k + 2]) > 0;
    if (biref_outfile_close(o, ok, msg, sizeof msg) != BIREF_OK || !ok) return cli_error(CAL, "%s", msg), CLI_EXIT_FAIL;
    return CLI_EXIT_OK;
}

/* The table's values. Returns a CLI exit code. */
static int compute_table(const cal_args *a, size_t n, const double *orders, double *rgb, int *linear)
{
    biref_pe_setup s;
    memset(&s, 0, sizeof s);
    biref_pe_material_preset(a->material, &s.material);
    s.thickness = 6e-3;
    s.eta_i = a->eta_i;
    s.light = BIREF_PE_WHITE;
    biref_pe_polariscope_make(a->circular ? BIREF_PE_CIRCULAR : BIREF_PE_PLANE, a->light_field ? BIREF_PE_LIGHT : BIREF_PE_DARK,
                              0.0, &s.pol);
    char msg[BIREF_MSG_SIZE];
    biref_spectral *sp = NULL;
    double *lam = NULL, *sens = NULL;
    size_t ns = 0;
    int rc = CLI_EXIT_OK;
    *linear = a->camera && strcmp(a->camera, "srgb");
    if (*linear)
        rc = read_columns4(CAL, a->camera, "lambda_nm,r,g,b", &lam, &sens, &ns, NULL);
    else if (biref_spectral_create(NULL, &sp, msg, sizeof msg) != BIREF_OK)
        rc = (cli_error(CAL, "cannot create the spectral tables: %s", msg), CLI_EXIT_FAIL);
    biref_pe_camera cam = {ns, lam, sens};
    if (!rc && biref_pe_tfp_calibrate(&s, sp, *linear ? &cam : NULL, 550.0, n, orders, rgb, msg, sizeof msg) != BIREF_OK)
        rc = (cli_error(CAL, "%s%s%s", *linear ? a->camera : "", *linear ? ": " : "", msg), CLI_EXIT_USAGE);
    biref_spectral_destroy(sp);
    free(lam);
    free(sens);
    return rc;
}

int cmd_photoelastic_calibrate(int argc, char **argv)
{
    cal_args a = {.material = "polycarbonate", .max_order = 6, .step = 0.01, .eta_i = 1, .circular = 1};
    cli_parsed p;
    int r = cli_opts_parse(&CLI_PHOTOELASTIC_CALIBRATE, &a, argc, argv, &p);
    if (r) return r > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    if (p.n_args) return cli_error(CAL, "unexpected argument '%s'", argv[p.first_arg]), CLI_EXIT_USAGE;
    if (!a.out) return cli_error(CAL, "missing -o TABLE.csv"), CLI_EXIT_USAGE;
    const char *inputs[1] = {a.camera};
    int rc = cli_check_output(CAL, a.out, inputs, 1);
    if (rc) return rc;
    const size_t n = (size_t)floor(a.max_order / a.step + 1e-9) + 1;
    double *orders = malloc(n * sizeof *orders), *rgb = malloc(n * 3 * sizeof *rgb);
    int linear = 0;
    if (!orders || !rgb) rc = (cli_error(CAL, "out of memory"), CLI_EXIT_FAIL);
    for (size_t k = 0; !rc && k < n; k++) orders[k] = (double)k * a.step;
    if (!rc) rc = compute_table(&a, n, orders, rgb, &linear);
    if (!rc) rc = write_table(&a, n, orders, rgb, linear);
    if (!rc && a.json) {
        cJSON *root = cJSON_CreateObject();
        cJSON_AddStringToObject(root, "output", a.out);
        cJSON_AddNumberToObject(root, "rows", (double)n);
        cJSON_AddNumberToObject(root, "max_order", orders[n - 1]);
        cJSON_AddStringToObject(root, "camera", a.camera ? a.camera : "srgb");
        cJSON_AddStringToObject(root, "encoding", linear ? "linear" : "srgb");
        cJSON_AddNumberToObject(root, "fringe_order_lambda_nm", 550);
        rc = json_print_and_free(root) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
    } else if (!rc) {
        printf("wrote %s: %zu rows, N 0..%g at 550 nm, camera %s\n", a.out, n, orders[n - 1], a.camera ? a.camera : "srgb");
    }
    free(orders);
    free(rgb);
    return rc;
}

/* ------------------------------------------------------------------------ */
/* demodulate --tfp                                                          */
/* ------------------------------------------------------------------------ */

enum { OPT_SEED = 1 };

typedef struct {
    const char *photo, *table, *out;
    int json, have_seed;
    biref_pe_tfp_opts o;
} tfp_args;

static int tfp_handle(void *args, int code, const char *arg)
{
    tfp_args *a = args;
    (void)code;
    double v[3] = {0, 0, NAN};
    const int n = strchr(arg, ',') && strchr(strchr(arg, ',') + 1, ',') ? 3 : 2;
    if (cli_parse_list(TFP, "--seed", arg, v, n)) return -1;
    if (v[0] != floor(v[0]) || v[1] != floor(v[1]) || !(fabs(v[0]) < 1e9 && fabs(v[1]) < 1e9))
        return cli_error(TFP, "--seed: expected whole pixel coordinates PX,PY[,N], got '%s'", arg), -1;
    if (n == 3 && !(v[2] >= 0 && v[2] <= 1000)) return cli_error(TFP, "--seed: the order must be in 0..1000, got %g", v[2]), -1;
    a->o.seed_x = (int)v[0];
    a->o.seed_y = (int)v[1];
    a->o.seed_order = v[2];
    a->have_seed = 1;
    return 0;
}

#define F(field) offsetof(tfp_args, field)
static const cli_opt TFP_OPTS[] = {
    CLI_STRING("tfp", 0, "PHOTO.png", F(photo), "the colour picture (8-bit: as encoded, e.g. sRGB; 16-bit: as stored)"),
    CLI_STRING("calibration", 0, "TABLE.csv", F(table), "the table of 'biref photoelastic calibrate' (same encoding)"),
    CLI_CUSTOM("seed", "PX,PY[,N]", OPT_SEED,
               "the pixel (column, row from the top, 0-based) the matching grows from,\n"
               "with its fringe order N if known (else its best match in the table)"),
    CLI_DOUBLE("window", "W", F(o.window), 0.01, 10,
               "largest change of order from a pixel to its neighbour (default 0.3)"),
    CLI_DOUBLE("max-residual", "R", F(o.max_residual), 1e-4, 2,
               "RMS colour difference (0..1) above which a pixel is left NaN (default 0.08)"),
    CLI_STRING("output", 'o', "FILE", F(out), "the fringe-order map: FILE.csv (col,row,fringe_order) or FILE.pfm"),
    CLI_FLAG("json", 0, F(json), "machine-readable report"),
};
#undef F

const cli_command_spec CLI_PHOTOELASTIC_TFP = {
    "photoelastic demodulate --tfp",
    "usage: biref photoelastic demodulate --tfp PHOTO.png --calibration TABLE.csv --seed PX,PY[,N] -o N.csv\n\n"
    "Fringe orders from one white-light colour picture (RGB or three-fringe photoelasticity):\n"
    "each pixel's colour is matched against the calibration table within a window around the\n"
    "order of the neighbour it is reached from, growing from the seed, best-matched pixels first.\n\n",
    TFP_OPTS,
    CLI_OPTS_COUNT(TFP_OPTS),
    "Reliable, measured on biref's disk with camera noise 2/255: N within 0.05 up to N = 3 (see\n"
    "docs/PHOTOELASTICITY.md); beyond N of about 4 the colours of white light fade.\n\n"
    "Exit status: 0 success, 1 runtime failure, 2 bad usage or input.\n",
    0,
    tfp_handle,
    0,
};

/* Writes the map and reports. Returns a CLI exit code. */
static int tfp_report(const tfp_args *a, int W, int H, const float *N)
{
    char msg[600];
    biref_status st = pe_has_ext(a->out, ".csv") ? pe_csv_write_map(a->out, W, H, NULL, "fringe_order", N, msg, sizeof msg)
                                                 : pe_pfm_write(a->out, W, H, 1, N, msg, sizeof msg);
    if (st != BIREF_OK) return cli_error(TFP, "%s", msg), CLI_EXIT_FAIL;
    size_t valid = 0;
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < (size_t)W * H; i++)
        if (!isnan(N[i])) valid++, lo = fmin(lo, N[i]), hi = fmax(hi, N[i]);
    if (!a->json) {
        printf("wrote %s: %d x %d px, %zu matched (N %.3g .. %.3g), %zu NaN\n", a->out, W, H, valid, valid ? lo : 0,
               valid ? hi : 0, (size_t)W * H - valid);
        return CLI_EXIT_OK;
    }
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "output", a->out);
    cJSON_AddNumberToObject(root, "width", W);
    cJSON_AddNumberToObject(root, "height", H);
    cJSON_AddNumberToObject(root, "matched_pixels", (double)valid);
    if (valid) {
        cJSON_AddNumberToObject(root, "fringe_order_min", lo);
        cJSON_AddNumberToObject(root, "fringe_order_max", hi);
    }
    return json_print_and_free(root) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

int cmd_photoelastic_tfp(int argc, char **argv)
{
    tfp_args a = {.o = {.window = 0.3, .max_residual = 0.08, .seed_order = NAN}};
    for (int i = 1; i < argc; i++) /* "--tfp --help" is a request for help, not a photo named --help */
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) return cli_opts_help(&CLI_PHOTOELASTIC_TFP, stdout), CLI_EXIT_OK;
    cli_parsed p;
    int r = cli_opts_parse(&CLI_PHOTOELASTIC_TFP, &a, argc, argv, &p);
    if (r) return r > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    if (p.n_args) return cli_error(TFP, "unexpected argument '%s'", argv[p.first_arg]), CLI_EXIT_USAGE;
    if (!a.photo || !a.table || !a.out || !a.have_seed)
        return cli_error(TFP, "missing %s", !a.photo ? "--tfp PHOTO.png" : !a.table ? "--calibration TABLE.csv"
                                            : !a.have_seed ? "--seed PX,PY[,N]" : "-o N.csv|N.pfm"),
               CLI_EXIT_USAGE;
    if (!pe_has_ext(a.out, ".csv") && !pe_has_ext(a.out, ".pfm"))
        return cli_error(TFP, "-o must end in .csv or .pfm, got '%s'", a.out), CLI_EXIT_USAGE;
    const char *inputs[2] = {a.photo, a.table};
    int rc = cli_check_output(TFP, a.out, inputs, 2);
    if (rc) return rc;
    double *orders = NULL, *tab = NULL;
    size_t n = 0;
    int linear = 0, W = 0, H = 0, bits = 0;
    float *img = NULL, *N = NULL;
    char msg[BIREF_MSG_SIZE];
    rc = read_columns4(TFP, a.table, "fringe_order,r,g,b", &orders, &tab, &n, &linear);
    if (!rc && pe_png_read_rgb(a.photo, &W, &H, &img, &bits, msg, sizeof msg) != BIREF_OK)
        rc = (cli_error(TFP, "%s", msg), CLI_EXIT_USAGE);
    if (!rc && !(N = malloc((size_t)W * H * sizeof *N))) rc = (cli_error(TFP, "out of memory"), CLI_EXIT_FAIL);
    if (!rc && biref_pe_tfp_demodulate(img, W, H, n, orders, tab, &a.o, N, NULL, msg, sizeof msg) != BIREF_OK)
        rc = (cli_error(TFP, "%s", msg), CLI_EXIT_USAGE);
    if (!rc) rc = tfp_report(&a, W, H, N);
    free(orders);
    free(tab);
    free(img);
    free(N);
    return rc;
}
