/* biref material: the named dispersive materials (list) and one material's indices and group
 * indices at one wavelength. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "json_out.h"

static const char *const CMD = "material";

typedef struct {
    double lambda;
    int have_lambda, json;
} material_args;

enum { OPT_LAMBDA = 1 };

static int handle(void *args, int code, const char *arg)
{
    material_args *a = args;
    if (a->have_lambda) return cli_error(CMD, "--lambda-nm given twice"), -1;
    if (cli_parse_double(CMD, "--lambda-nm", arg, &a->lambda)) return -1;
    if (!(a->lambda > 0)) return cli_error(CMD, "--lambda-nm: must be positive, got %g", a->lambda), -1;
    a->have_lambda = 1;
    return 0;
}

static const cli_opt OPTS[] = {
    CLI_CUSTOM("lambda-nm", "L", OPT_LAMBDA, "vacuum wavelength in nm (default 589.3, the sodium D line)"),
    CLI_FLAG("json", 0, offsetof(material_args, json), "machine-readable output"),
};

const cli_command_spec CLI_MATERIAL = {
    "material",
    "usage: biref material list [--json]\n"
    "       biref material NAME [--lambda-nm L] [--json]\n\n"
    "The named dispersive materials (their formulas, valid ranges and sources: docs/MATERIALS.md),\n"
    "or one material's ordinary and extraordinary indices and group indices n - L dn/dL at one\n"
    "wavelength. Outside a formula's valid range the formula is still evaluated (a warning says\n"
    "so); where it is unphysical (n^2 <= 1, a pole) the material is refused.\n\n"
    "Options:\n",
    OPTS,
    CLI_OPTS_COUNT(OPTS),
    "Example:\n  biref material calcite --lambda-nm 589.3 --json\n",
    0,
    handle,
    0,
};

static int list(int json)
{
    const size_t n = biref_material_catalogue_size();
    if (json) {
        cJSON *arr = cJSON_CreateArray();
        for (size_t i = 0; i < n; i++) {
            biref_material_info info;
            biref_material_get_info(biref_material_catalogue(i), &info);
            cJSON *o = cJSON_CreateObject();
            cJSON_AddStringToObject(o, "name", info.name);
            cJSON_AddStringToObject(o, "description", info.description);
            cJSON_AddBoolToObject(o, "isotropic", info.isotropic);
            cJSON_AddItemToObject(o, "range_nm", cJSON_CreateDoubleArray(info.range_nm, 2));
            cJSON_AddStringToObject(o, "source", info.source);
            cJSON_AddItemToArray(arr, o);
        }
        return json_print_and_free(arr) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
    }
    printf("%-14s %-12s %s\n", "name", "range nm", "description");
    for (size_t i = 0; i < n; i++) {
        biref_material_info info;
        biref_material_get_info(biref_material_catalogue(i), &info);
        char range[32];
        snprintf(range, sizeof range, "%g-%g", info.range_nm[0], info.range_nm[1]);
        printf("%-14s %-12s %s\n", info.name, range, info.description);
    }
    printf("\nSources and formulas: docs/MATERIALS.md; 'biref material NAME' for the indices at a wavelength.\n");
    return CLI_EXIT_OK;
}

static int show(const char *name, double lambda, int json)
{
    const biref_material *m = biref_material_find(name);
    if (!m) return cli_error(CMD, "unknown material '%s' (biref material list names them)", name), CLI_EXIT_USAGE;
    cli_slab_opts so; /* the slab options' checks: the one error line and the extrapolation warning */
    cli_slab_opts_init(&so);
    so.material = m;
    if (cli_slab_check_band(CMD, &so, lambda, lambda)) return CLI_EXIT_USAGE;
    double n[2], ng[2];
    biref_material_indices(m, lambda, n, ng); /* physical there: checked */
    biref_material_info info;
    biref_material_get_info(m, &info);
    if (json) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "name", info.name);
        cJSON_AddNumberToObject(o, "lambda_nm", lambda);
        cJSON_AddNumberToObject(o, "n_o", n[0]);
        cJSON_AddNumberToObject(o, "n_e", n[1]);
        cJSON_AddNumberToObject(o, "n_o_group", ng[0]);
        cJSON_AddNumberToObject(o, "n_e_group", ng[1]);
        cJSON_AddStringToObject(o, "source", info.source);
        cJSON_AddItemToObject(o, "range_nm", cJSON_CreateDoubleArray(info.range_nm, 2));
        return json_print_and_free(o) ? CLI_EXIT_FAIL : CLI_EXIT_OK;
    }
    printf("%s: %s\n", info.name, info.description);
    printf("at %g nm:  n_o %.6f  n_e %.6f  (n_e - n_o %+.6f)\n", lambda, n[0], n[1], n[1] - n[0]);
    printf("group:     n_o %.6f  n_e %.6f  (n_e - n_o %+.6f", ng[0], ng[1], ng[1] - ng[0]);
    if (!info.isotropic) printf(", %.4f x the phase birefringence", (ng[1] - ng[0]) / (n[1] - n[0]));
    printf(")\nvalid %g-%g nm; source: %s\n", info.range_nm[0], info.range_nm[1], info.source);
    return CLI_EXIT_OK;
}

int cmd_material(int argc, char **argv)
{
    material_args a;
    memset(&a, 0, sizeof a);
    a.lambda = 589.3;
    cli_parsed p;
    const int r = cli_opts_parse(&CLI_MATERIAL, &a, argc, argv, &p);
    if (r) return r > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    if (p.n_args != 1)
        return cli_error(CMD, p.n_args ? "expected one argument, 'list' or a material name"
                                        : "missing argument: 'list' or a material name (see biref material --help)"),
               CLI_EXIT_USAGE;
    const char *what = argv[p.first_arg];
    if (!strcmp(what, "list")) {
        if (a.have_lambda) return cli_error(CMD, "--lambda-nm: not used by 'list'"), CLI_EXIT_USAGE;
        return list(a.json);
    }
    return show(what, a.lambda, a.json);
}
