/* Built instead of the plotting code when biref is configured with BIREF_WITH_PLOTS=OFF (no cairo
 * or PLplot): `biref figure` and `biref accuracy --plot-dir` say so instead of drawing. */
#include <stdio.h>

#include "cli_common.h"
#include "commands.h"
#include "plot.h"

static const char WHY[] = "this biref was built without plots (BIREF_WITH_PLOTS=OFF: no cairo/PLplot)";

/* No options: biref help --markdown then lists none for figure. */
const cli_command_spec CLI_FIGURE = {"figure", "usage: biref figure (not in this build)\n", NULL, 0, NULL, 0, NULL, 0};

int cmd_figure(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    cli_error("figure", "%s", WHY);
    return CLI_EXIT_FAIL;
}

int acc_plot_vs_cost(const char *path, const acc_plot_cost_point *p, int n, const char *note)
{
    (void)p, (void)n, (void)note;
    fprintf(stderr, "%s: %s\n", path, WHY);
    return -1;
}

int acc_plot_vs_theta(const char *path, const acc_plot_theta_data *d)
{
    (void)d;
    fprintf(stderr, "%s: %s\n", path, WHY);
    return -1;
}
