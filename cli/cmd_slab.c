/* biref slab: Jones matrices and power fractions of one slab at one (theta, lambda). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "json_out.h"

static const char *const CMD = "slab";

enum { OPT_LAMBDA = OPT_SLAB_LAST + 1, OPT_METHOD };

/* The command line, parsed. */
typedef struct {
    cli_slab_opts so;
    double lambda;
    int json, tmm;
} slab_args;

static int handle(void *args, int code, const char *arg)
{
    slab_args *a = args;
    int r = cli_slab_opts_handle(CMD, &a->so, code, arg);
    if (r) return r < 0 ? -1 : 0;
    if (code == OPT_LAMBDA) {
        if (cli_parse_double(CMD, "--lambda-nm", arg, &a->lambda)) return -1;
        if (a->lambda <= 0) return cli_error(CMD, "--lambda-nm: must be positive, got %g", a->lambda), -1;
        return 0;
    }
    if (!strcmp(arg, "closed-form"))
        a->tmm = 0;
    else if (!strcmp(arg, "tmm"))
        a->tmm = 1;
    else
        return cli_error(CMD, "--method: expected closed-form or tmm, got '%s'", arg), -1;
    return 0;
}

static const cli_opt OPTS[] = {
    CLI_SLAB_OPTIONS,
    CLI_CUSTOM("lambda-nm", "L", OPT_LAMBDA, "vacuum wavelength in nm (default 550)"),
    CLI_CUSTOM("method", "M", OPT_METHOD, "closed-form (default; paper eq. 17) or tmm (4x4 transfer matrix)"),
    CLI_FLAG("json", 0, offsetof(slab_args, json), "machine-readable output"),
};

const cli_command_spec CLI_SLAB = {
    "slab",
    "usage: biref slab [OPTIONS]\n\n"
    "Transmission and reflection of a plane wave by a uniaxial slab at one wavelength:\n"
    "2x2 Jones matrices (input s/p -> output s/p), power fractions, normal modes.\n\n"
    "Options:\n",
    OPTS,
    CLI_OPTS_COUNT(OPTS),
    "Example:\n  biref slab --eta-o 1.775 --eta-e 1.231 --axis 0.084,0.979,-0.187 \\\n"
    "             --thickness-mm 1.15 --theta-deg 30 --lambda-nm 550 --json\n",
    0,
    handle,
    0,
};

static const char *const MODE_NAMES[4] = {"o_down", "e_down", "o_up", "e_up"};
static const char *const SP[2] = {"s", "p"};

static cJSON *modes_json(const biref_slab_state *st)
{
    cJSON *m = cJSON_CreateObject();
    for (int i = 0; i < 4; i++) {
        cJSON *o = cJSON_AddObjectToObject(m, MODE_NAMES[i]);
        cJSON_AddItemToObject(o, "q", json_complex(st->modes.q[i]));
        cJSON_AddItemToObject(o, "E", json_cvec3(st->modes.E[i]));
        cJSON_AddItemToObject(o, "poynting", json_vec3(st->modes.poynting[i]));
        if (isfinite(st->modes.eta_eff[i]))
            cJSON_AddNumberToObject(o, "eta_eff", st->modes.eta_eff[i]);
        else
            cJSON_AddNullToObject(o, "eta_eff");
    }
    return m;
}

static int run(const slab_args *a);

int cmd_slab(int argc, char **argv)
{
    slab_args a;
    memset(&a, 0, sizeof a);
    cli_slab_opts_init(&a.so);
    a.lambda = 550.0;
    cli_parsed p;
    int r = cli_opts_parse(&CLI_SLAB, &a, argc, argv, &p);
    if (r) return r > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    if (p.n_args) return cli_error(CMD, "unexpected argument '%s'", argv[p.first_arg]), CLI_EXIT_USAGE;
    if (cli_slab_opts_finish(CMD, &a.so)) return CLI_EXIT_USAGE;
    const int rc = run(&a);
    cli_slab_opts_free(&a.so);
    return rc;
}

