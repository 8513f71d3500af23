/* biref photoelastic: the extension options (nodes, maps, phase steps, key, scale bar), their
 * checks, and stress from finite-element node exports (docs/PHOTOELASTICITY.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "fea_vtk.h"
#include "photoelastic_ext.h"

static const char *const CMD = "photoelastic";

void pe_ext_init(pe_ext *e)
{
    memset(e, 0, sizeof *e);
    biref_pe_node_format_default(&e->fmt);
    e->map = -1;
}

void pe_ext_free(pe_ext *e)
{
    biref_pe_mesh_destroy(e->mesh);
    e->mesh = NULL;
}

static int parse_columns(pe_ext *e, const char *arg)
{
    static const char *const roles[5] = {"x", "y", "sxx", "syy", "txy"};
    const char **slots[5] = {&e->fmt.x, &e->fmt.y, &e->fmt.sxx, &e->fmt.syy, &e->fmt.txy};
    char buf[512];
    if (strlen(arg) >= sizeof buf) return cli_error(CMD, "--columns: value too long"), -1;
    strcpy(buf, arg);
    char *save = NULL;
    for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        char *eq = strchr(tok, '=');
        if (!eq || eq == tok || !eq[1])
            return cli_error(CMD, "--columns: expected ROLE=NAME pairs such as sxx=S11, got '%s'", tok), -1;
        *eq = '\0';
        int r = -1;
        for (int i = 0; i < 5; i++)
            if (!strcmp(tok, roles[i])) r = i;
        if (r < 0) return cli_error(CMD, "--columns: unknown role '%s' (expected x, y, sxx, syy or txy)", tok), -1;
        if (strlen(eq + 1) >= sizeof e->names[r]) return cli_error(CMD, "--columns: name too long: '%s'", eq + 1), -1;
        strcpy(e->names[r], eq + 1);
        *slots[r] = e->names[r];
    }
    e->have_columns = 1;
    return 0;
}

int pe_ext_option(pe_ext *e, int code, const char *arg)
{
    switch (code) {
    case OPT_PE_NODES: e->nodes_path = arg; return 1;
    case OPT_PE_FEA: e->fea_path = arg; return 1;
    case OPT_PE_FEA_STRESS: e->fea_tensor = arg; return 1;
    case OPT_PE_FEA_FORMAT:
        e->fea_format = !strcmp(arg, "frd") ? PE_FEA_FRD : !strcmp(arg, "vtu") ? PE_FEA_VTU : !strcmp(arg, "vtk") ? PE_FEA_VTK : -1;
        if (e->fea_format < 0) return cli_error(CMD, "--fea-format: expected frd, vtu or vtk, got '%s'", arg), -1;
        return 1;
    case OPT_PE_BOUNDARY: e->boundary_path = arg; return 1;
    case OPT_PE_COLUMNS: return parse_columns(e, arg) ? -1 : 1;
    case OPT_PE_LENGTH_UNIT:
        if (!strcmp(arg, "mm"))
            e->fmt.length_m = 1e-3;
        else if (!strcmp(arg, "m"))
            e->fmt.length_m = 1.0;
        else
            return cli_error(CMD, "--length-unit: expected mm or m, got '%s'", arg), -1;
        e->have_units = 1;
        return 1;
    case OPT_PE_STRESS_UNIT:
        if (!strcmp(arg, "MPa"))
            e->fmt.stress_pa = 1e6;
        else if (!strcmp(arg, "Pa"))
            e->fmt.stress_pa = 1.0;
        else
            return cli_error(CMD, "--stress-unit: expected MPa or Pa, got '%s'", arg), -1;
        e->have_units = 1;
        return 1;
    case OPT_PE_MAP: {
        biref_pe_map_kind k;
        if (biref_pe_map_from_name(arg, &k) != BIREF_OK)
            return cli_error(CMD, "--map: expected fringe-order, isoclinic, retardation, sigma1 or sigma2, got '%s'", arg),
                   -1;
        e->map = (int)k;
        return 1;
    }
    case OPT_PE_PFM: e->pfm = 1; return 1;
    case OPT_PE_FORMAT:
        if (strcmp(arg, "png") && strcmp(arg, "pfm"))
            return cli_error(CMD, "--format: expected png or pfm, got '%s'", arg), -1;
        e->pfm = !strcmp(arg, "pfm");
        return 1;
    case OPT_PE_PHASE_STEPS:
        if (strcmp(arg, "4") && strcmp(arg, "6")) return cli_error(CMD, "--phase-steps: expected 4 or 6, got '%s'", arg), -1;
        e->phase_steps = atoi(arg);
        return 1;
    case OPT_PE_KEY: e->key = 1; return 1;
    case OPT_PE_SCALE_BAR: e->scale_bar = 1; return 1;
    default: return 0;
    }
}

int pe_ext_check(const pe_ext *e, int have_kind, int mono, int have_out, int have_tilt)
{
    if ((e->nodes_path || e->fea_path) && (have_kind || (e->nodes_path && e->fea_path)))
        return cli_error(CMD, "give one of --preset, --stress-grid, --stress-nodes or --fea"), -1;
    if (!e->nodes_path && !e->fea_path && (e->have_columns || e->have_units || e->boundary_path))
        return cli_error(CMD, "%s needs --stress-nodes or --fea",
                         e->have_columns ? "--columns" : e->boundary_path ? "--boundary" : "--length-unit/--stress-unit"),
               -1;
    if (!e->fea_path && (e->fea_tensor || e->fea_format))
        return cli_error(CMD, "%s needs --fea", e->fea_tensor ? "--fea-stress" : "--fea-format"), -1;
    if (e->fea_tensor && e->have_columns)
        return cli_error(CMD, "give one of --fea-stress (a tensor array) and --columns (three components)"), -1;
    const int outputs = (e->map >= 0) + e->pfm + (e->phase_steps > 0);
    if (outputs > 1) return cli_error(CMD, "give at most one of --map, --format pfm and --phase-steps"), -1;
    if (outputs && !have_out) return cli_error(CMD, "--map, --format pfm and --phase-steps write to -o FILE"), -1;
    if ((e->key || e->scale_bar) && (outputs || !have_out))
        return cli_error(CMD, "--key and --scale-bar draw on the PNG picture (-o FILE.png)"), -1;
    if (e->phase_steps && !mono)
        return cli_error(CMD, "--phase-steps needs --light mono (the phase-stepping formulas hold for one wavelength)"), -1;
    if ((e->phase_steps || e->map >= 0) && have_tilt)
        return cli_error(CMD, "--phase-steps and --map are for normal incidence (no --tilt-deg)"), -1;
    return 0;
}

/* The format of --fea: as given, else from the extension. */
static int fea_format(const pe_ext *e)
{
    if (e->fea_format) return e->fea_format;
    const char *dot = strrchr(e->fea_path, '.');
    if (dot && !strcasecmp(dot, ".frd")) return PE_FEA_FRD;
    if (dot && (!strcasecmp(dot, ".vtu") || !strcasecmp(dot, ".vtp"))) return PE_FEA_VTU;
    if (dot && !strcasecmp(dot, ".vtk")) return PE_FEA_VTK;
    return PE_FEA_AUTO;
}

