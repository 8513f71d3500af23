#include "json_out.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static const char *const SP[2] = {"s", "p"};

cJSON *json_complex(double complex z)
{
    double v[2] = {creal(z), cimag(z)};
    return cJSON_CreateDoubleArray(v, 2);
}

cJSON *json_vec3(const double v[3]) { return cJSON_CreateDoubleArray(v, 3); }

cJSON *json_cvec3(const double complex v[3])
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; i < 3; i++) cJSON_AddItemToArray(a, json_complex(v[i]));
    return a;
}

cJSON *json_sp_matrix(const double m[2][2])
{
    cJSON *o = cJSON_CreateObject();
    for (int i = 0; i < 2; i++) {
        cJSON *row = cJSON_AddObjectToObject(o, SP[i]);
        for (int j = 0; j < 2; j++) cJSON_AddNumberToObject(row, SP[j], m[i][j]);
    }
    return o;
}

cJSON *json_sp_cmatrix(const double complex m[2][2])
{
    cJSON *o = cJSON_CreateObject();
    for (int i = 0; i < 2; i++) {
        cJSON *row = cJSON_AddObjectToObject(o, SP[i]);
        for (int j = 0; j < 2; j++) cJSON_AddItemToObject(row, SP[j], json_complex(m[i][j]));
    }
    return o;
}

cJSON *json_sp_xyz_pairs(const double X[2][2][3])
{
    cJSON *o = cJSON_CreateObject();
    for (int i = 0; i < 2; i++) {
        cJSON *row = cJSON_AddObjectToObject(o, SP[i]);
        for (int j = 0; j < 2; j++) cJSON_AddItemToObject(row, SP[j], json_vec3(X[i][j]));
    }
    return o;
}

int json_print_and_free(cJSON *root)
{
    char *text = root ? cJSON_Print(root) : NULL;
    cJSON_Delete(root);
    if (!text) {
        fprintf(stderr, "biref: error: out of memory while writing JSON\n");
        return 1;
    }
    puts(text);
    free(text);
    return 0;
}

cJSON *json_dispersive_material(const biref_material *m, double lo_nm, double hi_nm)
{
    biref_material_info info;
    biref_material_get_info(m, &info);
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "name", info.name);
    cJSON_AddStringToObject(o, "source", info.source);
    if (isfinite(info.range_nm[1]))
        cJSON_AddItemToObject(o, "range_nm", cJSON_CreateDoubleArray(info.range_nm, 2));
    else
        cJSON_AddNullToObject(o, "range_nm");
    double ex[2][2];
    const int n = biref_material_extrapolated(m, lo_nm, hi_nm, ex);
    cJSON *arr = cJSON_AddArrayToObject(o, "extrapolated_nm");
    for (int i = 0; i < n; i++) cJSON_AddItemToArray(arr, cJSON_CreateDoubleArray(ex[i], 2));
    return o;
}

cJSON *json_spectrum_head(biref_method method, int samples, const biref_spectral_config *cfg)
{
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "method", biref_method_name(method));
    if (samples)
        cJSON_AddNumberToObject(root, "samples", samples);
    else
        cJSON_AddNullToObject(root, "samples");
    cJSON_AddStringToObject(root, "cmf", biref_cmf_kind_name(cfg->cmf));
    const double range[2] = {cfg->lambda_min_nm, cfg->lambda_max_nm};
    cJSON_AddItemToObject(root, "range_nm", cJSON_CreateDoubleArray(range, 2));
    return root;
}
