/* biref photoelastic: a stressed plate in a plane or circular polariscope, as a picture (PNG)
 * and/or as a profile of intensity, retardation and fringe order along a line
 * (docs/PHOTOELASTICITY.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_render.h"
#include "commands.h"
#include "json_out.h"
#include "cli_values.h"
#include "photoelastic_ext.h"

static const char *const CMD = "photoelastic";

/* White light has no single wavelength; fringe orders are then quoted at 550 nm (mid-band). */
#define WHITE_FRINGE_LAMBDA_NM 550.0

static void help(void)
{
    printf("usage: biref photoelastic (--preset disk|hole|beam | --stress-grid FILE | --stress-nodes FILE) [OPTIONS]\n"
           "       biref photoelastic demodulate IMAGES... -o DIR --zero-order PX,PY (see its --help)\n\n"
           "A plate under plane stress seen in a polariscope (at normal incidence unless --tilt-deg):\n"
           "isochromatic fringes (and isoclinics in a plane polariscope) from the stress-optic law\n"
           "n1 - n2 = C (s1 - s2).\n"
           "Each point is a uniaxial slab with its optic axis along the first principal stress\n"
           "(docs/PHOTOELASTICITY.md).\n\n"
           "Specimen:\n"
           "  --preset disk        disk under diametral compression (Hertz/Frocht)\n"
           "      --radius-mm R      disk radius (default 25)   --load-N P   compressive load (default 500)\n"
           "  --preset hole        plate with a circular hole under remote uniaxial tension along x (Kirsch)\n"
           "      --radius-mm a      hole radius (default 5)    --stress-MPa S   remote stress (default 4)\n"
           "      --width-mm W, --height-mm H   plate sides (default 60, height = width)\n"
           "      --tension-deg A    direction of the tension from x towards y (default 0)\n"
           "  --preset beam        beam in pure bending, sigma_xx = M y / I\n"
           "      --length-mm L      (default 100)   --depth-mm D (default 20)   --moment-Nmm M (default 2000)\n"
           "  --stress-grid FILE   CSV with header x_mm,y_mm,sxx_MPa,syy_MPa,txy_MPa on a regular grid\n"
           "                       (bilinear interpolation; the picture shows the grid's extent)\n"
           "  --thickness-mm h     plate thickness (default: disk 6, hole 3, beam 6, grid 6)\n\n"
           "Material:\n"
           "  --material M         polycarbonate (default), epoxy, pmma, glass\n"
           "  --n0 N               override the index of the unstressed material\n"
           "  --C-brewster C       override the stress-optic coefficient (1 Brewster = 1e-12 /Pa)\n"
           "  --eta-i N            index around the plate (default 1; n0 = index-matched immersion)\n\n"
           "Polariscope and light:\n"
           "  --polariscope P      plane or circular (default circular)\n"
           "  --field F            dark (crossed, default) or light (parallel)\n"
           "  --polarizer linear:DEG  polarizer angle from x towards y, counter-clockwise (default\n"
           "                       linear:0 = s); an ideal circular polariscope does not depend on it\n"
           "  --light L            white (illuminant E, CIE 1931, default) or mono\n"
           "  --lambda-nm L        wavelength for mono (default 589); fringe orders use it too\n"
           "  --tint               mono: tint the grey levels with the colour of that wavelength\n\n"
           "Output:\n"
           "  -o, --output FILE    write an sRGB PNG\n"
           "  --size N             pixels along the longer side of the picture (default 512)\n"
           "  --window-mm x0,y0,x1,y1  show the window with opposite corners (x0, y0) and (x1, y1) of\n"
           "                       the plate instead of the whole part\n"
           "  --tilt-deg A         view the plate A degrees off its normal (turned about its x axis;\n"
           "                       0-80, default 0). Uses the general slab path (about 15x slower) and\n"
           "                       the uniaxial approximation, exact only at 0 or where one principal\n"
           "                       stress vanishes (docs/PHOTOELASTICITY.md)\n"
           "  --supersample K      K x K samples per pixel (default 2)\n"
           "  --exposure E         multiply intensities by E (default 1)\n"
           "  --threads T          OpenMP threads (default: all cores); the picture does not depend on T\n"
           "  --profile x0,y0,x1,y1  print intensity, retardation (nm) and fringe order N = h C (s1 - s2) / lambda\n"
           "                       along a line in mm (white light: N at 550 nm; tilted: the model's\n"
           "                       retardation along the oblique path)\n"
           "  --profile-points N   points on the profile (default 201)\n"
           "  --json               machine-readable output\n"
           "  -h, --help           this help\n\n");
    pe_ext_help();
    printf("Exit status: 0 success, 1 runtime failure (e.g. unwritable output), 2 bad usage or input.\n\n"
           "Examples:\n"
           "  biref photoelastic --preset disk --light mono --lambda-nm 589 -o disk.png\n"
           "  biref photoelastic --preset hole --polariscope plane --polarizer linear:0 -o hole.png\n"
           "  biref photoelastic --preset disk --profile 0,-25,0,25 --json\n"
           "  biref photoelastic --stress-nodes part.csv --columns sxx=S11,syy=S22,txy=S12 --map fringe-order -o N.pfm\n");
}

