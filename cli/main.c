/* biref: command-line front end. One sub-command per file (cmd_*.c). */
#include <stdio.h>
#include <string.h>

#include "cli_progress.h"
#include "commands.h"

static const struct {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} commands[] = {
    {"slab", cmd_slab, "Jones matrices and power fractions of one slab at one wavelength"},
    {"spectrum", cmd_spectrum, "colour (band integrals) of one slab: analytic, numeric or ground truth"},
    {"accuracy", cmd_accuracy, "accuracy study: analytic vs ground truth (docs/ACCURACY.md)"},
    {"render", cmd_render, "render a scene file to PNG"},
    {"diff", cmd_diff, "CIEDE2000 difference map and statistics of two PNG images"},
    {"bench", cmd_bench, "time the spectral integration methods on a scene"},
    {"figure", cmd_figure, "regenerate the paper's figures and table 1"},
    {"gl-data", cmd_gl_data, "the WebGL2 viewer's data: GLSL source, look-up table, scene presets"},
    {"photoelastic", cmd_photoelastic, "a stressed plate in a plane or circular polariscope (photoelasticity)"},
};

static void usage(FILE *f)
{
    fprintf(f, "usage: biref COMMAND [OPTIONS]\n\nBirefringence-induced iridescence of uniaxial slabs.\n\nCommands:\n");
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        fprintf(f, "  %-12s %s\n", commands[i].name, commands[i].summary);
    fprintf(f, "\nOptions:\n"
               "  -h, --help     this list\n"
               "  -V, --version  the version of biref\n"
               "\nEvery command also takes --progress (progress on stderr from the start) and -q, --quiet\n"
               "(none); by default a long job shows a bar on a terminal, otherwise a line every few\n"
               "seconds once it has run 2 s.\n"
               "\nRun 'biref COMMAND --help' for the options of a command; the grammar they share is in\n"
               "docs/CLI.md.\n");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(argv[1], "--version") || !strcmp(argv[1], "-V")) {
        printf("biref 0.1.0\n");
        return 0;
    }
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (!strcmp(argv[1], commands[i].name)) {
            /* --progress and --quiet mean the same for every command: taken here, once. */
            const int n = cli_progress_options(argc - 1, argv + 1);
            return commands[i].run(n, argv + 1);
        }
    fprintf(stderr, "biref: error: unknown command '%s' (see biref --help)\n", argv[1]);
    return 2;
}
