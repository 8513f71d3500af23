/* biref photoelastic: full-field maps (PFM, CSV), float pictures and phase-stepped image sets
 * (docs/PHOTOELASTICITY.md, "Maps and float output", "Phase stepping"). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pe_image_io.h"
#include "photoelastic_ext.h"

static const char *const CMD = "photoelastic";

int pe_ext_owns_output(const pe_ext *e)
{
    return e->map >= 0 || e->pfm || e->phase_steps > 0;
}

static int write_map(const pe_ext *e, const pe_ext_ctx *c)
{
    const int W = c->io->width, H = c->io->height;
    const biref_pe_map_kind k = (biref_pe_map_kind)e->map;
    float *v = malloc((size_t)W * H * sizeof *v);
    if (!v) return cli_error(CMD, "out of memory for a %d x %d map", W, H), CLI_EXIT_FAIL;
    char msg[512];
    int rc = CLI_EXIT_OK;
    if (biref_pe_render_map(c->setup, c->field, k, c->lambda_N, W, H, c->io->threads, v, msg, sizeof msg) != BIREF_OK) {
        cli_error(CMD, "%s", msg);
        free(v);
        return CLI_EXIT_FAIL;
    }
    char name[64];
    snprintf(name, sizeof name, "%s%s%s", biref_pe_map_name(k), strcmp(biref_pe_map_unit(k), "1") ? "_" : "",
             strcmp(biref_pe_map_unit(k), "1") ? biref_pe_map_unit(k) : "");
    biref_status st = pe_has_ext(c->out, ".csv")
                          ? pe_csv_write_map(c->out, W, H, c->field->frame, name, v, msg, sizeof msg)
                          : pe_pfm_write(c->out, W, H, 1, v, msg, sizeof msg);
    if (st != BIREF_OK) {
        cli_error(CMD, "%s", msg);
        rc = CLI_EXIT_FAIL;
    } else {
        double lo = INFINITY, hi = -INFINITY;
        size_t nan = 0;
        for (size_t i = 0; i < (size_t)W * H; i++)
            if (isnan(v[i]))
                nan++;
            else
                lo = fmin(lo, v[i]), hi = fmax(hi, v[i]);
        if (c->root) {
            cJSON_AddStringToObject(c->root, "output", c->out);
            cJSON_AddStringToObject(c->root, "map", biref_pe_map_name(k));
            cJSON_AddStringToObject(c->root, "unit", biref_pe_map_unit(k));
            cJSON_AddNumberToObject(c->root, "width", W);
            cJSON_AddNumberToObject(c->root, "height", H);
            if (nan < (size_t)W * H) {
                cJSON_AddNumberToObject(c->root, "min", lo);
                cJSON_AddNumberToObject(c->root, "max", hi);
            }
            cJSON_AddNumberToObject(c->root, "no_material_pixels", (double)nan);
        } else {
            char range[96] = "no pixel has material";
            if (nan < (size_t)W * H) snprintf(range, sizeof range, "range %.6g .. %.6g", lo, hi);
            printf("wrote %s: %s map (%s%s), %d x %d px, %s, %zu pixels without material (NaN)\n", c->out,
                   biref_pe_map_name(k), biref_pe_map_unit(k),
                   k == BIREF_PE_MAP_FRINGE_ORDER ? (c->setup->light == BIREF_PE_MONO ? ", at the light's wavelength"
                                                                                      : ", at 550 nm")
                                                  : "",
                   W, H, range, nan);
        }
    }
    free(v);
    return rc;
}

/* The picture as floats: mono without tint as grey intensity, else linear sRGB. */
static int write_pfm_picture(const pe_ext_ctx *c)
{
    const int W = c->io->width, H = c->io->height;
    const size_t np = (size_t)W * H;
    float *xyz = malloc(np * 3 * sizeof *xyz), *px = malloc(np * 3 * sizeof *px);
    int rc = CLI_EXIT_OK;
    char msg[512];
    if (!xyz || !px) {
        rc = CLI_EXIT_FAIL;
        cli_error(CMD, "out of memory for a %d x %d picture", W, H);
        goto done;
    }
    char why[BIREF_MSG_SIZE];
    if (biref_pe_render(c->setup, c->sp, c->field, c->io, xyz, why, sizeof why) != BIREF_OK) {
        rc = CLI_EXIT_FAIL;
        cli_error(CMD, "%s", why);
        goto done;
    }
    const int mono = c->setup->light == BIREF_PE_MONO;
    const int grey = mono && c->tint[0] == 1.0 && c->tint[1] == 1.0 && c->tint[2] == 1.0;
    if (!mono)
        for (size_t i = 0; i < np * 3; i++) xyz[i] = (float)(xyz[i] * c->exposure);
    if (grey)
        for (size_t i = 0; i < np; i++) px[i] = xyz[3 * i + 1];
    else
        biref_xyz_image_to_linear_srgb(xyz, np, px);
    if (pe_pfm_write(c->out, W, H, grey ? 1 : 3, px, msg, sizeof msg) != BIREF_OK) {
        rc = CLI_EXIT_FAIL;
        cli_error(CMD, "%s", msg);
        goto done;
    }
    if (c->root) {
        cJSON_AddStringToObject(c->root, "output", c->out);
        cJSON_AddStringToObject(c->root, "format", grey ? "pfm grey intensity" : "pfm linear sRGB");
        cJSON_AddNumberToObject(c->root, "width", W);
        cJSON_AddNumberToObject(c->root, "height", H);
    } else {
        printf("wrote %s: %d x %d px float PFM (%s)\n", c->out, W, H, grey ? "grey intensity" : "linear sRGB");
    }
done:
    free(xyz);
    free(px);
    return rc;
}