enum {
    OPT_PRESET = 3000,
    OPT_GRID,
    OPT_THICKNESS,
    OPT_RADIUS,
    OPT_LOAD,
    OPT_STRESS,
    OPT_WIDTH,
    OPT_HEIGHT,
    OPT_LENGTH,
    OPT_DEPTH,
    OPT_MOMENT,
    OPT_TENSION_DEG,
    OPT_MATERIAL,
    OPT_N0,
    OPT_CBREW,
    OPT_ETA_I_PE,
    OPT_POLARISCOPE,
    OPT_FIELD,
    OPT_POLARIZER,
    OPT_LIGHT,
    OPT_LAMBDA,
    OPT_TINT,
    OPT_SIZE,
    OPT_SUPERSAMPLE,
    OPT_EXPOSURE,
    OPT_THREADS,
    OPT_PROFILE,
    OPT_SAMPLES,
    OPT_JSON,
    OPT_VIEW,
    OPT_WINDOW,
    OPT_POLARIZER_DEG,
    OPT_TILT,
    OPT_END
};

/* Geometry options and the presets they belong to (bit 1 << kind; grid has none). */
typedef struct {
    int code;
    const char *name;
    unsigned presets;
} geo_opt;

static const geo_opt GEO[] = {
    {OPT_RADIUS, "--radius-mm", 1u << BIREF_PE_DISK | 1u << BIREF_PE_HOLE},
    {OPT_LOAD, "--load-N", 1u << BIREF_PE_DISK},
    {OPT_STRESS, "--stress-MPa", 1u << BIREF_PE_HOLE},
    {OPT_WIDTH, "--width-mm", 1u << BIREF_PE_HOLE},
    {OPT_HEIGHT, "--height-mm", 1u << BIREF_PE_HOLE},
    {OPT_LENGTH, "--length-mm", 1u << BIREF_PE_BEAM},
    {OPT_DEPTH, "--depth-mm", 1u << BIREF_PE_BEAM},
    {OPT_MOMENT, "--moment-Nmm", 1u << BIREF_PE_BEAM},
    {OPT_TENSION_DEG, "--tension-deg", 1u << BIREF_PE_HOLE},
};
#define N_GEO (sizeof GEO / sizeof GEO[0])
static const char *const KIND_NAMES[] = {"disk", "hole", "beam", "grid", "nodes"};

/* Scales a monochromatic colour to a displayable tint: band-normalised XYZ of the spectral line,
 * negative linear sRGB clipped (spectral colours lie outside the gamut) and the largest
 * component raised to 1. */
static int mono_tint(double lambda, double tint[3])
{
    biref_cmf_band band;
    if (biref_cmf_band_init(&band, BIREF_CMF_CIE1931, 380.0, 780.0, NULL, 0) != BIREF_OK) return -1;
    double lam[3], rgb[3];
    biref_cmf_band_eval(&band, lambda, lam);
    biref_xyz_to_linear_srgb(lam, rgb);
    double mx = 0;
    for (int i = 0; i < 3; i++) {
        rgb[i] = fmax(rgb[i], 0.0);
        mx = fmax(mx, rgb[i]);
    }
    if (!(mx > 0)) return -1;
    for (int i = 0; i < 3; i++) rgb[i] /= mx;
    biref_linear_srgb_to_xyz(rgb, tint);
    return 0;
}

static cJSON *material_json(const biref_pe_material *m, double lambda_for_f)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "name", m->name);
    cJSON_AddNumberToObject(o, "n0", m->n0);
    cJSON_AddNumberToObject(o, "C_brewster", m->C_per_Pa / BIREF_BREWSTER);
    cJSON_AddNumberToObject(o, "fringe_constant_N_per_m", biref_pe_fringe_constant(m, lambda_for_f));
    cJSON_AddNumberToObject(o, "fringe_constant_lambda_nm", lambda_for_f);
    cJSON_AddStringToObject(o, "source", m->source);
    return o;
}

