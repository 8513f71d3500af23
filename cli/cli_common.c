#include "cli_common.h"
#include "cli_mpi.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

void cli_error(const char *cmd, const char *fmt, ...)
{
    /* One line, also kept for the other processes of an MPI job (cli_mpi.h). */
    char line[8192];
    int n = snprintf(line, sizeof line, "biref %s: error: ", cmd);
    va_list ap;
    va_start(ap, fmt);
    if (n >= 0 && (size_t)n < sizeof line) vsnprintf(line + n, sizeof line - (size_t)n, fmt, ap);
    va_end(ap);
    fprintf(stderr, "%s\n", line);
    cli_mpi_note_error(line);
}

/* The length of the decimal number at the start of s: [+-]digits[.digits][(e|E)[+-]digits], at
 * least one digit before the exponent; 0 if none. strtod alone would also take leading blanks,
 * hexadecimal ("0x10"), "inf" and "nan" (docs/CLI.md, "Numbers"). */
static size_t decimal_length(const char *s, int integer)
{
    size_t i = 0, digits = 0;
    if (s[i] == '+' || s[i] == '-') i++;
    while (s[i] >= '0' && s[i] <= '9') i++, digits++;
    if (integer) return digits ? i : 0;
    if (s[i] == '.') {
        i++;
        while (s[i] >= '0' && s[i] <= '9') i++, digits++;
    }
    if (!digits) return 0;
    if (s[i] == 'e' || s[i] == 'E') {
        size_t j = i + 1, e = 0;
        if (s[j] == '+' || s[j] == '-') j++;
        while (s[j] >= '0' && s[j] <= '9') j++, e++;
        if (e) i = j;
    }
    return i;
}

int cli_number_syntax_ok(const char *text, int integer)
{
    size_t n = decimal_length(text, integer);
    return n > 0 && text[n] == '\0';
}

int cli_parse_double(const char *cmd, const char *opt, const char *text, double *out)
{
    char *end = NULL;
    errno = 0;
    double v = strtod(text, &end);
    if (!cli_number_syntax_ok(text, 0) || end == text || *end != '\0' || errno == ERANGE || !isfinite(v)) {
        cli_error(cmd, "%s: expected a finite decimal number, got '%s'", opt, text);
        return -1;
    }
    *out = v;
    return 0;
}

int cli_parse_int(const char *cmd, const char *opt, const char *text, long lo, long hi, long *out)
{
    char *end = NULL;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (!cli_number_syntax_ok(text, 1) || end == text || *end != '\0' || errno == ERANGE) {
        cli_error(cmd, "%s: expected an integer, got '%s'", opt, text);
        return -1;
    }
    if (v < lo || v > hi) {
        cli_error(cmd, "%s: must be between %ld and %ld, got %ld", opt, lo, hi, v);
        return -1;
    }
    *out = v;
    return 0;
}

int cli_parse_list(const char *cmd, const char *opt, const char *text, double *out, int n)
{
    char buf[256];
    if (strlen(text) >= sizeof buf) {
        cli_error(cmd, "%s: value too long", opt);
        return -1;
    }
    strcpy(buf, text);
    int count = 0;
    char *save = NULL;
    for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (count == n) break;
        char *end = NULL;
        errno = 0;
        double v = strtod(tok, &end);
        if (!cli_number_syntax_ok(tok, 0) || end == tok || *end != '\0' || errno == ERANGE || !isfinite(v)) {
            cli_error(cmd, "%s: expected %d comma-separated finite decimal numbers, got '%s'", opt, n, text);
            return -1;
        }
        out[count++] = v;
    }
    /* Reject "1,2", "1,2,3,4" and empty fields such as "1,,2". */
    int commas = 0;
    for (const char *c = text; *c; c++) commas += *c == ',';
    if (count != n || commas != n - 1) {
        cli_error(cmd, "%s: expected %d comma-separated finite numbers, got '%s'", opt, n, text);
        return -1;
    }
    return 0;
}

void cli_slab_opts_init(cli_slab_opts *o)
{
    memset(o, 0, sizeof *o);
    o->slab.eta_i = 1.0;
}