/* FILE.ext -> FILE-k.ext */
static void step_name(char *buf, size_t n, const char *out, int k)
{
    const char *dot = strrchr(out, '.'), *slash = strrchr(out, '/');
    if (!dot || (slash && dot < slash)) dot = out + strlen(out);
    snprintf(buf, n, "%.*s-%d%s", (int)(dot - out), out, k, dot);
}

static int write_phase_steps(const pe_ext *e, const pe_ext_ctx *c)
{
    const int W = c->io->width, H = c->io->height, n = e->phase_steps;
    const size_t np = (size_t)W * H;
    const int png = pe_has_ext(c->out, ".png");
    biref_pe_step steps[6];
    biref_pe_phase_steps(n, steps);
    float *xyz = malloc(np * 3 * sizeof *xyz), *grey = malloc(np * sizeof *grey);
    if (!xyz || !grey) {
        free(xyz);
        free(grey);
        return cli_error(CMD, "out of memory for a %d x %d picture", W, H), CLI_EXIT_FAIL;
    }
    /* Raw intensities (unit input light): no tint, no exposure. */
    biref_pe_image_opts io = *c->io;
    io.tint[0] = io.tint[1] = io.tint[2] = 1.0;
    cJSON *arr = c->root ? cJSON_AddArrayToObject(c->root, "phase_steps") : NULL;
    int rc = CLI_EXIT_OK;
    for (int k = 0; k < n && rc == CLI_EXIT_OK; k++) {
        biref_pe_setup s = *c->setup;
        biref_pe_polariscope_stepped(steps[k].qwp_deg * M_PI / 180.0, steps[k].analyzer_deg * M_PI / 180.0, &s.pol);
        char path[4096], msg[512];
        step_name(path, sizeof path, c->out, k + 1);
        if (biref_pe_render(&s, c->sp, c->field, &io, xyz, msg, sizeof msg) != BIREF_OK) {
            cli_error(CMD, "%s", msg);
            rc = CLI_EXIT_FAIL;
            break;
        }
        for (size_t i = 0; i < np; i++) grey[i] = xyz[3 * i + 1];
        biref_status st = png ? pe_png16_write_gray(path, W, H, grey, msg, sizeof msg)
                              : pe_pfm_write(path, W, H, 1, grey, msg, sizeof msg);
        if (st != BIREF_OK) {
            cli_error(CMD, "%s", msg);
            rc = CLI_EXIT_FAIL;
            break;
        }
        const double *a = steps[k].stokes;
        if (arr) {
            cJSON *o = cJSON_CreateObject();
            cJSON_AddStringToObject(o, "file", path);
            cJSON_AddNumberToObject(o, "quarter_wave_deg", steps[k].qwp_deg);
            cJSON_AddNumberToObject(o, "analyzer_deg", steps[k].analyzer_deg);
            cJSON_AddItemToObject(o, "analyzer_stokes", cJSON_CreateDoubleArray(a, 4));
            cJSON_AddItemToArray(arr, o);
        } else {
            printf("wrote %s: quarter-wave plate %3.0f deg, analyzer %3.0f deg: I = Ib + Ia/2 (1 %s)\n", path,
                   steps[k].qwp_deg, steps[k].analyzer_deg,
                   a[3] > 0.5    ? "+ cos d"
                   : a[3] < -0.5 ? "- cos d"
                   : a[1] > 0.5  ? "- sin 2phi sin d"
                   : a[1] < -0.5 ? "+ sin 2phi sin d"
                   : a[2] > 0.5  ? "+ cos 2phi sin d"
                                 : "- cos 2phi sin d");
        }
    }
    if (c->root) {
        cJSON_AddNumberToObject(c->root, "width", W);
        cJSON_AddNumberToObject(c->root, "height", H);
        cJSON_AddStringToObject(c->root, "format", png ? "png 16-bit linear grey" : "pfm grey");
    }
    free(xyz);
    free(grey);
    return rc;
}

int pe_ext_write(const pe_ext *e, const pe_ext_ctx *c)
{
    pe_ext_json(e, c->root);
    if (e->map >= 0 && !pe_has_ext(c->out, ".pfm") && !pe_has_ext(c->out, ".csv"))
        return cli_error(CMD, "--map: -o must end in .pfm or .csv, got '%s'", c->out), CLI_EXIT_USAGE;
    if (e->pfm && !pe_has_ext(c->out, ".pfm"))
        return cli_error(CMD, "--format pfm: -o must end in .pfm, got '%s'", c->out), CLI_EXIT_USAGE;
    if (e->phase_steps && !pe_has_ext(c->out, ".pfm") && !pe_has_ext(c->out, ".png"))
        return cli_error(CMD, "--phase-steps: -o must end in .pfm or .png, got '%s'", c->out), CLI_EXIT_USAGE;
    if (e->map >= 0) return write_map(e, c);
    if (e->pfm) return write_pfm_picture(c);
    return write_phase_steps(e, c);
}
