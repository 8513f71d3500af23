/* biref photoelastic: the option table (which also gives --help and docs/CLI.md), the values
 * that need more than a number, and the checks between options. */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "cli_values.h"
#include "photoelastic_args.h"

static const char *const CMD = "photoelastic";

enum {
    OPT_PRESET = 1,
    OPT_GRID,
    OPT_THICKNESS,
    OPT_MATERIAL,
    OPT_POLARISCOPE,
    OPT_FIELD,
    OPT_POLARIZER,
    OPT_POLARIZER_DEG,
    OPT_LIGHT,
    OPT_EXPOSURE,
    OPT_PROFILE,
    OPT_WINDOW,
    OPT_VIEW,
    OPT_ANTIALIAS,
    OPT_FRINGE_VALUE
};

/* Geometry options and the presets they belong to (bit 1 << kind; grid and nodes have none). */
static const struct {
    const char *name;
    unsigned presets;
} GEO[PE_N_GEO] = {
    [PE_RADIUS] = {"--radius-mm", 1u << BIREF_PE_DISK | 1u << BIREF_PE_HOLE},
    [PE_LOAD] = {"--load-N", 1u << BIREF_PE_DISK},
    [PE_STRESS] = {"--stress-MPa", 1u << BIREF_PE_HOLE},
    [PE_WIDTH] = {"--width-mm", 1u << BIREF_PE_HOLE},
    [PE_HEIGHT] = {"--height-mm", 1u << BIREF_PE_HOLE},
    [PE_LENGTH] = {"--length-mm", 1u << BIREF_PE_BEAM},
    [PE_DEPTH] = {"--depth-mm", 1u << BIREF_PE_BEAM},
    [PE_MOMENT] = {"--moment-Nmm", 1u << BIREF_PE_BEAM},
    [PE_TENSION] = {"--tension-deg", 1u << BIREF_PE_HOLE},
};

const char *pe_kind_name(int kind)
{
    static const char *const names[] = {"disk", "hole", "beam", "grid", "nodes"};
    return kind >= 0 && kind < 5 ? names[kind] : "?";
}

double pe_geo_or(const pe_args *a, int g, double dflt)
{
    return isnan(a->geo[g]) ? dflt : a->geo[g];
}

/* One word of a list ("plane", "circular") -> its value; -1 after an error. */
static int pick(const char *opt, const char *arg, const char *const *words, const int *values, int n, int *out)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(arg, words[i])) {
            *out = values[i];
            return 0;
        }
    char expected[128] = "";
    for (int i = 0; i < n; i++)
        snprintf(expected + strlen(expected), sizeof expected - strlen(expected), "%s%s",
                 i == 0 ? "" : i == n - 1 ? " or " : ", ", words[i]);
    cli_error(CMD, "%s: expected %s, got '%s'", opt, expected, arg);
    return -1;
}

static int set_kind(pe_args *a, int kind)
{
    if (a->kind >= 0) return cli_error(CMD, "give one of --preset or --stress-grid, once"), -1;
    a->kind = kind;
    return 0;
}

static int handle_choice(pe_args *a, int code, const char *arg)
{
    int v = 0, r;
    switch (code) {
    case OPT_PRESET:
        if (a->kind >= 0) return set_kind(a, 0);
        r = pick("--preset", arg, (const char *const[]){"disk", "hole", "beam"},
                 (const int[]){BIREF_PE_DISK, BIREF_PE_HOLE, BIREF_PE_BEAM}, 3, &v);
        return r ? r : set_kind(a, v);
    case OPT_POLARISCOPE:
        r = pick("--polariscope", arg, (const char *const[]){"plane", "circular"},
                 (const int[]){BIREF_PE_PLANE, BIREF_PE_CIRCULAR}, 2, &v);
        a->pk = (biref_pe_polariscope_kind)v;
        return r;
    case OPT_FIELD:
        r = pick("--field", arg, (const char *const[]){"dark", "light"}, (const int[]){BIREF_PE_DARK, BIREF_PE_LIGHT},
                 2, &v);
        a->ft = (biref_pe_field_type)v;
        return r;
    case OPT_LIGHT:
        r = pick("--light", arg, (const char *const[]){"white", "mono"}, (const int[]){BIREF_PE_WHITE, BIREF_PE_MONO},
                 2, &v);
        a->light = (biref_pe_light_kind)v;
        return r;
    default: return -1;
    }
}

