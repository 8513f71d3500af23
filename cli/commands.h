/* Entry points of the sub-commands; each receives argv starting at the command name. */
#ifndef BIREF_CLI_COMMANDS_H
#define BIREF_CLI_COMMANDS_H

int cmd_slab(int argc, char **argv);

#endif
