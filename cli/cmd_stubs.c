/* Weak placeholders so that the CLI links while sub-commands are being written in parallel;
 * each cmd_*.c provides the strong definition. Remove an entry once its command exists. */
#include <stdio.h>

#include "commands.h"

static int not_built(const char *name)
{
    fprintf(stderr, "biref %s: error: this command is not available in this build\n", name);
    return 1;
}

__attribute__((weak)) int cmd_spectrum(int argc, char **argv) { return not_built("spectrum"); }
__attribute__((weak)) int cmd_accuracy(int argc, char **argv) { return not_built("accuracy"); }
__attribute__((weak)) int cmd_render(int argc, char **argv) { return not_built("render"); }
__attribute__((weak)) int cmd_diff(int argc, char **argv) { return not_built("diff"); }
__attribute__((weak)) int cmd_bench(int argc, char **argv) { return not_built("bench"); }
__attribute__((weak)) int cmd_figure(int argc, char **argv) { return not_built("figure"); }