/* --fringe-value F@L: the material fringe value F (N/mm per fringe) quoted at L nm. */
static int parse_fringe_value(pe_args *a, const char *arg)
{
    const char *at = strchr(arg, '@');
    char f[64];
    if (!at || (size_t)(at - arg) >= sizeof f)
        return cli_error(CMD, "--fringe-value: expected F@LAMBDA_NM, the fringe value in N/mm per fringe and the "
                              "wavelength it is quoted at, e.g. 7.0@546.1; got '%s'", arg),
               -1;
    memcpy(f, arg, (size_t)(at - arg));
    f[at - arg] = '\0';
    if (cli_parse_double(CMD, "--fringe-value", f, &a->fringe_value) ||
        cli_parse_double(CMD, "--fringe-value (wavelength)", at + 1, &a->fringe_value_nm))
        return -1;
    if (!(a->fringe_value > 0 && a->fringe_value <= 1e9))
        return cli_error(CMD, "--fringe-value: must be positive and at most 1e9 N/mm, got %g", a->fringe_value), -1;
    if (!(a->fringe_value_nm >= 200 && a->fringe_value_nm <= 2000))
        return cli_error(CMD, "--fringe-value: the wavelength must be in [200, 2000] nm, got %g", a->fringe_value_nm), -1;
    return 0;
}

static int handle(void *args, int code, const char *arg)
{
    pe_args *a = args;
    switch (code) {
    case OPT_PRESET:
    case OPT_POLARISCOPE:
    case OPT_FIELD:
    case OPT_LIGHT: return handle_choice(a, code, arg);
    case OPT_GRID:
        if (set_kind(a, BIREF_PE_GRID)) return -1;
        a->grid_path = arg;
        return 0;
    case OPT_THICKNESS:
        if (cli_parse_double(CMD, "--thickness-mm", arg, &a->thickness_mm)) return -1;
        if (!(a->thickness_mm > 0 && a->thickness_mm <= 1000))
            return cli_error(CMD, "--thickness-mm: must be in (0, 1000], got %g", a->thickness_mm), -1;
        return 0;
    case OPT_MATERIAL: {
        biref_pe_material m;
        if (biref_pe_material_preset(arg, &m) != BIREF_OK)
            return cli_error(CMD, "--material: expected polycarbonate, epoxy, pmma or glass, got '%s'", arg), -1;
        a->material_name = arg;
        a->material_given = 1;
        return 0;
    }
    case OPT_POLARIZER: return cli_parse_linear_polarizer(CMD, "--polarizer", arg, &a->polarizer_deg);
    case OPT_POLARIZER_DEG:
        if (cli_parse_double(CMD, "--polarizer-deg", arg, &a->polarizer_deg)) return -1;
        a->polarizer_deg = fmod(a->polarizer_deg, 360.0);
        return 0;
    case OPT_EXPOSURE:
        if (cli_parse_double(CMD, "--exposure", arg, &a->exposure)) return -1;
        if (!(a->exposure > 0 && a->exposure <= 1e30))
            return cli_error(CMD, "--exposure: must be positive and at most 1e30, got %g", a->exposure), -1;
        return 0;
    case OPT_PROFILE:
        a->have_profile = 1;
        if (cli_parse_list(CMD, "--profile", arg, a->profile, 4)) return -1;
        return cli_check_coordinates_mm(CMD, "--profile", arg, a->profile, 4);
    case OPT_WINDOW:
        a->have_view = 1;
        return cli_parse_window(CMD, "--window-mm", arg, a->view);
    case OPT_ANTIALIAS: return cli_parse_antialias(CMD, arg, &a->prefilter);
    case OPT_FRINGE_VALUE: return parse_fringe_value(a, arg);
    case OPT_VIEW:
        if (cli_parse_list(CMD, "--view-mm", arg, a->view, 4) || cli_check_coordinates_mm(CMD, "--view-mm", arg, a->view, 4))
            return -1;
        if (!(a->view[1] > a->view[0] && a->view[3] > a->view[2]))
            return cli_error(CMD, "--view-mm: expected xmin,xmax,ymin,ymax with xmin < xmax and ymin < ymax"), -1;
        a->have_view = 1;
        return 0;
    default: return pe_ext_option(&a->ext, code, arg) > 0 ? 0 : -1;
    }
}

