/* biref spectrum --stack FILE: the colours of a stack of layers (docs/STACKS.md §2), by the path
 * expansion (default), numeric or ground-truth integration, under the light of the command line. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli_common.h"
#include "json_out.h"
#include "spectrum_stack.h"

static const char *const CMD = "spectrum";
static const char *const SP[2] = {"s", "p"};

static int print_json(const spectrum_stack_args *a, const biref_stack *stack, const biref_stack_state *st,
                      const biref_spectrum *spec, const double xyz[2][3], const biref_stack_spectrum_info *info)
{
    cJSON *root = json_spectrum_head(a->opts.method, info->samples, &a->cfg);
    cJSON *in = cJSON_AddObjectToObject(root, "input");
    cJSON_AddStringToObject(in, "stack", a->file);
    cJSON_AddNumberToObject(in, "layers", stack->n_layers);
    cJSON_AddNumberToObject(in, "theta_deg", a->theta_deg);
    cJSON_AddNumberToObject(in, "eta_i", stack->eta_i);
    cJSON_AddBoolToObject(root, "total_reflection", st->evanescent > 0);
    if (a->opts.method == BIREF_METHOD_EXPANSION) {
        cJSON *ex = cJSON_AddObjectToObject(root, "expansion");
        cJSON_AddNumberToObject(ex, "tolerance", a->opts.tolerance);
        cJSON_AddBoolToObject(ex, "fallback", info->fallback);
        cJSON_AddStringToObject(ex, "reason", info->reason);
        if (isfinite(info->bound))
            cJSON_AddNumberToObject(ex, "bound", info->bound);
        else
            cJSON_AddNullToObject(ex, "bound");
        cJSON_AddNumberToObject(ex, "legs", info->legs);
        cJSON *g = cJSON_AddObjectToObject(ex, "groups");
        cJSON_AddNumberToObject(g, "T", info->groups[0]);
        cJSON_AddNumberToObject(g, "R", info->groups[1]);
    }
    cJSON_AddItemToObject(root, "T", json_sp_xyz_pairs(spec->T));
    cJSON_AddItemToObject(root, "R", json_sp_xyz_pairs(spec->R));
    cJSON *mx = cJSON_AddObjectToObject(root, "mixed");
    cJSON *pol = cJSON_AddObjectToObject(mx, "polarization");
    cJSON_AddStringToObject(pol, "state", a->pol_name);
    cJSON_AddItemToObject(pol, "stokes", cJSON_CreateDoubleArray(a->stokes, 4));
    cJSON_AddStringToObject(mx, "analyzer", a->an_name);
    double rgb[2][3];
    biref_xyz_to_srgb(xyz[0], rgb[0]);
    biref_xyz_to_srgb(xyz[1], rgb[1]);
    cJSON_AddItemToObject(mx, "T_xyz", json_vec3(xyz[0]));
    cJSON_AddItemToObject(mx, "R_xyz", json_vec3(xyz[1]));
    cJSON_AddItemToObject(mx, "T_srgb", json_vec3(rgb[0]));
    cJSON_AddItemToObject(mx, "R_srgb", json_vec3(rgb[1]));
    cJSON_AddStringToObject(mx, "srgb_note", "encoded sRGB (IEC 61966-2-1), white E -> (1,1,1), not clamped");
    return json_print_and_free(root) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

static void print_text(const spectrum_stack_args *a, const biref_stack *stack, const biref_spectrum *spec,
                       const double xyz[2][3], const biref_stack_spectrum_info *info)
{
    printf("stack: %s, %d layer%s, eta_i %.4g, theta %.4g deg\n", a->file, stack->n_layers,
           stack->n_layers == 1 ? "" : "s", stack->eta_i, a->theta_deg);
    printf("method %s", biref_method_name(a->opts.method));
    if (a->opts.method == BIREF_METHOD_EXPANSION && !info->fallback)
        printf(" (%d + %d path groups, %d legs, bound %.2g)", info->groups[0], info->groups[1], info->legs,
               info->bound);
    else if (info->fallback)
        printf(" -> adaptive numeric, %d samples (%s)", info->samples, info->reason);
    else
        printf(" (%d samples)", info->samples);
    printf(", cmf %s, band %g-%g nm\n\n", biref_cmf_kind_name(a->cfg.cmf), a->cfg.lambda_min_nm, a->cfg.lambda_max_nm);
    printf("Band-normalised XYZ (flat spectrum = 1,1,1), input -> output:\n");
    printf("  %-8s %-30s %-30s\n", "", "transmission X Y Z", "reflection X Y Z");
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++) {
            char t[64], r[64];
            snprintf(t, sizeof t, "%.6f %.6f %.6f", spec->T[i][o][0], spec->T[i][o][1], spec->T[i][o][2]);
            snprintf(r, sizeof r, "%.6f %.6f %.6f", spec->R[i][o][0], spec->R[i][o][1], spec->R[i][o][2]);
            printf("  %s -> %s   %-30s %-30s\n", SP[i], SP[o], t, r);
        }
    printf("\nMixed: polarization %s, analyzer %s\n", a->pol_name, a->an_name);
    const char *lbl[2] = {"T", "R"};
    for (int k = 0; k < 2; k++) {
        double rgb[3];
        biref_xyz_to_srgb(xyz[k], rgb);
        printf("  %s  XYZ %.6f %.6f %.6f   sRGB %.4f %.4f %.4f\n", lbl[k], xyz[k][0], xyz[k][1], xyz[k][2], rgb[0],
               rgb[1], rgb[2]);
    }
    printf("  (sRGB encoded, unclamped)\n");
}

int spectrum_stack_run(const spectrum_stack_args *a)
{
    char msg[BIREF_MSG_SIZE];
    biref_stack stack;
    biref_status s = biref_stack_load(a->file, &stack, msg, sizeof msg);
    if (s != BIREF_OK)
        return cli_error(CMD, "--stack %s: %s", a->file, msg), s == BIREF_ERR_IO ? CLI_EXIT_FAIL : CLI_EXIT_USAGE;
    biref_stack_state st;
    s = biref_stack_prepare(&stack, a->theta_deg * M_PI / 180.0, &st);
    if (s != BIREF_OK) return cli_error(CMD, "%s", biref_status_string(s)), CLI_EXIT_FAIL;
    biref_spectral *sp = NULL;
    s = biref_spectral_create(&a->cfg, &sp, msg, sizeof msg);
    if (s == BIREF_ERR_INVALID) return cli_error(CMD, "--range-nm: %s", msg), CLI_EXIT_USAGE;
    if (s != BIREF_OK) return cli_error(CMD, "spectral context: %s", msg), CLI_EXIT_FAIL;
    biref_spectrum spec;
    double xyz[2][3];
    biref_stack_spectrum_info info;
    s = biref_stack_spectrum(sp, &st, &a->opts, &a->light, &spec, xyz[0], xyz[1], &info, msg, sizeof msg);
    biref_spectral_destroy(sp);
    if (s != BIREF_OK) return cli_error(CMD, "%s", msg), s == BIREF_ERR_INVALID ? CLI_EXIT_USAGE : CLI_EXIT_FAIL;
    if (a->json) return print_json(a, &stack, &st, &spec, (const double(*)[3])xyz, &info);
    print_text(a, &stack, &spec, (const double(*)[3])xyz, &info);
    return CLI_EXIT_OK;
}
