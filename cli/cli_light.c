#include "cli_light.h"

#include <math.h>
#include <string.h>

#include "cli_common.h"

void cli_light_default(cli_light *l)
{
    l->w_in[0] = l->w_in[1] = 0.5;
    l->mask[0] = l->mask[1] = 1.0;
}

int cli_parse_polarization(const char *cmd, const char *opt, const char *text, double w_in[2])
{
    if (!strcmp(text, "s")) {
        w_in[0] = 1.0, w_in[1] = 0.0;
        return 0;
    }
    if (!strcmp(text, "p")) {
        w_in[0] = 0.0, w_in[1] = 1.0;
        return 0;
    }
    if (!strcmp(text, "unpolarized")) {
        w_in[0] = w_in[1] = 0.5;
        return 0;
    }
    if (!strchr(text, ',')) {
        cli_error(cmd, "%s: expected s, p, unpolarized or S,P fractions, got '%s'", opt, text);
        return -1;
    }
    double w[2];
    if (cli_parse_list(cmd, opt, text, w, 2)) return -1;
    if (w[0] < 0.0 || w[1] < 0.0 || w[0] + w[1] <= 0.0) {
        cli_error(cmd, "%s: fractions must be non-negative and not both zero, got '%s'", opt, text);
        return -1;
    }
    /* Relative weights: the colour of the mix must not depend on how the user scales them.
     * Dividing by the larger weight first keeps the sum finite for weights near DBL_MAX. */
    const double big = fmax(w[0], w[1]), a = w[0] / big, b = w[1] / big;
    w_in[0] = a / (a + b);
    w_in[1] = b / (a + b);
    return 0;
}

int cli_parse_analyzer(const char *cmd, const char *opt, const char *text, double mask[2])
{
    if (!strcmp(text, "none"))
        mask[0] = 1.0, mask[1] = 1.0;
    else if (!strcmp(text, "s"))
        mask[0] = 1.0, mask[1] = 0.0;
    else if (!strcmp(text, "p"))
        mask[0] = 0.0, mask[1] = 1.0;
    else {
        cli_error(cmd, "%s: expected none, s or p, got '%s'", opt, text);
        return -1;
    }
    return 0;
}

const char *cli_polarization_name(const double w_in[2], char *buf, size_t len)
{
    if (w_in[0] == 1.0 && w_in[1] == 0.0) return "s";
    if (w_in[0] == 0.0 && w_in[1] == 1.0) return "p";
    if (w_in[0] == 0.5 && w_in[1] == 0.5) return "unpolarized";
    snprintf(buf, len, "%.6g,%.6g", w_in[0], w_in[1]);
    return buf;
}

const char *cli_analyzer_name(const double mask[2])
{
    if (mask[0] != 0.0 && mask[1] != 0.0) return "none";
    return mask[0] != 0.0 ? "s" : "p";
}

int cli_parse_range_nm(const char *cmd, const char *opt, const char *text, double range[2])
{
    double r[2];
    if (cli_parse_list(cmd, opt, text, r, 2)) return -1;
    if (r[0] <= 0.0 || r[1] <= r[0]) {
        cli_error(cmd, "%s: need 0 < MIN < MAX, got '%s'", opt, text);
        return -1;
    }
    range[0] = r[0];
    range[1] = r[1];
    return 0;
}

void cli_print_swatch(FILE *f, const double srgb[3])
{
    int c[3];
    for (int i = 0; i < 3; i++) {
        double v = srgb[i];
        if (!(v > 0.0)) v = 0.0; /* NaN too */
        if (v > 1.0) v = 1.0;
        c[i] = (int)lround(v * 255.0);
    }
    fprintf(f, "\033[48;2;%d;%d;%dm    \033[0m", c[0], c[1], c[2]);
}
