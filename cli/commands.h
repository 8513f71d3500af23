/* Entry points of the sub-commands; each receives argv starting at the command name. Their
 * option tables (cli_opts.h) give --help and the option tables of docs/CLI.md. */
#ifndef BIREF_CLI_COMMANDS_H
#define BIREF_CLI_COMMANDS_H

#include "cli_opts.h"

int cmd_slab(int argc, char **argv);
int cmd_stack(int argc, char **argv);
int cmd_spectrum(int argc, char **argv);
int cmd_accuracy(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_diff(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_figure(int argc, char **argv);
int cmd_photoelastic(int argc, char **argv);
int cmd_gl_data(int argc, char **argv);
int cmd_material(int argc, char **argv);

extern const cli_command_spec CLI_SLAB, CLI_STACK, CLI_SPECTRUM, CLI_ACCURACY, CLI_RENDER, CLI_DIFF, CLI_BENCH,
    CLI_FIGURE, CLI_PHOTOELASTIC, CLI_PHOTOELASTIC_DEMODULATE, CLI_PHOTOELASTIC_TFP, CLI_PHOTOELASTIC_CALIBRATE,
    CLI_GL_DATA, CLI_MATERIAL;

#endif
