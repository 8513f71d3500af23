/* biref: command-line front end. One sub-command per file (cmd_*.c). */
#include <stdio.h>
#include <string.h>

#include "cli_common.h"
#include "cli_mpi.h"
#include "cli_progress.h"
#include "commands.h"

static const struct {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
    const cli_command_spec *spec;
} commands[] = {
    {"slab", cmd_slab, "Jones matrices and power fractions of one slab at one wavelength", &CLI_SLAB},
    {"stack", cmd_stack, "Jones matrices and power fractions of a stack of layers at one wavelength", &CLI_STACK},
    {"material", cmd_material, "dispersive materials: the named list, indices and group indices at a wavelength",
     &CLI_MATERIAL},
    {"spectrum", cmd_spectrum, "colour (band integrals) of one slab: analytic, numeric or ground truth", &CLI_SPECTRUM},
    {"accuracy", cmd_accuracy, "accuracy study: analytic vs ground truth (docs/ACCURACY.md)", &CLI_ACCURACY},
    {"render", cmd_render, "render a scene file to PNG", &CLI_RENDER},
    {"diff", cmd_diff, "CIEDE2000 difference map and statistics of two PNG images", &CLI_DIFF},
    {"bench", cmd_bench, "time the spectral integration methods on a scene", &CLI_BENCH},
    {"figure", cmd_figure, "regenerate the paper's figures and table 1", &CLI_FIGURE},
    {"gl-data", cmd_gl_data, "the WebGL2 viewer's data: GLSL source, look-up table, scene presets", &CLI_GL_DATA},
    {"photoelastic", cmd_photoelastic, "a stressed plate in a plane or circular polariscope (photoelasticity)",
     &CLI_PHOTOELASTIC},
};
enum { N_COMMANDS = sizeof commands / sizeof commands[0] };

/* The option tables of docs/CLI.md, from the same tables that parse the options. */
static void markdown(FILE *f)
{
    const cli_command_spec *specs[N_COMMANDS + 3];
    size_t n = 0;
    for (size_t i = 0; i < N_COMMANDS; i++) {
        specs[n++] = commands[i].spec;
        if (commands[i].spec == &CLI_PHOTOELASTIC) {
            specs[n++] = &CLI_PHOTOELASTIC_DEMODULATE;
            specs[n++] = &CLI_PHOTOELASTIC_TFP;
            specs[n++] = &CLI_PHOTOELASTIC_CALIBRATE;
        }
    }
    fprintf(f, "## Options of each command\n\n");
    for (size_t i = 0; i < n; i++) cli_opts_markdown(specs[i], f);
    fprintf(f, "## Old spellings\n\n"
               "These spellings of the previous release are still accepted, with their old meaning, for\n"
               "one more release; new scripts should use the new ones.\n\n"
               "| Command | Old | New |\n|---|---|---|\n");
    for (size_t i = 0; i < n; i++) cli_opts_markdown_old(specs[i], f);
}

static void usage(FILE *f)
{
    fprintf(f, "usage: biref COMMAND [OPTIONS]\n\nBirefringence-induced iridescence of uniaxial slabs.\n\nCommands:\n");
    for (size_t i = 0; i < N_COMMANDS; i++)
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

/* The commands that share their work over the processes of an MPI job (cli_mpi.h). */
static int runs_distributed(const char *name)
{
    return !strcmp(name, "render") || !strcmp(name, "accuracy") || !strcmp(name, "figure");
}

static int run(int argc, char **argv);

int main(int argc, char **argv)
{
    cli_mpi_init(&argc, &argv);
    return cli_mpi_finish(run(argc, argv));
}

static int run(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!strcmp(argv[1], "help") && argc == 3 && !strcmp(argv[2], "--markdown")) {
        markdown(stdout);
        return 0;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(argv[1], "--version") || !strcmp(argv[1], "-V")) {
        printf("biref 0.1.0\n");
        return 0;
    }
    for (size_t i = 0; i < N_COMMANDS; i++)
        if (!strcmp(argv[1], commands[i].name)) {
            if (cli_mpi_active() && !runs_distributed(argv[1]))
                return cli_error(argv[1], "runs in one process: mpirun -n N is for render, accuracy and figure"), 2;
            /* --progress and --quiet mean the same for every command: taken here, once. */
            const int n = cli_progress_options(argc - 1, argv + 1);
            return n < 0 ? 2 : commands[i].run(n, argv + 1);
        }
    fprintf(stderr, "biref: error: unknown command '%s' (see biref --help)\n", argv[1]);
    return 2;
}