#define F(field) offsetof(pe_args, field)
static const cli_opt OPTS[] = {
    CLI_TEXT("Specimen:\n"),
    CLI_CUSTOM("preset", "P",
               OPT_PRESET,
               "disk: disk under diametral compression (Hertz/Frocht);\n"
               "hole: plate with a circular hole under remote uniaxial tension\n"
               "along x (Kirsch); beam: beam in pure bending, sigma_xx = M y / I"),
    CLI_DOUBLE("radius-mm", "R", F(geo[PE_RADIUS]), 0, 0, "disk radius (default 25) or hole radius (default 5)"),
    CLI_DOUBLE("load-N", "P", F(geo[PE_LOAD]), 0, 0, "disk: compressive load (default 500)"),
    CLI_DOUBLE("stress-MPa", "S", F(geo[PE_STRESS]), 0, 0, "hole: remote stress (default 4)"),
    CLI_DOUBLE("width-mm", "W", F(geo[PE_WIDTH]), 0, 0, "hole: plate width (default 60)"),
    CLI_DOUBLE("height-mm", "H", F(geo[PE_HEIGHT]), 0, 0, "hole: plate height (default: the width)"),
    CLI_DOUBLE("tension-deg", "A", F(geo[PE_TENSION]), 0, 0, "hole: direction of the tension from x towards y (default 0)"),
    CLI_DOUBLE("length-mm", "L", F(geo[PE_LENGTH]), 0, 0, "beam: length (default 100)"),
    CLI_DOUBLE("depth-mm", "D", F(geo[PE_DEPTH]), 0, 0, "beam: depth (default 20)"),
    CLI_DOUBLE("moment-Nmm", "M", F(geo[PE_MOMENT]), 0, 0, "beam: bending moment (default 2000)"),
    CLI_CUSTOM("stress-grid", "FILE", OPT_GRID,
               "CSV with header x_mm,y_mm,sxx_MPa,syy_MPa,txy_MPa on a regular grid\n"
               "(bilinear interpolation; the picture shows the grid's extent)"),
    CLI_CUSTOM("stress-nodes", "FILE", OPT_PE_NODES,
               "node table with a header (finite-element nodes, scattered; Delaunay\n"
               "triangulation, linear in each triangle); other columns are ignored;\n"
               "comma, semicolon or blank separated; repeated nodes are averaged"),
    CLI_CUSTOM("fea", "FILE", OPT_PE_FEA,
               "finite-element results with their elements: CalculiX .frd (ASCII),\n"
               "VTK .vtu/.vtp (XML, any encoding) or legacy .vtk; plane elements (linear\n"
               "and quadratic triangles and quads), interpolated inside each element;\n"
               "outside every element there is no material (holes need no boundary)"),
    CLI_CUSTOM("fea-format", "frd|vtu|vtk", OPT_PE_FEA_FORMAT, "the format of --fea (default: from the extension)"),
    CLI_CUSTOM("fea-stress", "NAME", OPT_PE_FEA_STRESS,
               "VTK: the point-data stress tensor (3, 6 or 9 components; default the\n"
               "first of stress, S, sigma, then scalars stress_xx/_yy/_xy, sxx/syy/sxy,\n"
               "S11/S22/S12); .frd: components SXX, SYY, SXY unless --columns"),
    CLI_CUSTOM("columns", "x=X,y=Y,sxx=S11,syy=S22,txy=S12", OPT_PE_COLUMNS,
               "column names of the nodes (default x, y, sxx, syy, txy); with --fea\n"
               "the three stress components' names (arrays, or .frd components)"),
    CLI_CUSTOM("length-unit", "mm|m", OPT_PE_LENGTH_UNIT, "unit of the nodes' coordinates (default mm)"),
    CLI_CUSTOM("stress-unit", "MPa|Pa", OPT_PE_STRESS_UNIT, "unit of the nodes' stresses (default MPa)"),
    CLI_CUSTOM("boundary", "FILE", OPT_PE_BOUNDARY,
               "outline polygons of the nodes (x,y per line, blank line between\n"
               "polygons, even-odd: an outline and its holes); outside it, or outside\n"
               "the triangulation, there is no material (background in pictures,\n"
               "NaN in maps)"),
    CLI_CUSTOM("thickness-mm", "h", OPT_THICKNESS, "plate thickness (default: disk 6, hole 3, beam 6, grid 6)"),
    CLI_TEXT("\nMaterial:\n"),
    CLI_CUSTOM("material", "M", OPT_MATERIAL, "polycarbonate (default), epoxy, pmma, glass"),
    CLI_DOUBLE("n0", "N", F(n0), 0, 0, "override the index of the unstressed material"),
    CLI_DOUBLE("C-brewster", "C", F(c_brew), 0, 0, "override the stress-optic coefficient (1 Brewster = 1e-12 /Pa)"),
    CLI_CUSTOM("fringe-value", "F@L", OPT_FRINGE_VALUE,
               "the material fringe value instead: F N/mm per fringe, as quoted at\n"
               "L nm (e.g. 7.0@546.1); C = L / F"),
    CLI_DOUBLE("dispersion-alpha", "A", F(dispersion_alpha), -1, 3,
               "dispersion of birefringence: C(lambda) = C (Lref / lambda)^A, Lref the\n"
               "wavelength of C (546.1 nm, or L of --fringe-value); 0 = none (the\n"
               "presets' default; docs/PHOTOELASTICITY.md)"),
    CLI_DOUBLE("eta-i", "N", F(eta_i), 1, 5, "index around the plate (default 1; n0 = index-matched immersion)"),
    CLI_TEXT("\nPolariscope and light:\n"),
    CLI_CUSTOM("polariscope", "P", OPT_POLARISCOPE, "plane or circular (default circular)"),
    CLI_CUSTOM("field", "F", OPT_FIELD, "dark (crossed, default) or light (parallel)"),
    CLI_CUSTOM("polarizer", "linear:DEG", OPT_POLARIZER,
               "polarizer angle from x towards y, counter-clockwise (default\n"
               "linear:0 = s); an ideal circular polariscope does not depend on it"),
    CLI_CUSTOM("light", "L", OPT_LIGHT, "white (illuminant E, CIE 1931, default) or mono"),
    CLI_DOUBLE("lambda-nm", "L", F(lambda), 200, 2000, "wavelength for mono (default 589); fringe orders use it too"),
    CLI_FLAG("tint", 0, F(tint), "mono: tint the grey levels with the colour of that wavelength"),
    CLI_TEXT("\nPicture:\n"),
    CLI_STRING("output", 'o', "FILE", F(out), "write an sRGB PNG (or what --format, --map, --phase-steps say)"),
    CLI_INT("size", "N", F(size), 1, BIREF_PE_MAX_SIDE, "pixels along the longer side of the picture (default 512)"),
    CLI_CUSTOM("window-mm", "x0,y0,x1,y1", OPT_WINDOW,
               "show the window with opposite corners (x0, y0) and (x1, y1) of\n"
               "the plate instead of the whole part (|x|, |y| <= 1e6 mm)"),
    CLI_DOUBLE("margin-pct", "P", F(margin_pct), 0, 100,
               "space around the part, % of its larger side on each side (default 5\n"
               "for --stress-nodes and --fea; presets and grids: their own frame)"),
    CLI_DOUBLE("tilt-deg", "A", F(tilt_deg), 0, BIREF_PE_MAX_TILT_DEG,
               "view the plate A degrees off its normal (turned about its x axis;\n"
               "0-80, default 0). Uses the general slab path (about 15x slower) and\n"
               "the uniaxial approximation, exact only at 0 or where one principal\n"
               "stress vanishes (docs/PHOTOELASTICITY.md)"),
    CLI_INT("supersample", "K", F(supersample), 1, BIREF_PE_MAX_SUPERSAMPLE, "K x K samples per pixel, 1-64 (default 2)"),
    CLI_CUSTOM("antialias", "A", OPT_ANTIALIAS,
               "prefilter (default): each sample averages the fringes over its\n"
               "footprint in retardation (no moire where fringes crowd, e.g. at the\n"
               "loads); none: the fringes at the sample point (docs/ANTIALIASING.md).\n"
               "Normal-view pictures only (not --tilt-deg, --map or --phase-steps)"),
    CLI_CUSTOM("exposure", "E", OPT_EXPOSURE, "multiply intensities by E (default 1)"),
    CLI_INT("threads", "T", F(threads), 0, 1024,
            "OpenMP threads (default: all cores); the picture does not depend on T"),
    CLI_CUSTOM("format", "png|pfm", OPT_PE_FORMAT,
               "the picture as 8-bit sRGB PNG (default) or float PFM (linear sRGB;\n"
               "mono untinted: grey)"),
    CLI_CUSTOM("map", "M", OPT_PE_MAP,
               "fringe-order, isoclinic (deg, direction of s1), retardation (nm),\n"
               "sigma1 or sigma2 (MPa) on the picture's pixel grid instead of a picture:\n"
               "FILE.pfm (float, NaN = no material) or FILE.csv (x_mm,y_mm,value)"),
    CLI_CUSTOM("phase-steps", "4|6", OPT_PE_PHASE_STEPS,
               "the images of a phase-stepped circular polariscope (six-step method of\n"
               "Patterson & Wang; 4 = its first four), mono light: FILE-1.pfm ... or\n"
               "FILE-1.png ... (16-bit linear grey); recover the maps with\n"
               "'biref photoelastic demodulate'"),
    CLI_CUSTOM("key", NULL, OPT_PE_KEY, "add a fringe-order colour key (Michel-Levy chart) below the picture"),
    CLI_CUSTOM("scale-bar", NULL, OPT_PE_SCALE_BAR, "add a length bar to the picture"),
    CLI_TEXT("\nProfile:\n"),
    CLI_CUSTOM("profile", "x0,y0,x1,y1", OPT_PROFILE,
               "print intensity, retardation (nm) and fringe order N = h C (s1 - s2) / lambda\n"
               "along the line from (x0, y0) to (x1, y1) in mm, |x|, |y| <= 1e6 (white\n"
               "light: N at 550 nm;\n"
               "tilted: the model's retardation along the oblique path)"),
    CLI_INT("profile-points", "N", F(samples), 2, 100000, "points on the profile (default 201)"),
    CLI_FLAG("json", 0, F(json), "machine-readable output"),
    {.name = "samples", .kind = CLI_OPT_INT, .value = "N", .offset = F(samples), .lo = 2, .hi = 100000,
     .old_of = "profile-points", .help = "--profile-points N"},
    CLI_OLD("polarizer-deg", "A", OPT_POLARIZER_DEG, "polarizer", "--polarizer linear:A"),
    CLI_OLD("view-mm", "xmin,xmax,ymin,ymax", OPT_VIEW, "window-mm", "--window-mm xmin,ymin,xmax,ymax"),
    CLI_OLD("pfm", NULL, OPT_PE_PFM, "format", "--format pfm"),
};
#undef F

