/* biref photoelastic demodulate: isoclinic angle and unwrapped isochromatic phase from a
 * phase-stepped image set (docs/PHOTOELASTICITY.md, "Phase stepping"). */
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli_opts.h"
#include "json_out.h"
#include "pe_image_io.h"
#include "photoelastic_ext.h"

static const char *const CMD = "photoelastic demodulate";

enum { OPT_ZERO = 1, OPT_ORDER_AT, OPT_MINMOD, OPT_FORMAT };

/* The command line, parsed. */
typedef struct {
    const char *dir;
    int have_ref, csv, json, n;
    char **images;
    biref_pe_demod_opts o;
} demod_args;

static int handle(void *args, int code, const char *arg)
{
    demod_args *a = args;
    switch (code) {
    case OPT_MINMOD:
        if (cli_parse_double(CMD, "--min-modulation", arg, &a->o.min_modulation)) return -1;
        if (!(a->o.min_modulation >= 0 && a->o.min_modulation < 1))
            return cli_error(CMD, "--min-modulation: must be in [0, 1), got %g", a->o.min_modulation), -1;
        return 0;
    case OPT_FORMAT:
        if (!strcmp(arg, "pfm"))
            a->csv = 0;
        else if (!strcmp(arg, "csv"))
            a->csv = 1;
        else
            return cli_error(CMD, "--format: expected pfm or csv, got '%s'", arg), -1;
        return 0;
    default: { /* --zero-order PX,PY or --order-at PX,PY,N */
        const int zero = code == OPT_ZERO;
        double ref[3] = {0, 0, 0};
        if (a->have_ref) return cli_error(CMD, "give one of --zero-order and --order-at, once"), -1;
        if (cli_parse_list(CMD, zero ? "--zero-order" : "--order-at", arg, ref, zero ? 2 : 3)) return -1;
        a->o.ref_x = ref[0];
        a->o.ref_y = ref[1];
        a->o.ref_order = zero ? 0 : ref[2];
        a->have_ref = 1;
        return 0;
    }
    }
}

#define F(field) offsetof(demod_args, field)
static const cli_opt OPTS[] = {
    CLI_TEXT("  IMAGE                .pfm (float) or .png (read as linear grey by libpng)\n"),
    CLI_STRING("output", 'o', "DIR", F(dir),
               "directory for isoclinic (deg, direction of s1), phase-wrapped (rad,\n"
               "[0, 2 pi)), fringe-order, modulation (Ia) and background (Ib) maps;\n"
               "NaN where masked or not connected to the reference"),
    CLI_CUSTOM("zero-order", "PX,PY", OPT_ZERO,
               "pixel (column, row from the top-left, 0-based) of fringe order 0,\n"
               "e.g. the empty field of the polariscope next to the part"),
    CLI_CUSTOM("order-at", "PX,PY,N", OPT_ORDER_AT, "pixel of known fringe order N instead (|N| <= 1e5)"),
    CLI_CUSTOM("min-modulation", "F", OPT_MINMOD, "mask pixels whose Ia is below F times the largest (default 0.05)"),
    CLI_CUSTOM("format", "pfm|csv", OPT_FORMAT, "map files (default pfm; csv: col,row,value)"),
    CLI_FLAG("json", 0, F(json), "machine-readable report"),
};
#undef F

static const char *const EXCLUSIVE[] = {"zero-order order-at", NULL};

const cli_command_spec CLI_PHOTOELASTIC_DEMODULATE = {
    "photoelastic demodulate",
    "usage: biref photoelastic demodulate IMAGE1 ... IMAGEn -o DIR (--zero-order PX,PY | --order-at PX,PY,N)\n"
    "                                     [OPTIONS]\n\n"
    "Recovers the isoclinic angle and the isochromatic phase from the n = 4 or 6 images of a\n"
    "phase-stepped circular polariscope, in the order 'biref photoelastic --phase-steps' writes\n"
    "them (quarter-wave plate / analyzer at 0/45, 0/135, 0/0, 45/45, 90/90, 135/135 deg; input\n"
    "light circular, S3 = +1), and unwraps the phase from a point of known fringe order:\n"
    "  I1 = Ib + Ia/2 (1 - cos d)   I2 = Ib + Ia/2 (1 + cos d)   I3 = Ib + Ia/2 (1 - sin 2phi sin d)\n"
    "  I4 = Ib + Ia/2 (1 + cos 2phi sin d)   I5 = ... (1 + sin 2phi sin d)   I6 = ... (1 - cos 2phi sin d)\n\n",
    OPTS,
    CLI_OPTS_COUNT(OPTS),
    "The set leaves the sign of the phase open (s1 and s2 swapped); the sign with the fewest\n"
    "negative fringe orders is taken. The unwrapping keeps the isoclinic continuous and fails\n"
    "where fringes are closer than about two pixels (load points) and at isotropic points.\n\n"
    "Exit status: 0 success, 1 runtime failure, 2 bad usage or input.\n\n"
    "Example:\n"
    "  biref photoelastic --preset disk --light mono --phase-steps 6 -o steps/disk.pfm\n"
    "  biref photoelastic demodulate steps/disk-{1,2,3,4,5,6}.pfm --zero-order 2,2 -o maps\n",
    0,
    handle,
    0,
    EXCLUSIVE,
};

static const char *const MAP_NAMES[5] = {"isoclinic", "phase-wrapped", "fringe-order", "modulation", "background"};

