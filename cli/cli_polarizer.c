#include "cli_polarizer.h"

#include <math.h>
#include <string.h>

#include "biref/biref.h"
#include "cli_common.h"

int cli_parse_polarizer_state(const char *cmd, const char *opt, const char *text, double S[4])
{
    biref_polarizer p;
    char why[BIREF_MSG_SIZE];
    if (biref_polarizer_parse(text, &p, why, sizeof why) != BIREF_OK) {
        cli_error(cmd, "%s: %s", opt, why);
        return -1;
    }
    memcpy(S, p.stokes, sizeof p.stokes);
    return 0;
}

int cli_parse_stokes(const char *cmd, const char *opt, const char *text, double S[4])
{
    if (cli_parse_list(cmd, opt, text, S, 4)) return -1;
    if (!isfinite(fabs(S[0]) + fabs(S[1])) || !isfinite(fabs(S[2]) + fabs(S[3]))) {
        cli_error(cmd, "%s: too large: S0 + S1 and S2 + S3 must stay finite (the scale only sets the brightness)", opt);
        return -1;
    }
    double complex C[2][2];
    if (biref_stokes_to_coherency(S, C) != BIREF_OK) {
        cli_error(cmd, "%s: not a physical Stokes vector (need S0 >= 0 and S1^2+S2^2+S3^2 <= S0^2)", opt);
        return -1;
    }
    return 0;
}

int cli_parse_general_analyzer(const char *cmd, const char *opt, const char *text, double complex P[2][2])
{
    if (strncmp(text, "linear:", 7) && strncmp(text, "circular:", 9)) return 0;
    biref_polarizer p;
    char why[BIREF_MSG_SIZE];
    if (biref_polarizer_parse(text, &p, why, sizeof why) != BIREF_OK) {
        cli_error(cmd, "%s: %s", opt, why);
        return -1;
    }
    memcpy(P, p.analyzer, sizeof p.analyzer);
    return 1;
}

int cli_parse_expansion_order(const char *cmd, const char *text, biref_expansion_opts *o)
{
    long v;
    if (cli_parse_int(cmd, "--order", text, 0, BIREF_EXPANSION_MAX_ORDER, &v)) return -1;
    o->order = (int)v;
    return 0;
}

int cli_parse_expansion_tolerance(const char *cmd, const char *text, biref_expansion_opts *o)
{
    double t;
    if (cli_parse_double(cmd, "--tolerance", text, &t)) return -1;
    if (!(t > 0.0 && t < 1.0)) {
        cli_error(cmd, "--tolerance: must be in (0, 1), got %g", t);
        return -1;
    }
    o->tolerance = t;
    return 0;
}