static const char *const EXCLUSIVE[] = {"preset stress-grid stress-nodes fea", "map format phase-steps", NULL};

const cli_command_spec CLI_PHOTOELASTIC = {
    "photoelastic",
    "usage: biref photoelastic (--preset disk|hole|beam | --stress-grid FILE | --stress-nodes FILE | --fea FILE)\n"
    "                          [OPTIONS]\n"
    "       biref photoelastic demodulate IMAGES... -o DIR --zero-order PX,PY (see its --help)\n\n"
    "A plate under plane stress seen in a polariscope (at normal incidence unless --tilt-deg):\n"
    "isochromatic fringes (and isoclinics in a plane polariscope) from the stress-optic law\n"
    "n1 - n2 = C (s1 - s2).\n"
    "Each point is a uniaxial slab with its optic axis along the first principal stress\n"
    "(docs/PHOTOELASTICITY.md).\n\n",
    OPTS,
    CLI_OPTS_COUNT(OPTS),
    "Exit status: 0 success, 1 runtime failure (e.g. unwritable output), 2 bad usage or input.\n\n"
    "Examples:\n"
    "  biref photoelastic --preset disk --light mono --lambda-nm 589 -o disk.png\n"
    "  biref photoelastic --preset hole --polariscope plane --polarizer linear:0 -o hole.png\n"
    "  biref photoelastic --preset disk --profile 0,-25,0,25 --json\n"
    "  biref photoelastic --stress-nodes part.csv --columns sxx=S11,syy=S22,txy=S12 --map fringe-order -o N.pfm\n",
    0,
    handle,
    1,
    EXCLUSIVE,
};