/* A solver's result file with its elements. */
static biref_status load_fea(pe_ext *e, char *msg, size_t msg_len)
{
    const int fmt = fea_format(e);
    if (fmt == PE_FEA_AUTO)
        return snprintf(msg, msg_len, "cannot tell the format from the extension (.frd, .vtu, .vtp, .vtk): give "
                                      "--fea-format frd|vtu|vtk"),
               BIREF_ERR_INVALID;
    if (fmt == PE_FEA_FRD) {
        biref_pe_frd_format f;
        biref_pe_frd_format_default(&f);
        if (e->have_columns) f.sxx = e->fmt.sxx, f.syy = e->fmt.syy, f.txy = e->fmt.txy;
        f.length_m = e->fmt.length_m;
        f.stress_pa = e->fmt.stress_pa;
        snprintf(e->fea_used, sizeof e->fea_used, "%.28s, %.28s, %.28s", f.sxx, f.syy, f.txy);
        return biref_pe_frd_load(e->fea_path, &f, &e->mesh, msg, msg_len);
    }
    pe_vtk_request rq = {e->fea_tensor, {NULL, NULL, NULL}, e->fmt.length_m, e->fmt.stress_pa};
    if (e->have_columns) rq.comp[0] = e->fmt.sxx, rq.comp[1] = e->fmt.syy, rq.comp[2] = e->fmt.txy;
    return pe_vtk_load(e->fea_path, fmt == PE_FEA_VTK, &rq, &e->mesh, e->fea_used, msg, msg_len);
}