static int run(const slab_args *a)
{
    const double lambda = a->lambda;
    const int json = a->json, tmm = a->tmm;
    /* A dispersive material: the slab of its indices at this wavelength (exact, both methods). */
    cli_slab_opts so = a->so;
    if (cli_slab_at(CMD, &a->so, lambda, &so.slab)) return CLI_EXIT_USAGE;

    double theta = so.theta_deg * M_PI / 180.0;
    biref_slab_state st;
    biref_status s = biref_slab_prepare(&so.slab, theta, &st);
    if (s != BIREF_OK) return cli_error(CMD, "%s", biref_status_string(s)), CLI_EXIT_FAIL;
    biref_jones T, R;
    if (tmm) {
        s = biref_slab_jones_tmm(&so.slab, theta, lambda, &T, &R);
        if (s != BIREF_OK) return cli_error(CMD, "tmm: %s", biref_status_string(s)), CLI_EXIT_FAIL;
    } else {
        biref_slab_jones_at(&st, lambda, &T, &R);
    }
    double PT[2][2], PR[2][2];
    biref_jones_intensity(&T, PT);
    biref_jones_intensity(&R, PR);
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            if (!isfinite(PT[i][j]) || !isfinite(PR[i][j]))
                return cli_error(CMD, "numerical failure (non-finite result)"), CLI_EXIT_FAIL;

    if (json) {
        cJSON *root = cJSON_CreateObject();
        cJSON_AddStringToObject(root, "method", tmm ? "tmm" : "closed-form");
        cJSON *in = cJSON_AddObjectToObject(root, "input");
        if (so.material)
            cJSON_AddItemToObject(in, "material", json_dispersive_material(so.material, lambda, lambda));
        else
            cJSON_AddNullToObject(in, "material");
        cJSON_AddNumberToObject(in, "eta_o", so.slab.eta_o);
        cJSON_AddNumberToObject(in, "eta_e", so.slab.eta_e);
        cJSON_AddItemToObject(in, "axis", json_vec3(so.slab.axis));
        cJSON_AddNumberToObject(in, "thickness_nm", so.slab.thickness_nm);
        cJSON_AddNumberToObject(in, "theta_deg", so.theta_deg);
        cJSON_AddNumberToObject(in, "lambda_nm", lambda);
        cJSON_AddNumberToObject(in, "eta_i", so.slab.eta_i);
        cJSON_AddItemToObject(root, "T", json_sp_matrix(PT));
        cJSON_AddItemToObject(root, "R", json_sp_matrix(PR));
        cJSON_AddItemToObject(root, "jones_T", json_sp_cmatrix(T.m));
        cJSON_AddItemToObject(root, "jones_R", json_sp_cmatrix(R.m));
        cJSON *en = cJSON_AddObjectToObject(root, "energy");
        for (int i = 0; i < 2; i++) cJSON_AddNumberToObject(en, SP[i], PT[i][0] + PT[i][1] + PR[i][0] + PR[i][1]);
        cJSON_AddNumberToObject(root, "K", st.K);
        cJSON *km = cJSON_AddObjectToObject(root, "K_max");
        cJSON_AddNumberToObject(km, "o", st.modes.K_max_o);
        cJSON_AddNumberToObject(km, "e", st.modes.K_max_e);
        cJSON *tr = cJSON_AddObjectToObject(root, "total_reflection");
        cJSON_AddBoolToObject(tr, "o", st.modes.evanescent_o);
        cJSON_AddBoolToObject(tr, "e", st.modes.evanescent_e);
        cJSON_AddBoolToObject(tr, "any", st.total_reflection);
        cJSON_AddItemToObject(root, "modes", modes_json(&st));
        return json_print_and_free(root) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
    }
    if (so.material) {
        biref_material_info info;
        biref_material_get_info(so.material, &info);
        printf("material %s at %g nm: ", info.name, lambda);
    }
    printf("slab: eta_o %.6g, eta_e %.6g, axis (%.4f, %.4f, %.4f), d %.6g um, eta_i %.4g\n", so.slab.eta_o,
           so.slab.eta_e, so.slab.axis[0], so.slab.axis[1], so.slab.axis[2], so.slab.thickness_nm / 1e3,
           so.slab.eta_i);
    printf("theta %.4g deg, lambda %.6g nm, method %s, K %.6f, K_max o %.6f e %.6f%s\n\n", so.theta_deg, lambda,
           tmm ? "tmm" : "closed-form", st.K, st.modes.K_max_o, st.modes.K_max_e,
           st.total_reflection ? "  (total reflection inside)" : "");
    cli_print_jones_table("Transmission: power fraction (Jones amplitude)", &T, PT);
    cli_print_jones_table("Reflection:   power fraction (Jones amplitude)", &R, PR);
    printf("\nEnergy check T+R: s %.12f, p %.12f\n", PT[0][0] + PT[0][1] + PR[0][0] + PR[0][1],
           PT[1][0] + PT[1][1] + PR[1][0] + PR[1][1]);
    printf("\nNormal modes (q in units of k0):\n");
    for (int i = 0; i < 4; i++)
        printf("  %-7s q = %+.6f%+.6fi   poynting (%+.4f, %+.4f, %+.4f)\n", MODE_NAMES[i], creal(st.modes.q[i]),
               cimag(st.modes.q[i]), st.modes.poynting[i][0], st.modes.poynting[i][1], st.modes.poynting[i][2]);
    return CLI_EXIT_OK;
}
