/* biref photoelastic demodulate: isoclinic angle and unwrapped isochromatic phase from a
 * phase-stepped image set (docs/PHOTOELASTICITY.md, "Phase stepping"). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "json_out.h"
#include "pe_image_io.h"
#include "photoelastic_ext.h"

static const char *const CMD = "photoelastic demodulate";

static void help(void)
{
    printf("usage: biref photoelastic demodulate IMAGE1 ... IMAGEn -o DIR (--zero-order PX,PY | --order-at PX,PY,N)\n"
           "                                     [OPTIONS]\n\n"
           "Recovers the isoclinic angle and the isochromatic phase from the n = 4 or 6 images of a\n"
           "phase-stepped circular polariscope, in the order 'biref photoelastic --phase-steps' writes\n"
           "them (quarter-wave plate / analyzer at 0/45, 0/135, 0/0, 45/45, 90/90, 135/135 deg; input\n"
           "light circular, S3 = +1), and unwraps the phase from a point of known fringe order:\n"
           "  I1 = Ib + Ia/2 (1 - cos d)   I2 = Ib + Ia/2 (1 + cos d)   I3 = Ib + Ia/2 (1 - sin 2phi sin d)\n"
           "  I4 = Ib + Ia/2 (1 + cos 2phi sin d)   I5 = ... (1 + sin 2phi sin d)   I6 = ... (1 - cos 2phi sin d)\n\n"
           "  IMAGE                .pfm (float) or .png (read as linear grey by libpng)\n"
           "  -o, --output DIR     directory for isoclinic (deg, direction of s1), phase-wrapped (rad,\n"
           "                       [0, 2 pi)), fringe-order, modulation (Ia) and background (Ib) maps;\n"
           "                       NaN where masked or not connected to the reference\n"
           "  --zero-order PX,PY   pixel (column, row from the top-left, 0-based) of fringe order 0,\n"
           "                       e.g. the empty field of the polariscope next to the part\n"
           "  --order-at PX,PY,N   pixel of known fringe order N instead\n"
           "  --min-modulation F   mask pixels whose Ia is below F times the largest (default 0.05)\n"
           "  --format pfm|csv     map files (default pfm; csv: col,row,value)\n"
           "  --json               machine-readable report\n"
           "  -h, --help           this help\n\n"
           "The set leaves the sign of the phase open (s1 and s2 swapped); the sign with the fewest\n"
           "negative fringe orders is taken. The unwrapping keeps the isoclinic continuous and fails\n"
           "where fringes are closer than about two pixels (load points) and at isotropic points.\n\n"
           "Exit status: 0 success, 1 runtime failure, 2 bad usage or input.\n\n"
           "Example:\n"
           "  biref photoelastic --preset disk --light mono --phase-steps 6 -o steps/disk.pfm\n"
           "  biref photoelastic demodulate steps/disk-{1,2,3,4,5,6}.pfm --zero-order 2,2 -o maps\n");
}

enum { OPT_ZERO = 3200, OPT_ORDER_AT, OPT_MINMOD, OPT_FORMAT, OPT_JSON_D };

int cmd_photoelastic_demodulate(int argc, char **argv)
{
    static const struct option longopts[] = {{"output", required_argument, 0, 'o'},
                                             {"zero-order", required_argument, 0, OPT_ZERO},
                                             {"order-at", required_argument, 0, OPT_ORDER_AT},
                                             {"min-modulation", required_argument, 0, OPT_MINMOD},
                                             {"format", required_argument, 0, OPT_FORMAT},
                                             {"json", no_argument, 0, OPT_JSON_D},
                                             {"help", no_argument, 0, 'h'},
                                             {0, 0, 0, 0}};
    const char *dir = NULL;
    int have_ref = 0, csv = 0, json = 0;
    double ref[3] = {0, 0, 0};
    biref_pe_demod_opts o = {0, 0, 0, 0.05};
    opterr = 0;
    optind = 1;
    int c;
    while ((c = getopt_long(argc, argv, ":ho:", longopts, NULL)) != -1) {
        switch (c) {
        case 'h': help(); return CLI_EXIT_OK;
        case 'o': dir = optarg; break;
        case OPT_ZERO:
        case OPT_ORDER_AT:
            if (have_ref) return cli_error(CMD, "give one of --zero-order and --order-at, once"), CLI_EXIT_USAGE;
            if (cli_parse_list(CMD, c == OPT_ZERO ? "--zero-order" : "--order-at", optarg, ref, c == OPT_ZERO ? 2 : 3))
                return CLI_EXIT_USAGE;
            if (c == OPT_ZERO) ref[2] = 0;
            have_ref = 1;
            break;
        case OPT_MINMOD:
            if (cli_parse_double(CMD, "--min-modulation", optarg, &o.min_modulation)) return CLI_EXIT_USAGE;
            if (!(o.min_modulation >= 0 && o.min_modulation < 1))
                return cli_error(CMD, "--min-modulation: must be in [0, 1), got %g", o.min_modulation), CLI_EXIT_USAGE;
            break;
        case OPT_FORMAT:
            if (!strcmp(optarg, "pfm"))
                csv = 0;
            else if (!strcmp(optarg, "csv"))
                csv = 1;
            else
                return cli_error(CMD, "--format: expected pfm or csv, got '%s'", optarg), CLI_EXIT_USAGE;
            break;
        case OPT_JSON_D: json = 1; break;
        default: cli_getopt_error(CMD, c, argv); return CLI_EXIT_USAGE;
        }
    }
    const int n = argc - optind;
    if (n != 4 && n != 6)
        return cli_error(CMD, "expected 4 or 6 images (in the order of --phase-steps), got %d", n), CLI_EXIT_USAGE;
    if (!dir) return cli_error(CMD, "missing -o DIR"), CLI_EXIT_USAGE;
    if (!have_ref) return cli_error(CMD, "missing --zero-order PX,PY or --order-at PX,PY,N"), CLI_EXIT_USAGE;
    o.ref_x = ref[0];
    o.ref_y = ref[1];
    o.ref_order = ref[2];

    float *img[6] = {0};
    int W = 0, H = 0, rc = CLI_EXIT_OK;
    char msg[512];
    float *maps[5] = {0};
    static const char *const names[5] = {"isoclinic", "phase-wrapped", "fringe-order", "modulation", "background"};
    for (int k = 0; k < n; k++) {
        int w, h;
        if (pe_image_read_gray(argv[optind + k], &w, &h, &img[k], msg, sizeof msg) != BIREF_OK) {
            cli_error(CMD, "%s", msg);
            rc = CLI_EXIT_USAGE;
            goto done;
        }
        if (k == 0) {
            W = w;
            H = h;
        } else if (w != W || h != H) {
            cli_error(CMD, "%s: %d x %d px, but %s is %d x %d", argv[optind + k], w, h, argv[optind], W, H);
            rc = CLI_EXIT_USAGE;
            goto done;
        }
    }
    for (int m = 0; m < 5; m++)
        if (!(maps[m] = malloc((size_t)W * H * sizeof(float)))) {
            cli_error(CMD, "out of memory");
            rc = CLI_EXIT_FAIL;
            goto done;
        }
    const biref_pe_demod_maps dm = {maps[0], maps[1], maps[2], maps[3], maps[4]};
    biref_status st = biref_pe_demodulate(n, (const float *const *)img, W, H, &o, &dm, msg, sizeof msg);
    if (st != BIREF_OK) {
        cli_error(CMD, "%s", msg);
        rc = st == BIREF_ERR_NOMEM ? CLI_EXIT_FAIL : CLI_EXIT_USAGE;
        goto done;
    }
    if (mkdir(dir, 0755) != 0 && errno != EEXIST) {
        cli_error(CMD, "%s: cannot create the directory: %s", dir, strerror(errno));
        rc = CLI_EXIT_FAIL;
        goto done;
    }
    cJSON *root = json ? cJSON_CreateObject() : NULL, *files = root ? cJSON_AddArrayToObject(root, "maps") : NULL;
    for (int m = 0; m < 5 && rc == CLI_EXIT_OK; m++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s.%s", dir, names[m], csv ? "csv" : "pfm");
        st = csv ? pe_csv_write_map(path, W, H, NULL, names[m], maps[m], msg, sizeof msg)
                 : pe_pfm_write(path, W, H, 1, maps[m], msg, sizeof msg);
        if (st != BIREF_OK) {
            cli_error(CMD, "%s", msg);
            rc = CLI_EXIT_FAIL;
        } else if (files) {
            cJSON_AddItemToArray(files, cJSON_CreateString(path));
        }
    }
    if (rc == CLI_EXIT_OK) {
        size_t valid = 0;
        double lo = INFINITY, hi = -INFINITY;
        for (size_t i = 0; i < (size_t)W * H; i++)
            if (!isnan(maps[2][i])) valid++, lo = fmin(lo, maps[2][i]), hi = fmax(hi, maps[2][i]);
        if (root) {
            cJSON_AddNumberToObject(root, "steps", n);
            cJSON_AddNumberToObject(root, "width", W);
            cJSON_AddNumberToObject(root, "height", H);
            cJSON_AddNumberToObject(root, "unwrapped_pixels", (double)valid);
            cJSON_AddNumberToObject(root, "fringe_order_min", lo);
            cJSON_AddNumberToObject(root, "fringe_order_max", hi);
            if (json_print_and_free(root)) rc = CLI_EXIT_FAIL;
            root = NULL;
        } else {
            printf("wrote %s/{isoclinic,phase-wrapped,fringe-order,modulation,background}.%s: %d x %d px, %zu pixels "
                   "unwrapped, fringe order %.4g .. %.4g\n",
                   dir, csv ? "csv" : "pfm", W, H, valid, lo, hi);
        }
    }
    cJSON_Delete(root);
done:
    for (int k = 0; k < 6; k++) free(img[k]);
    for (int m = 0; m < 5; m++) free(maps[m]);
    return rc;
}