int cmd_photoelastic(int argc, char **argv)
{
    static const struct option longopts[] = {{"preset", required_argument, 0, OPT_PRESET},
                                             {"stress-grid", required_argument, 0, OPT_GRID},
                                             {"thickness-mm", required_argument, 0, OPT_THICKNESS},
                                             {"radius-mm", required_argument, 0, OPT_RADIUS},
                                             {"load-N", required_argument, 0, OPT_LOAD},
                                             {"stress-MPa", required_argument, 0, OPT_STRESS},
                                             {"width-mm", required_argument, 0, OPT_WIDTH},
                                             {"height-mm", required_argument, 0, OPT_HEIGHT},
                                             {"length-mm", required_argument, 0, OPT_LENGTH},
                                             {"depth-mm", required_argument, 0, OPT_DEPTH},
                                             {"moment-Nmm", required_argument, 0, OPT_MOMENT},
                                             {"tension-deg", required_argument, 0, OPT_TENSION_DEG},
                                             {"material", required_argument, 0, OPT_MATERIAL},
                                             {"n0", required_argument, 0, OPT_N0},
                                             {"C-brewster", required_argument, 0, OPT_CBREW},
                                             {"eta-i", required_argument, 0, OPT_ETA_I_PE},
                                             {"polariscope", required_argument, 0, OPT_POLARISCOPE},
                                             {"field", required_argument, 0, OPT_FIELD},
                                             {"polarizer", required_argument, 0, OPT_POLARIZER},
                                             {"polarizer-deg", required_argument, 0, OPT_POLARIZER_DEG}, /* old */
                                             {"light", required_argument, 0, OPT_LIGHT},
                                             {"lambda-nm", required_argument, 0, OPT_LAMBDA},
                                             {"tint", no_argument, 0, OPT_TINT},
                                             {"output", required_argument, 0, 'o'},
                                             {"size", required_argument, 0, OPT_SIZE},
                                             {"supersample", required_argument, 0, OPT_SUPERSAMPLE},
                                             {"exposure", required_argument, 0, OPT_EXPOSURE},
                                             {"threads", required_argument, 0, OPT_THREADS},
                                             {"profile", required_argument, 0, OPT_PROFILE},
                                             {"profile-points", required_argument, 0, OPT_SAMPLES},
                                             {"samples", required_argument, 0, OPT_SAMPLES}, /* old name */
                                             {"json", no_argument, 0, OPT_JSON},
                                             {"window-mm", required_argument, 0, OPT_WINDOW},
                                             {"view-mm", required_argument, 0, OPT_VIEW}, /* old, x0,x1,y0,y1 */
                                             {"tilt-deg", required_argument, 0, OPT_TILT},
                                             {"help", no_argument, 0, 'h'},
                                             PE_EXT_LONG_OPTIONS,
                                             {0, 0, 0, 0}};
    if (argc > 1 && !strcmp(argv[1], "demodulate")) return cmd_photoelastic_demodulate(argc - 1, argv + 1);
    int kind = -1, json = 0, tint = 0, have_profile = 0, have_lambda = 0, have_samples = 0;
    const char *grid_path = NULL, *out = NULL, *material_name = "polycarbonate";
    double thickness_mm = NAN, n0 = NAN, c_brew = NAN, eta_i = 1.0, polarizer_deg = 0.0, lambda = 589.0,
           exposure = 1.0;
    double geo[OPT_END - OPT_PRESET];
    int geo_given[OPT_END - OPT_PRESET];
    for (int i = 0; i < OPT_END - OPT_PRESET; i++) {
        geo[i] = NAN;
        geo_given[i] = 0;
    }
    double profile[4], view[4], tilt_deg = 0.0;
    int have_view = 0;
    long size = 512, supersample = 2, threads = 0, samples = 201;
    biref_pe_polariscope_kind pk = BIREF_PE_CIRCULAR;
    biref_pe_field_type ft = BIREF_PE_DARK;
    biref_pe_light_kind light = BIREF_PE_WHITE;

    pe_ext ext;
    pe_ext_init(&ext);
    opterr = 0;
    optind = 1;
    int c;
    while ((c = getopt_long(argc, argv, ":ho:", longopts, NULL)) != -1) {
        switch (c) {
        case 'h': help(); return CLI_EXIT_OK;
        case 'o': out = optarg; break;
        case OPT_PRESET:
            if (kind >= 0) return cli_error(CMD, "give one of --preset or --stress-grid, once"), CLI_EXIT_USAGE;
            if (!strcmp(optarg, "disk"))
                kind = BIREF_PE_DISK;
            else if (!strcmp(optarg, "hole"))
                kind = BIREF_PE_HOLE;
            else if (!strcmp(optarg, "beam"))
                kind = BIREF_PE_BEAM;
            else
                return cli_error(CMD, "--preset: expected disk, hole or beam, got '%s'", optarg), CLI_EXIT_USAGE;
            break;
        case OPT_GRID:
            if (kind >= 0) return cli_error(CMD, "give one of --preset or --stress-grid, once"), CLI_EXIT_USAGE;
            kind = BIREF_PE_GRID;
            grid_path = optarg;
            break;
        case OPT_THICKNESS:
            if (cli_parse_double(CMD, "--thickness-mm", optarg, &thickness_mm)) return CLI_EXIT_USAGE;
            if (!(thickness_mm > 0 && thickness_mm <= 1000))
                return cli_error(CMD, "--thickness-mm: must be in (0, 1000], got %g", thickness_mm), CLI_EXIT_USAGE;
            break;
        case OPT_RADIUS:
        case OPT_LOAD:
        case OPT_STRESS:
        case OPT_WIDTH:
        case OPT_HEIGHT:
        case OPT_LENGTH:
        case OPT_DEPTH:
        case OPT_MOMENT:
        case OPT_TENSION_DEG: {
            const char *name = "";
            for (size_t i = 0; i < N_GEO; i++)
                if (GEO[i].code == c) name = GEO[i].name;
            if (cli_parse_double(CMD, name, optarg, &geo[c - OPT_PRESET])) return CLI_EXIT_USAGE;
            geo_given[c - OPT_PRESET] = 1;
            break;
        }
        case OPT_MATERIAL: {
            biref_pe_material m;
            if (biref_pe_material_preset(optarg, &m) != BIREF_OK)
                return cli_error(CMD, "--material: expected polycarbonate, epoxy, pmma or glass, got '%s'", optarg),
                       CLI_EXIT_USAGE;
            material_name = optarg;
            break;
        }
        case OPT_N0:
            if (cli_parse_double(CMD, "--n0", optarg, &n0)) return CLI_EXIT_USAGE;
            break;
        case OPT_CBREW:
            if (cli_parse_double(CMD, "--C-brewster", optarg, &c_brew)) return CLI_EXIT_USAGE;
            break;
        case OPT_ETA_I_PE:
            if (cli_parse_double(CMD, "--eta-i", optarg, &eta_i)) return CLI_EXIT_USAGE;
            if (!(eta_i >= 1.0 && eta_i <= 5.0))
                return cli_error(CMD, "--eta-i: must be between 1 and 5, got %g", eta_i), CLI_EXIT_USAGE;
            break;
        case OPT_POLARISCOPE:
            if (!strcmp(optarg, "plane"))
                pk = BIREF_PE_PLANE;
            else if (!strcmp(optarg, "circular"))
                pk = BIREF_PE_CIRCULAR;
            else
                return cli_error(CMD, "--polariscope: expected plane or circular, got '%s'", optarg), CLI_EXIT_USAGE;
            break;
        case OPT_FIELD:
            if (!strcmp(optarg, "dark"))
                ft = BIREF_PE_DARK;
            else if (!strcmp(optarg, "light"))
                ft = BIREF_PE_LIGHT;
            else
                return cli_error(CMD, "--field: expected dark or light, got '%s'", optarg), CLI_EXIT_USAGE;
            break;
        case OPT_POLARIZER:
            if (cli_parse_linear_polarizer(CMD, "--polarizer", optarg, &polarizer_deg)) return CLI_EXIT_USAGE;
            break;
        case OPT_POLARIZER_DEG:
            if (cli_parse_double(CMD, "--polarizer-deg", optarg, &polarizer_deg)) return CLI_EXIT_USAGE;
            break;
        case OPT_LIGHT:
            if (!strcmp(optarg, "white"))
                light = BIREF_PE_WHITE;
            else if (!strcmp(optarg, "mono"))
                light = BIREF_PE_MONO;
            else
                return cli_error(CMD, "--light: expected white or mono, got '%s'", optarg), CLI_EXIT_USAGE;
            break;
        case OPT_LAMBDA:
            if (cli_parse_double(CMD, "--lambda-nm", optarg, &lambda)) return CLI_EXIT_USAGE;
            if (!(lambda >= 200 && lambda <= 2000))
                return cli_error(CMD, "--lambda-nm: must be between 200 and 2000, got %g", lambda), CLI_EXIT_USAGE;
            have_lambda = 1;
            break;
        case OPT_TINT: tint = 1; break;
        case OPT_SIZE:
            if (cli_parse_int(CMD, "--size", optarg, 1, 8192, &size)) return CLI_EXIT_USAGE;
            break;
        case OPT_SUPERSAMPLE:
            if (cli_parse_int(CMD, "--supersample", optarg, 1, 8, &supersample)) return CLI_EXIT_USAGE;
            break;
        case OPT_EXPOSURE:
            if (cli_parse_double(CMD, "--exposure", optarg, &exposure)) return CLI_EXIT_USAGE;
            if (!(exposure > 0 && exposure <= 1e30))
                return cli_error(CMD, "--exposure: must be positive and at most 1e30, got %g", exposure), CLI_EXIT_USAGE;
            break;
        case OPT_THREADS:
            if (cli_parse_int(CMD, "--threads", optarg, 0, 1024, &threads)) return CLI_EXIT_USAGE;
            break;
        case OPT_PROFILE:
            if (cli_parse_list(CMD, "--profile", optarg, profile, 4)) return CLI_EXIT_USAGE;
            have_profile = 1;
            break;
        case OPT_SAMPLES:
            if (cli_parse_int(CMD, "--profile-points", optarg, 2, 100000, &samples)) return CLI_EXIT_USAGE;
            have_samples = 1;
            break;
        case OPT_JSON: json = 1; break;
        case OPT_TILT:
            if (cli_parse_double(CMD, "--tilt-deg", optarg, &tilt_deg)) return CLI_EXIT_USAGE;
            if (!(tilt_deg >= 0 && tilt_deg <= 80))
                return cli_error(CMD, "--tilt-deg: must be between 0 and 80, got %g", tilt_deg), CLI_EXIT_USAGE;
            break;
        case OPT_VIEW:
            if (cli_parse_list(CMD, "--view-mm", optarg, view, 4)) return CLI_EXIT_USAGE;
            if (!(view[1] > view[0] && view[3] > view[2]))
                return cli_error(CMD, "--view-mm: expected xmin,xmax,ymin,ymax with xmin < xmax and ymin < ymax"),
                       CLI_EXIT_USAGE;
            have_view = 1;
            break;
        case OPT_WINDOW:
            if (cli_parse_window(CMD, "--window-mm", optarg, view)) return CLI_EXIT_USAGE;
            have_view = 1;
            break;
        default: {
            int r = pe_ext_option(&ext, c, optarg);
            if (r > 0) break;
            if (r == 0) cli_getopt_error(CMD, c, argv);
            return CLI_EXIT_USAGE;
        }
        }
    }
    if (pe_ext_check(&ext, kind >= 0, light == BIREF_PE_MONO, out != NULL, tilt_deg > 0)) return CLI_EXIT_USAGE;
    if (ext.nodes_path) kind = BIREF_PE_NODES;
    if (optind < argc) return cli_error(CMD, "unexpected argument '%s'", argv[optind]), CLI_EXIT_USAGE;
    if (kind < 0)
        return cli_error(CMD, "missing --preset disk|hole|beam, --stress-grid FILE or --stress-nodes FILE"), CLI_EXIT_USAGE;
    for (size_t i = 0; i < N_GEO; i++)
        if (geo_given[GEO[i].code - OPT_PRESET] && !(GEO[i].presets & (1u << kind)))
            return cli_error(CMD, "%s does not apply to %s", GEO[i].name,
                             kind >= BIREF_PE_GRID ? (kind == BIREF_PE_GRID ? "--stress-grid" : "--stress-nodes")
                                                   : KIND_NAMES[kind]),
                   CLI_EXIT_USAGE;
    if (!out && !have_profile) return cli_error(CMD, "nothing to do: give -o OUT.png and/or --profile"), CLI_EXIT_USAGE;
    if (tint && light != BIREF_PE_MONO) return cli_error(CMD, "--tint needs --light mono"), CLI_EXIT_USAGE;
    if (have_lambda && light != BIREF_PE_MONO)
        return cli_error(CMD, "--lambda-nm needs --light mono (white-light fringe orders are quoted at %.0f nm)",
                         WHITE_FRINGE_LAMBDA_NM),
               CLI_EXIT_USAGE;
    if (have_samples && !have_profile) return cli_error(CMD, "--profile-points needs --profile"), CLI_EXIT_USAGE;

    biref_pe_setup setup;
    memset(&setup, 0, sizeof setup);
    (void)biref_pe_material_preset(material_name, &setup.material);
    if (!isnan(n0) || !isnan(c_brew)) {
        setup.material.name = "custom";
        setup.material.source = "user";
        if (!isnan(n0)) setup.material.n0 = n0;
        if (!isnan(c_brew)) setup.material.C_per_Pa = c_brew * BIREF_BREWSTER;
    }
    char msg[256];
    if (biref_pe_material_check(&setup.material, msg, sizeof msg) != BIREF_OK)
        return cli_error(CMD, "material: %s", msg), CLI_EXIT_USAGE;

    /* Geometry, SI units from here on. */
#define GEO_OR(code, dflt) (geo_given[(code) - OPT_PRESET] ? geo[(code) - OPT_PRESET] : (dflt))
    const double mm = 1e-3;
    double h = (isnan(thickness_mm) ? (kind == BIREF_PE_HOLE ? 3.0 : 6.0) : thickness_mm) * mm;
    biref_pe_field field;
    biref_pe_grid *grid = NULL;
    biref_status st = BIREF_OK;
    switch (kind) {
    case BIREF_PE_DISK:
        st = biref_pe_field_disk(&field, GEO_OR(OPT_RADIUS, 25.0) * mm, h, GEO_OR(OPT_LOAD, 500.0), msg, sizeof msg);
        break;
    case BIREF_PE_HOLE: {
        double w = GEO_OR(OPT_WIDTH, 60.0);
        st = biref_pe_field_hole(&field, GEO_OR(OPT_RADIUS, 5.0) * mm, w * mm, GEO_OR(OPT_HEIGHT, w) * mm, h,
                                 GEO_OR(OPT_STRESS, 4.0) * 1e6, GEO_OR(OPT_TENSION_DEG, 0.0) * M_PI / 180.0, msg,
                                 sizeof msg);
        break;
    }
    case BIREF_PE_BEAM:
        st = biref_pe_field_beam(&field, GEO_OR(OPT_LENGTH, 100.0) * mm, GEO_OR(OPT_DEPTH, 20.0) * mm, h,
                                 GEO_OR(OPT_MOMENT, 2000.0) * 1e-3, msg, sizeof msg);
        break;
    case BIREF_PE_NODES: {
        int r = pe_ext_nodes_field(&ext, &field, h);
        if (r) {
            pe_ext_free(&ext);
            return r;
        }
        break;
    }
    default: {
        st = biref_pe_grid_load(grid_path, &grid, msg, sizeof msg);
        if (st != BIREF_OK) {
            cli_error(CMD, "%s: %s", grid_path, msg);
            return st == BIREF_ERR_NOMEM ? CLI_EXIT_FAIL : CLI_EXIT_USAGE;
        }
        st = biref_pe_field_grid(&field, grid, h, msg, sizeof msg);
        break;
    }
    }
#undef GEO_OR
    int rc = CLI_EXIT_OK;
    biref_spectral *sp = NULL;
    float *xyz = NULL;
    unsigned char *rgb = NULL;
    cJSON *root = NULL;
    if (st != BIREF_OK) {
        cli_error(CMD, "%s: %s", KIND_NAMES[kind], msg);
        rc = CLI_EXIT_USAGE;
        goto done;
    }
    if (have_view)
        for (int i = 0; i < 4; i++) field.frame[i] = view[i] * mm;
    setup.thickness = h;
    setup.eta_i = eta_i;
    setup.light = light;
    setup.lambda_nm = lambda;
    biref_pe_polariscope_make(pk, ft, polarizer_deg * M_PI / 180.0, &setup.pol);
    biref_pe_image_opts io = {0, 0, (int)supersample, (int)threads, {1, 1, 1}, tilt_deg * M_PI / 180.0};
    if (tint && mono_tint(lambda, io.tint)) {
        cli_error(CMD, "--tint: %g nm has no visible colour (380-780 nm)", lambda);
        rc = CLI_EXIT_USAGE;
        goto done;
    }
    double tint_rgb[3] = {io.tint[0], io.tint[1], io.tint[2]};
    for (int i = 0; i < 3; i++) io.tint[i] *= exposure;
    const char *inputs[3] = {grid_path, ext.nodes_path, ext.boundary_path};
    if (out && (rc = cli_check_output(CMD, out, inputs, 3))) goto done;
    char why[BIREF_MSG_SIZE];
    if (light == BIREF_PE_WHITE && biref_spectral_create(NULL, &sp, why, sizeof why) != BIREF_OK) {
        cli_error(CMD, "cannot create the spectral tables: %s", why);
        rc = CLI_EXIT_FAIL;
        goto done;
    }
    if (json) root = cJSON_CreateObject();
    double ms = 0;
    /* Square pixels: the longer side of the frame gets --size pixels. */
    double fw = field.frame[1] - field.frame[0], fh = field.frame[3] - field.frame[2];
    fh *= cos(io.tilt); /* the tilted plate is foreshortened along y */
    io.width = fw >= fh ? (int)size : (int)fmax(1, lround(size * fw / fh));
    io.height = fw >= fh ? (int)fmax(1, lround(size * fh / fw)) : (int)size;
    const double lambda_N = light == BIREF_PE_MONO ? lambda : WHITE_FRINGE_LAMBDA_NM;
    const pe_ext_ctx ectx = {&setup, sp,       &field, &io, out, exposure, lambda_N,
                             tint_rgb, root, polarizer_deg * M_PI / 180};
    if (out && pe_ext_owns_output(&ext)) {
        if ((rc = pe_ext_write(&ext, &ectx))) goto done;
    } else if (out) {
        size_t npx = (size_t)io.width * io.height;
        xyz = malloc(npx * 3 * sizeof *xyz);
        rgb = malloc(npx * 3);
        if (!xyz || !rgb) {
            cli_error(CMD, "out of memory for a %d x %d picture", io.width, io.height);
            rc = CLI_EXIT_FAIL;
            goto done;
        }
        double t0 = biref_wall_seconds();
        if (biref_pe_render(&setup, sp, &field, &io, xyz, why, sizeof why) != BIREF_OK) {
            cli_error(CMD, "%s", why);
            rc = CLI_EXIT_FAIL;
            goto done;
        }
        ms = 1e3 * (biref_wall_seconds() - t0);
        if (light == BIREF_PE_WHITE && exposure != 1.0)
            for (size_t i = 0; i < npx * 3; i++) xyz[i] = (float)(xyz[i] * exposure);
        /* A non-finite colour is never an output (the loads are bounded where they enter). */
        for (size_t i = 0; i < npx * 3; i++)
            if (!isfinite(xyz[i])) {
                cli_error(CMD, "%s: the picture came out non-finite (no image written)", KIND_NAMES[kind]);
                rc = CLI_EXIT_FAIL;
                goto done;
            }
        biref_xyz_image_to_srgb8(xyz, npx, rgb);
        if ((rc = pe_ext_write_png(&ext, &ectx, rgb))) goto done;
        if (root) {
            cJSON_AddStringToObject(root, "output", out);
            cJSON_AddNumberToObject(root, "width", io.width);
            cJSON_AddNumberToObject(root, "height", io.height);
            cJSON_AddNumberToObject(root, "supersample", io.supersample);
            cJSON_AddNumberToObject(root, "ms", ms);
        } else if (!have_profile) {
            printf("wrote %s: %d x %d px, %d x %d samples per pixel, %.0f ms\n", out, io.width, io.height,
                   io.supersample, io.supersample, ms);
        }
    }

    if (root) {
        cJSON_AddStringToObject(root, "specimen", KIND_NAMES[kind]);
        cJSON_AddItemToObject(root, "material", material_json(&setup.material, lambda_N));
        cJSON_AddNumberToObject(root, "thickness_mm", h / mm);
        cJSON_AddNumberToObject(root, "eta_i", eta_i);
        cJSON_AddStringToObject(root, "polariscope", pk == BIREF_PE_PLANE ? "plane" : "circular");
        cJSON_AddStringToObject(root, "field", ft == BIREF_PE_DARK ? "dark" : "light");
        cJSON_AddNumberToObject(root, "polarizer_deg", polarizer_deg);
        cJSON_AddNumberToObject(root, "tilt_deg", tilt_deg);
        cJSON_AddStringToObject(root, "light", light == BIREF_PE_MONO ? "mono" : "white");
        if (light == BIREF_PE_MONO) cJSON_AddNumberToObject(root, "lambda_nm", lambda);
        cJSON_AddNumberToObject(root, "fringe_order_lambda_nm", lambda_N);
        if (light == BIREF_PE_WHITE)
            cJSON_AddStringToObject(root, "fringe_order_note",
                                    "white light has no single wavelength: N = retardation / 550 nm (mid-band)");
        double fr[4] = {field.frame[0] / mm, field.frame[1] / mm, field.frame[2] / mm, field.frame[3] / mm};
        cJSON_AddItemToObject(root, "frame_mm", cJSON_CreateDoubleArray(fr, 4));
    }
    if (have_profile) {
        cJSON *arr = root ? cJSON_AddArrayToObject(root, "profile") : NULL;
        if (!root) {
            printf("# profile from (%g, %g) to (%g, %g) mm, %s light%s; N = retardation / %g nm\n", profile[0],
                   profile[1], profile[2], profile[3], light == BIREF_PE_MONO ? "monochromatic" : "white",
                   light == BIREF_PE_MONO ? "" : " (intensity = luminance Y)", lambda_N);
            printf("# %10s %10s %6s %12s %12s %9s %14s %12s %10s\n", "x_mm", "y_mm", "inside", "sigma1_MPa",
                   "sigma2_MPa", "phi_deg", "retardation_nm", "fringe_order", "intensity");
        }
        const double bg = biref_pe_polariscope_background(&setup.pol) * exposure;
        for (long i = 0; i < samples; i++) {
            double t = (double)i / (double)(samples - 1);
            double x = profile[0] + t * (profile[2] - profile[0]), y = profile[1] + t * (profile[3] - profile[1]);
            biref_pe_stress s;
            int inside = biref_pe_field_stress(&field, x * mm, y * mm, &s);
            double col[3] = {bg, bg, bg};
            biref_pe_principal p = {0, 0, 0, 1, 0};
            double ret = 0;
            if (inside) {
                biref_pe_principal_of(&s, &p);
                if (io.tilt > 0.0) {
                    if (biref_pe_shade_oblique(&setup, sp, &p, io.tilt, col) != BIREF_OK)
                        col[0] = col[1] = col[2] = NAN;
                } else {
                    biref_pe_shade(&setup, sp, &p, col);
                }
                for (int j = 0; j < 3; j++) col[j] *= exposure;
                ret = io.tilt > 0.0 ? biref_pe_retardation_oblique_nm(&setup, &p, io.tilt)
                                    : biref_pe_retardation_nm(&setup, &p);
            }
            /* Mono: the grey level, shown through the tint; white: the luminance Y. */
            double intensity = col[1];
            if (light == BIREF_PE_MONO)
                for (int j = 0; j < 3; j++) col[j] *= tint_rgb[j];
            if (arr) {
                cJSON *o = cJSON_CreateObject();
                cJSON_AddNumberToObject(o, "x_mm", x);
                cJSON_AddNumberToObject(o, "y_mm", y);
                cJSON_AddBoolToObject(o, "inside", inside);
                if (inside) {
                    cJSON_AddNumberToObject(o, "sigma1_MPa", p.s1 / 1e6);
                    cJSON_AddNumberToObject(o, "sigma2_MPa", p.s2 / 1e6);
                    cJSON_AddNumberToObject(o, "phi_deg", p.phi * 180.0 / M_PI);
                    cJSON_AddNumberToObject(o, "retardation_nm", ret);
                    cJSON_AddNumberToObject(o, "fringe_order", ret / lambda_N);
                } else {
                    cJSON_AddNullToObject(o, "sigma1_MPa");
                    cJSON_AddNullToObject(o, "sigma2_MPa");
                    cJSON_AddNullToObject(o, "phi_deg");
                    cJSON_AddNullToObject(o, "retardation_nm");
                    cJSON_AddNullToObject(o, "fringe_order");
                }
                cJSON_AddNumberToObject(o, "intensity", intensity);
                cJSON_AddItemToObject(o, "xyz", cJSON_CreateDoubleArray(col, 3));
                unsigned char c8[3];
                biref_xyz_to_srgb8(col, c8);
                int ci[3] = {c8[0], c8[1], c8[2]};
                cJSON_AddItemToObject(o, "srgb8", cJSON_CreateIntArray(ci, 3));
                cJSON_AddItemToArray(arr, o);
            } else if (inside) {
                printf("  %10.4f %10.4f %6s %12.5g %12.5g %9.3f %14.3f %12.8f %10.8f\n", x, y, "yes", p.s1 / 1e6,
                       p.s2 / 1e6, p.phi * 180.0 / M_PI, ret, ret / lambda_N, intensity);
            } else {
                printf("  %10.4f %10.4f %6s %12s %12s %9s %14s %12s %10.8f\n", x, y, "no", "-", "-", "-", "-", "-",
                       intensity);
            }
        }
    }
    if (root) {
        if (json_print_and_free(root)) rc = CLI_EXIT_FAIL;
        root = NULL;
    }

done:
    cJSON_Delete(root);
    free(xyz);
    free(rgb);
    biref_spectral_destroy(sp);
    biref_pe_grid_destroy(grid);
    pe_ext_free(&ext);
    return rc;
}