int pe_ext_nodes_field(pe_ext *e, biref_pe_field *f, double h)
{
    char msg[512];
    const char *src = e->fea_path ? e->fea_path : e->nodes_path;
    biref_status st = e->fea_path ? load_fea(e, msg, sizeof msg) : biref_pe_mesh_load(e->nodes_path, &e->fmt, &e->mesh, msg, sizeof msg);
    if (st == BIREF_OK && e->boundary_path) {
        st = biref_pe_mesh_boundary_load(e->mesh, e->boundary_path, e->fmt.length_m, msg, sizeof msg);
        if (st != BIREF_OK) {
            cli_error(CMD, "%s: %s", e->boundary_path, msg);
            return st == BIREF_ERR_NOMEM ? CLI_EXIT_FAIL : CLI_EXIT_USAGE;
        }
    }
    if (st != BIREF_OK) {
        cli_error(CMD, "%s: %s", src, msg);
        return st == BIREF_ERR_NOMEM ? CLI_EXIT_FAIL : CLI_EXIT_USAGE;
    }
    if (e->boundary_path && biref_pe_mesh_nodes_inside(e->mesh, NULL) == 0) {
        biref_pe_mesh_info info;
        double b[4];
        biref_pe_mesh_get_info(e->mesh, &info);
        biref_pe_mesh_bounds(e->mesh, b);
        const double u = e->fmt.length_m;
        cli_error(CMD, "%s: the boundary encloses none of the %zu nodes (x %g..%g, y %g..%g in the nodes' unit): another "
                       "length unit, or another part's outline?",
                  e->boundary_path, info.nodes, b[0] / u, b[1] / u, b[2] / u, b[3] / u);
        return CLI_EXIT_USAGE;
    }
    if (biref_pe_field_nodes(f, e->mesh, h, msg, sizeof msg) != BIREF_OK) {
        cli_error(CMD, "nodes: %s", msg);
        return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
}

void pe_ext_json(const pe_ext *e, cJSON *root)
{
    if (!root || !e->mesh) return;
    biref_pe_mesh_info info;
    biref_pe_mesh_get_info(e->mesh, &info);
    cJSON *o = cJSON_AddObjectToObject(root, e->fea_path ? "fea" : "nodes");
    if (e->fea_path) {
        static const char *const fmts[] = {"?", "frd", "vtu", "vtk"};
        static const char *const types[BIREF_PE_ELEMENT_TYPES] = {"tri3", "tri6", "quad4", "quad8", "quad9"};
        cJSON_AddStringToObject(o, "file", e->fea_path);
        cJSON_AddStringToObject(o, "format", fmts[fea_format(e)]);
        cJSON_AddStringToObject(o, "stress", e->fea_used);
        cJSON_AddNumberToObject(o, "nodes", (double)info.nodes);
        cJSON_AddNumberToObject(o, "elements", (double)info.elements);
        cJSON *t = cJSON_AddObjectToObject(o, "element_types");
        for (int k = 0; k < BIREF_PE_ELEMENT_TYPES; k++)
            if (info.by_type[k]) cJSON_AddNumberToObject(t, types[k], (double)info.by_type[k]);
    } else {
        cJSON_AddNumberToObject(o, "rows", (double)info.rows);
        cJSON_AddNumberToObject(o, "distinct", (double)info.nodes);
        cJSON_AddNumberToObject(o, "triangles", (double)info.triangles);
    }
    cJSON_AddNumberToObject(o, "boundary_polygons", (double)info.loops);
}