int cli_slab_opts_handle(const char *cmd, cli_slab_opts *o, int code, const char *arg)
{
    double v;
    switch (code) {
    case OPT_ETA_O:
    case OPT_ETA_E: {
        const int e = code == OPT_ETA_E;
        const char *name = e ? "--eta-e" : "--eta-o";
        if (o->index_source[e])
            return cli_error(cmd, "%s: %s already given by %s", name, e ? "n_e" : "n_o", o->index_source[e]), -1;
        o->index_source[e] = name;
        *(e ? &o->have_eta_e : &o->have_eta_o) = 1;
        return cli_parse_double(cmd, name, arg, e ? &o->slab.eta_e : &o->slab.eta_o) ? -1 : 1;
    }
    case OPT_ETA_I: return cli_parse_double(cmd, "--eta-i", arg, &o->slab.eta_i) ? -1 : 1;
    case OPT_AXIS:
        o->have_axis = 1;
        return cli_parse_list(cmd, "--axis", arg, o->slab.axis, 3) ? -1 : 1;
    case OPT_THICKNESS_UM:
    case OPT_THICKNESS_MM:
    case OPT_THICKNESS_NM: {
        const char *name = code == OPT_THICKNESS_UM ? "--thickness-um"
                           : code == OPT_THICKNESS_MM ? "--thickness-mm" : "--thickness-nm";
        if (o->have_thickness) {
            cli_error(cmd, "%s: thickness given twice", name);
            return -1;
        }
        if (cli_parse_double(cmd, name, arg, &v)) return -1;
        o->have_thickness = 1;
        o->slab.thickness_nm = v * (code == OPT_THICKNESS_UM ? 1e3 : code == OPT_THICKNESS_MM ? 1e6 : 1.0);
        return 1;
    }
    case OPT_THETA_DEG:
        o->have_theta = 1;
        return cli_parse_double(cmd, "--theta-deg", arg, &o->theta_deg) ? -1 : 1;
    default: return cli_dispersion_handle(cmd, o, code, arg);
    }
}

void cli_slab_opts_free(cli_slab_opts *o)
{
    biref_material_destroy(o->owned_material);
    o->owned_material = NULL;
    o->material = NULL;
}

int cli_slab_opts_finish(const char *cmd, cli_slab_opts *o)
{
    if (cli_dispersion_finish(cmd, o)) return -1;
    if (!o->index_source[0]) return cli_error(cmd, "missing --eta-o (or --material)"), -1;
    if (!o->index_source[1]) return cli_error(cmd, "missing --eta-e (or --material)"), -1;
    if (!o->have_axis) return cli_error(cmd, "missing --axis"), -1;
    if (!o->have_thickness) return cli_error(cmd, "missing --thickness-um (or --thickness-mm, --thickness-nm)"), -1;
    char msg[200];
    if (biref_slab_check(&o->slab, msg, sizeof msg) != BIREF_OK) return cli_error(cmd, "%s", msg), -1;
    if (biref_theta_check(o->theta_deg * M_PI / 180.0, msg, sizeof msg) != BIREF_OK)
        return cli_error(cmd, "--theta-deg: %s", msg), -1;
    biref_axis_normalize(o->slab.axis, o->slab.axis); /* checked by biref_slab_check */
    return 0;
}

void cli_getopt_error(const char *cmd, int code, char *const argv[])
{
    const char *opt = argv[optind - 1];
    if (code == ':')
        cli_error(cmd, "option '%s' needs a value (see biref %s --help)", opt, cmd);
    else
        cli_error(cmd, "unknown option '%s' (see biref %s --help)", opt, cmd);
}

void cli_print_jones_table(const char *title, const biref_jones *J, double P[2][2])
{
    static const char *const sp[2] = {"s", "p"};
    printf("%s   (rows: input, columns: output)\n", title);
    printf("  %-3s %-28s %-28s\n", "", "s", "p");
    for (int i = 0; i < 2; i++) {
        printf("  %-3s", sp[i]);
        for (int j = 0; j < 2; j++) {
            char cell[64];
            snprintf(cell, sizeof cell, "%.6f (%+.4f%+.4fi)", P[i][j], creal(J->m[i][j]), cimag(J->m[i][j]));
            printf(" %-28s", cell);
        }
        printf("\n");
    }
}

int cli_cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}