static void defaults(pe_args *a)
{
    memset(a, 0, sizeof *a);
    a->kind = -1;
    a->material_name = "polycarbonate";
    a->thickness_mm = a->n0 = a->c_brew = a->fringe_value = a->fringe_value_nm = a->margin_pct = NAN;
    a->dispersion_alpha = NAN;
    a->eta_i = 1.0;
    a->lambda = 589.0;
    a->exposure = 1.0;
    for (int i = 0; i < PE_N_GEO; i++) a->geo[i] = NAN;
    a->size = 512;
    a->supersample = 2;
    a->prefilter = 1;
    a->samples = 201;
    a->pk = BIREF_PE_CIRCULAR;
    a->ft = BIREF_PE_DARK;
    a->light = BIREF_PE_WHITE;
    pe_ext_init(&a->ext);
}

/* The checks between options, in the order the messages should come. */
static int check(pe_args *a, const cli_parsed *p, char **argv)
{
    const int mono = a->light == BIREF_PE_MONO;
    if (pe_ext_check(&a->ext, a->kind >= 0, mono, a->out != NULL, a->tilt_deg > 0)) return -1;
    if (a->ext.nodes_path || a->ext.fea_path) a->kind = BIREF_PE_NODES;
    if (p->n_args > 0) return cli_error(CMD, "unexpected argument '%s'", argv[p->first_arg]), -1;
    if (a->kind < 0) return cli_error(CMD, "missing --preset disk|hole|beam, --stress-grid FILE, --stress-nodes FILE or --fea FILE"), -1;
    for (int i = 0; i < PE_N_GEO; i++)
        if (!isnan(a->geo[i]) && !(GEO[i].presets & (1u << a->kind)))
            return cli_error(CMD, "%s does not apply to %s", GEO[i].name,
                             a->kind >= BIREF_PE_GRID ? (a->kind == BIREF_PE_GRID ? "--stress-grid" : "--stress-nodes")
                                                      : pe_kind_name(a->kind)),
                   -1;
    if (!isnan(a->fringe_value) && !isnan(a->c_brew))
        return cli_error(CMD, "give one of --C-brewster and --fringe-value (both set the stress-optic coefficient)"), -1;
    if (!isnan(a->margin_pct) && a->have_view)
        return cli_error(CMD, "give one of --margin-pct and --window-mm (the window sets the frame)"), -1;
    if (!a->out && !a->have_profile) return cli_error(CMD, "nothing to do: give -o OUT.png and/or --profile"), -1;
    if (a->tint && !mono) return cli_error(CMD, "--tint needs --light mono"), -1;
    if (cli_opts_given(&CLI_PHOTOELASTIC, p, "lambda-nm") && !mono)
        return cli_error(CMD, "--lambda-nm needs --light mono (white-light fringe orders are quoted at %.0f nm)",
                         WHITE_FRINGE_LAMBDA_NM),
               -1;
    if (cli_opts_given(&CLI_PHOTOELASTIC, p, "antialias") && (a->ext.map >= 0 || a->ext.phase_steps || a->tilt_deg > 0))
        return cli_error(CMD, "--antialias applies to normal-view pictures, not to --tilt-deg, --map or --phase-steps"),
               -1;
    if (a->tilt_deg > 0) a->prefilter = 0; /* the tilted view samples the general slab path at points */
    if (cli_opts_given(&CLI_PHOTOELASTIC, p, "profile-points") && !a->have_profile)
        return cli_error(CMD, "--profile-points needs --profile"), -1;
    return 0;
}

int pe_args_parse(int argc, char **argv, pe_args *a)
{
    defaults(a);
    cli_parsed p;
    int r = cli_opts_parse(&CLI_PHOTOELASTIC, a, argc, argv, &p);
    if (!r) r = check(a, &p, argv);
    if (r) pe_ext_free(&a->ext);
    return r;
}
