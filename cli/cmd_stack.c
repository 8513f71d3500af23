/* biref stack: Jones matrices and power fractions of a stack of layers (a stack file) at one
 * (theta, lambda); the fields of biref slab --json. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "json_out.h"

static const char *const CMD = "stack";
static const char *const SP[2] = {"s", "p"};

enum { OPT_METHOD = 1 };

typedef struct {
    double theta_deg, lambda;
    int json, tmm;
} stack_args;

static int handle(void *args, int code, const char *arg)
{
    stack_args *a = args;
    (void)code;
    if (!strcmp(arg, "exact"))
        a->tmm = 0;
    else if (!strcmp(arg, "tmm"))
        a->tmm = 1;
    else
        return cli_error(CMD, "--method: expected exact or tmm, got '%s'", arg), -1;
    return 0;
}

static const cli_opt OPTS[] = {
    CLI_DOUBLE("theta-deg", "A", offsetof(stack_args, theta_deg), 0, 0,
               "angle of incidence in degrees, 0 <= A < 90 (default 0)"),
    CLI_DOUBLE("lambda-nm", "L", offsetof(stack_args, lambda), 0, 0, "vacuum wavelength in nm (default 550)"),
    CLI_CUSTOM("method", "M", OPT_METHOD,
               "exact (default; all orders in every layer, docs/STACKS.md)\n"
               "or tmm (product of the layers' 4x4 transfer matrices)"),
    CLI_FLAG("json", 0, offsetof(stack_args, json), "machine-readable output"),
};

const cli_command_spec CLI_STACK = {
    "stack",
    "usage: biref stack FILE [OPTIONS]\n\n"
    "Transmission and reflection of a plane wave by a stack of layers (a stack file,\n"
    "docs/STACKS.md) at one wavelength: 2x2 Jones matrices (input s/p -> output s/p) and\n"
    "power fractions, as biref slab prints them.\n\n"
    "Options:\n",
    OPTS,
    CLI_OPTS_COUNT(OPTS),
    "Example:\n  biref stack examples/stacks/solc_folded.json --theta-deg 0 --lambda-nm 550 --json\n",
    0,
    handle,
    0,
    NULL,
};

static cJSON *layers_json(const biref_stack *s)
{
    cJSON *arr = cJSON_CreateArray();
    for (int i = 0; i < s->n_layers; i++) {
        const biref_layer *l = &s->layers[i];
        cJSON *o = cJSON_CreateObject();
        if (l->material) {
            biref_material_info info;
            biref_material_get_info(l->material, &info);
            cJSON_AddStringToObject(o, "material", info.name);
            if (!l->isotropic) cJSON_AddItemToObject(o, "axis", json_vec3(l->axis));
        } else if (l->isotropic) {
            cJSON_AddNumberToObject(o, "eta", l->eta_o);
        } else {
            cJSON_AddNumberToObject(o, "eta_o", l->eta_o);
            cJSON_AddNumberToObject(o, "eta_e", l->eta_e);
            cJSON_AddItemToObject(o, "axis", json_vec3(l->axis));
        }
        cJSON_AddNumberToObject(o, "thickness_nm", l->thickness_nm);
        cJSON_AddItemToArray(arr, o);
    }
    return arr;
}

static int print_json(const char *file, const biref_stack *s, const stack_args *a, const biref_stack_state *st,
                      const biref_jones *T, const biref_jones *R, double PT[2][2], double PR[2][2])
{
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "method", a->tmm ? "tmm" : "exact");
    cJSON *in = cJSON_AddObjectToObject(root, "input");
    cJSON_AddStringToObject(in, "file", file);
    cJSON_AddNumberToObject(in, "eta_i", s->eta_i);
    cJSON_AddNumberToObject(in, "theta_deg", a->theta_deg);
    cJSON_AddNumberToObject(in, "lambda_nm", a->lambda);
    cJSON_AddItemToObject(in, "layers", layers_json(s));
    cJSON_AddItemToObject(root, "T", json_sp_matrix(PT));
    cJSON_AddItemToObject(root, "R", json_sp_matrix(PR));
    cJSON_AddItemToObject(root, "jones_T", json_sp_cmatrix(T->m));
    cJSON_AddItemToObject(root, "jones_R", json_sp_cmatrix(R->m));
    cJSON *en = cJSON_AddObjectToObject(root, "energy");
    for (int i = 0; i < 2; i++) cJSON_AddNumberToObject(en, SP[i], PT[i][0] + PT[i][1] + PR[i][0] + PR[i][1]);
    cJSON_AddNumberToObject(root, "K", st->K);
    cJSON *tr = cJSON_AddObjectToObject(root, "total_reflection");
    cJSON_AddBoolToObject(tr, "any", st->evanescent > 0);
    cJSON_AddNumberToObject(tr, "layers", st->evanescent);
    return json_print_and_free(root) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
}

int cmd_stack(int argc, char **argv)
{
    stack_args a = {0.0, 550.0, 0, 0};
    cli_parsed p;
    int r = cli_opts_parse(&CLI_STACK, &a, argc, argv, &p);
    if (r) return r > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    if (p.n_args == 0) return cli_error(CMD, "missing the stack file (biref stack FILE)"), CLI_EXIT_USAGE;
    if (p.n_args > 1) return cli_error(CMD, "unexpected argument '%s'", argv[p.first_arg + 1]), CLI_EXIT_USAGE;
    const char *file = argv[p.first_arg];
    char msg[BIREF_MSG_SIZE];
    const double theta = a.theta_deg * M_PI / 180.0;
    if (biref_theta_check(theta, msg, sizeof msg) != BIREF_OK)
        return cli_error(CMD, "--theta-deg: %s", msg), CLI_EXIT_USAGE;
    if (!(a.lambda > 0)) return cli_error(CMD, "--lambda-nm: must be positive, got %g", a.lambda), CLI_EXIT_USAGE;
    biref_stack stack;
    biref_status s = biref_stack_load(file, &stack, msg, sizeof msg);
    if (s != BIREF_OK) return cli_error(CMD, "%s: %s", file, msg), s == BIREF_ERR_IO ? CLI_EXIT_FAIL : CLI_EXIT_USAGE;

    biref_stack_state st;
    s = biref_stack_prepare_at(&stack, theta, a.lambda, &st);
    if (s == BIREF_ERR_INVALID && biref_stack_dispersive(&stack)) {
        for (int i = 0; i < stack.n_layers; i++)
            if (stack.layers[i].material &&
                biref_material_check_band(stack.layers[i].material, a.lambda, a.lambda, msg, sizeof msg) != BIREF_OK)
                return cli_error(CMD, "%s: layers[%d]: %s", file, i, msg), CLI_EXIT_USAGE;
    }
    if (s != BIREF_OK) return cli_error(CMD, "%s", biref_status_string(s)), CLI_EXIT_FAIL;
    biref_jones T, R;
    if (a.tmm) {
        s = biref_stack_jones_tmm(&stack, theta, a.lambda, &T, &R);
        if (s != BIREF_OK) return cli_error(CMD, "tmm: %s", biref_status_string(s)), CLI_EXIT_FAIL;
    } else {
        biref_stack_jones_at(&st, a.lambda, &T, &R);
    }
    double PT[2][2], PR[2][2];
    biref_jones_intensity(&T, PT);
    biref_jones_intensity(&R, PR);
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            if (!isfinite(PT[i][j]) || !isfinite(PR[i][j]))
                return cli_error(CMD, "numerical failure (non-finite result)"), CLI_EXIT_FAIL;
    if (a.json) return print_json(file, &stack, &a, &st, &T, &R, PT, PR);

    printf("stack: %s, %d layer%s, eta_i %.4g\n", file, stack.n_layers, stack.n_layers == 1 ? "" : "s", stack.eta_i);
    printf("theta %.4g deg, lambda %.6g nm, method %s, K %.6f%s\n\n", a.theta_deg, a.lambda, a.tmm ? "tmm" : "exact",
           st.K, st.evanescent ? "  (total reflection in some layer)" : "");
    cli_print_jones_table("Transmission: power fraction (Jones amplitude)", &T, PT);
    cli_print_jones_table("Reflection:   power fraction (Jones amplitude)", &R, PR);
    printf("\nEnergy check T+R: s %.12f, p %.12f\n", PT[0][0] + PT[0][1] + PR[0][0] + PR[0][1],
           PT[1][0] + PT[1][1] + PR[1][0] + PR[1][1]);
    return CLI_EXIT_OK;
}