/* Returns 0, 1 after --help, -1 after one error line. */
static int parse(int argc, char **argv, demod_args *a)
{
    memset(a, 0, sizeof *a);
    a->o.min_modulation = 0.05;
    cli_parsed p;
    int r = cli_opts_parse(&CLI_PHOTOELASTIC_DEMODULATE, a, argc, argv, &p);
    if (r) return r;
    a->n = p.n_args;
    a->images = argv + p.first_arg;
    if (a->n != 4 && a->n != 6)
        return cli_error(CMD, "expected 4 or 6 images (in the order of --phase-steps), got %d", a->n), -1;
    if (!a->dir) return cli_error(CMD, "missing -o DIR"), -1;
    if (!a->have_ref) return cli_error(CMD, "missing --zero-order PX,PY or --order-at PX,PY,N"), -1;
    return 0;
}

/* Reads the n images, which must have one size. Returns a CLI exit code. */
static int read_images(const demod_args *a, float *img[6], int *W, int *H)
{
    char msg[512];
    for (int k = 0; k < a->n; k++) {
        int w, h;
        if (pe_image_read_gray(a->images[k], &w, &h, &img[k], msg, sizeof msg) != BIREF_OK)
            return cli_error(CMD, "%s", msg), CLI_EXIT_USAGE;
        if (k == 0) {
            *W = w;
            *H = h;
        } else if (w != *W || h != *H) {
            return cli_error(CMD, "%s: %d x %d px, but %s is %d x %d", a->images[k], w, h, a->images[0], *W, *H),
                   CLI_EXIT_USAGE;
        }
    }
    return CLI_EXIT_OK;
}

/* Writes the five maps into the directory, listing them in files (JSON) if not NULL. */
static int write_maps(const demod_args *a, int W, int H, float *const maps[5], cJSON *files)
{
    char msg[512];
    if (mkdir(a->dir, 0755) != 0 && errno != EEXIST)
        return cli_error(CMD, "%s: cannot create the directory: %s", a->dir, strerror(errno)), CLI_EXIT_FAIL;
    for (int m = 0; m < 5; m++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s.%s", a->dir, MAP_NAMES[m], a->csv ? "csv" : "pfm");
        biref_status st = a->csv ? pe_csv_write_map(path, W, H, NULL, MAP_NAMES[m], maps[m], msg, sizeof msg)
                                 : pe_pfm_write(path, W, H, 1, maps[m], msg, sizeof msg);
        if (st != BIREF_OK) return cli_error(CMD, "%s", msg), CLI_EXIT_FAIL;
        if (files) cJSON_AddItemToArray(files, cJSON_CreateString(path));
    }
    return CLI_EXIT_OK;
}

/* Demodulates, writes the maps and reports. Returns a CLI exit code. */
static int demodulate(const demod_args *a, float *const img[6], int W, int H, float *const maps[5])
{
    char msg[512];
    const biref_pe_demod_maps dm = {maps[0], maps[1], maps[2], maps[3], maps[4]};
    biref_status st = biref_pe_demodulate(a->n, (const float *const *)img, W, H, &a->o, &dm, msg, sizeof msg);
    if (st != BIREF_OK) return cli_error(CMD, "%s", msg), st == BIREF_ERR_NOMEM ? CLI_EXIT_FAIL : CLI_EXIT_USAGE;
    cJSON *root = a->json ? cJSON_CreateObject() : NULL, *files = root ? cJSON_AddArrayToObject(root, "maps") : NULL;
    int rc = write_maps(a, W, H, maps, files);
    if (rc) {
        cJSON_Delete(root);
        return rc;
    }
    size_t valid = 0;
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < (size_t)W * H; i++)
        if (!isnan(maps[2][i])) valid++, lo = fmin(lo, maps[2][i]), hi = fmax(hi, maps[2][i]);
    if (!root) {
        printf("wrote %s/{isoclinic,phase-wrapped,fringe-order,modulation,background}.%s: %d x %d px, %zu pixels "
               "unwrapped, fringe order %.4g .. %.4g\n",
               a->dir, a->csv ? "csv" : "pfm", W, H, valid, lo, hi);
        return CLI_EXIT_OK;
    }
    cJSON_AddNumberToObject(root, "steps", a->n);
    cJSON_AddNumberToObject(root, "width", W);
    cJSON_AddNumberToObject(root, "height", H);
    cJSON_AddNumberToObject(root, "unwrapped_pixels", (double)valid);
    cJSON_AddNumberToObject(root, "fringe_order_min", lo);
    cJSON_AddNumberToObject(root, "fringe_order_max", hi);
    return json_print_and_free(root) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

int cmd_photoelastic_demodulate(int argc, char **argv)
{
    demod_args a;
    int r = parse(argc, argv, &a);
    if (r) return r > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    cli_files files;
    cli_files_init(&files);
    for (int k = 0; k < a.n; k++) cli_files_read(&files, "IMAGE", a.images[k]);
    for (int m = 0; m < 5; m++) {
        char name[64];
        snprintf(name, sizeof name, "%s.%s", MAP_NAMES[m], a.csv ? "csv" : "pfm");
        cli_files_write_in_dir(&files, "-o", a.csv ? "csv" : "pfm", a.dir, name);
    }
    int rc = cli_files_check(CMD, &files);
    cli_files_free(&files);
    if (rc) return rc;
    float *img[6] = {0}, *maps[5] = {0};
    int W = 0, H = 0;
    rc = read_images(&a, img, &W, &H);
    for (int m = 0; m < 5 && !rc; m++)
        if (!(maps[m] = malloc((size_t)W * H * sizeof(float)))) rc = (cli_error(CMD, "out of memory"), CLI_EXIT_FAIL);
    if (!rc) rc = demodulate(&a, img, W, H, maps);
    for (int k = 0; k < 6; k++) free(img[k]);
    for (int m = 0; m < 5; m++) free(maps[m]);
    return rc;
}
