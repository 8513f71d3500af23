/* Entry points of the sub-commands; each receives argv starting at the command name. */
#ifndef BIREF_CLI_COMMANDS_H
#define BIREF_CLI_COMMANDS_H

int cmd_slab(int argc, char **argv);
int cmd_spectrum(int argc, char **argv);
int cmd_accuracy(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_diff(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_figure(int argc, char **argv);
int cmd_photoelastic(int argc, char **argv);
int cmd_gl_data(int argc, char **argv);

#endif
