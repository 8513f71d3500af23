/* biref diff: per-pixel CIEDE2000 between two PNGs, a colour-coded map and statistics. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_files.h"
#include "cli_render.h"
#include "de_scale.h"
#include "commands.h"
#include "json_out.h"

static const char *const CMD = "diff";

typedef struct {
    const char *out;
    int json, no_legend;
} diff_args;

#define F(field) offsetof(diff_args, field)
static const cli_opt OPTS[] = {
    CLI_STRING("output", 'o', "FILE", F(out), "write the difference map (PNG)"),
    CLI_FLAG("no-legend", 0, F(no_legend), "write the map without the legend strip"),
    CLI_FLAG("json", 0, F(json),
             "{width, height, mean, p95, p99, max, over_1, over_4} on stdout\n"
             "(over_N: fraction of pixels with dE00 > N)"),
};
#undef F

const cli_command_spec CLI_DIFF = {
    "diff",
    "usage: biref diff A.png B.png [-o MAP.png] [--json]\n\n"
    "Decodes both images as sRGB, converts each pixel to XYZ (white E) and computes the\n"
    "CIEDE2000 colour difference dE00. Prints the mean, 95th percentile and maximum, and\n"
    "optionally writes a difference map coloured on a fixed scale (linear between stops):\n"
    "  " CLI_DE_SCALE_TEXT ",\n"
    "the scale of every dE00 map biref draws (biref figure fig9, aliasing), with a legend\n"
    "strip below the map (--no-legend: the map alone, pixel for pixel).\n\n"
    "Options:\n",
    OPTS,
    CLI_OPTS_COUNT(OPTS),
    "Both images must have the same size. Exit status 0 (whatever the difference), 1 on an\n"
    "I/O failure, 2 on bad usage or unreadable/mismatched images.\n",
    0,
    NULL,
    0,
    NULL,
};

int cmd_diff(int argc, char **argv)
{
    diff_args args = {NULL, 0, 0};
    cli_parsed parsed;
    int r = cli_opts_parse(&CLI_DIFF, &args, argc, argv, &parsed);
    if (r) return r > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    const char *out = args.out;
    const int json = args.json, legend = !args.no_legend, first_arg = parsed.first_arg;
    if (argc - first_arg < 2) return cli_error(CMD, "expected two images A.png B.png (see biref diff --help)"), CLI_EXIT_USAGE;
    if (argc - first_arg > 2) return cli_error(CMD, "unexpected argument '%s'", argv[first_arg + 2]), CLI_EXIT_USAGE;
    const char *pa = argv[first_arg], *pb = argv[first_arg + 1];
    cli_files files;
    cli_files_init(&files);
    cli_files_read(&files, "A", pa);
    cli_files_read(&files, "B", pb);
    cli_files_write(&files, "-o", "png", out);
    int rc_out = cli_files_check(CMD, &files);
    cli_files_free(&files);
    if (rc_out) return rc_out;

    char msg[600];
    int wa, ha, wb, hb;
    unsigned char *a = NULL, *b = NULL;
    biref_status s = biref_png_read_rgb8(pa, &wa, &ha, &a, msg, sizeof msg);
    if (!s) s = biref_png_read_rgb8(pb, &wb, &hb, &b, msg, sizeof msg);
    if (s) {
        free(a);
        return cli_error(CMD, "%s", msg), CLI_EXIT_USAGE;
    }
    if (wa != wb || ha != hb) {
        free(a);
        free(b);
        return cli_error(CMD, "image sizes differ: %s is %dx%d, %s is %dx%d", pa, wa, ha, pb, wb, hb), CLI_EXIT_USAGE;
    }
    const size_t n = (size_t)wa * ha;
    double *de = malloc(n * sizeof *de);
    unsigned char *map = out ? malloc(n * 3) : NULL;
    if (!de || (out && !map)) {
        free(a);
        free(b);
        free(de);
        free(map);
        return cli_error(CMD, "out of memory"), CLI_EXIT_FAIL;
    }
    double sum = 0, max = 0;
    size_t over1 = 0, over4 = 0;
    for (size_t i = 0; i < n; i++) {
        double xa[3], xb[3];
        biref_srgb8_to_xyz(a + 3 * i, xa);
        biref_srgb8_to_xyz(b + 3 * i, xb);
        /* Identical bytes: skip the Lab round trip (and its rounding) entirely. */
        double d = memcmp(a + 3 * i, b + 3 * i, 3) ? biref_delta_e00_xyz(xa, xb) : 0.0;
        if (!isfinite(d)) d = 0.0;
        de[i] = d;
        sum += d;
        if (d > max) max = d;
        over1 += d > 1.0;
        over4 += d > 4.0;
        if (map) cli_de_color(d, map + 3 * i);
    }
    free(a);
    free(b);
    int rc = CLI_EXIT_OK;
    if (map) {
        if (legend) {
            rc = cli_de_map_write(CMD, out, wa, ha, map, "dE00:");
        } else if (biref_png_write_rgb8(out, wa, ha, map, msg, sizeof msg) != BIREF_OK) {
            cli_error(CMD, "%s", msg);
            rc = CLI_EXIT_FAIL;
        }
        free(map);
    }
    double mean = sum / (double)n;
    /* 95th percentile: nearest rank on the sorted differences. */
    qsort(de, n, sizeof *de, cli_cmp_double);
    size_t rank = (size_t)ceil(0.95 * (double)n);
    double p95 = de[rank > 0 ? rank - 1 : 0];
    rank = (size_t)ceil(0.99 * (double)n);
    double p99 = de[rank > 0 ? rank - 1 : 0];
    free(de);
    if (rc) return rc;
    if (json) {
        cJSON *root = cJSON_CreateObject();
        cJSON_AddNumberToObject(root, "width", wa);
        cJSON_AddNumberToObject(root, "height", ha);
        cJSON_AddNumberToObject(root, "mean", mean);
        cJSON_AddNumberToObject(root, "p95", p95);
        cJSON_AddNumberToObject(root, "p99", p99);
        cJSON_AddNumberToObject(root, "max", max);
        cJSON_AddNumberToObject(root, "over_1", (double)over1 / (double)n);
        cJSON_AddNumberToObject(root, "over_4", (double)over4 / (double)n);
        if (out) cJSON_AddStringToObject(root, "map", out);
        return json_print_and_free(root) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
    }
    printf("dE00 over %dx%d pixels: mean %.3f, 95th percentile %.3f, max %.3f; > 1: %.2f %%, > 4: %.2f %%\n", wa, ha,
           mean, p95, max, 100.0 * (double)over1 / (double)n, 100.0 * (double)over4 / (double)n);
    if (out) printf("wrote %s\n", out);
    return CLI_EXIT_OK;
}
