#include "cli_values.h"

#include <math.h>
#include <string.h>

#include "cli_common.h"

int cli_parse_linear_polarizer(const char *cmd, const char *opt, const char *text, double *deg)
{
    static const char prefix[] = "linear:";
    if (strncmp(text, prefix, sizeof prefix - 1) != 0) {
        cli_error(cmd, "%s: expected linear:DEG (a polariscope's polarizer is linear), got '%s'", opt, text);
        return -1;
    }
    if (cli_parse_double(cmd, opt, text + sizeof prefix - 1, deg)) return -1;
    *deg = fmod(*deg, 360.0); /* exact; 1e308 deg in radians would overflow */
    return 0;
}

int cli_check_coordinates_mm(const char *cmd, const char *opt, const char *text, const double *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!(fabs(v[i]) <= CLI_MAX_COORDINATE_MM)) {
            cli_error(cmd, "%s: coordinates are at most %g mm in magnitude, got '%s'", opt, CLI_MAX_COORDINATE_MM, text);
            return -1;
        }
    return 0;
}

int cli_parse_window(const char *cmd, const char *opt, const char *text, double frame[4])
{
    double c[4];
    if (cli_parse_list(cmd, opt, text, c, 4) || cli_check_coordinates_mm(cmd, opt, text, c, 4)) return -1;
    if (c[0] == c[2] || c[1] == c[3]) {
        cli_error(cmd, "%s: expected two opposite corners x0,y0,x1,y1 with x0 != x1 and y0 != y1, got '%s'", opt,
                  text);
        return -1;
    }
    frame[0] = fmin(c[0], c[2]);
    frame[1] = fmax(c[0], c[2]);
    frame[2] = fmin(c[1], c[3]);
    frame[3] = fmax(c[1], c[3]);
    return 0;
}

int cli_parse_antialias(const char *cmd, const char *text, int *prefilter)
{
    if (strcmp(text, "prefilter") && strcmp(text, "none")) {
        cli_error(cmd, "--antialias: expected prefilter or none, got '%s'", text);
        return -1;
    }
    *prefilter = !strcmp(text, "prefilter");
    return 0;
}
