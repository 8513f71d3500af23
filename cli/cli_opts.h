/* One option layer for every command: a table of option specs drives the parsing (getopt_long),
 * the --help text and the option tables of docs/CLI.md (biref help --markdown). */
#ifndef BIREF_CLI_OPTS_H
#define BIREF_CLI_OPTS_H

#include <stddef.h>
#include <stdio.h>

typedef enum {
    CLI_OPT_FLAG,   /* no value: sets an int to 1 */
    CLI_OPT_STRING, /* keeps the text (const char *) */
    CLI_OPT_INT,    /* long in [lo, hi] */
    CLI_OPT_DOUBLE, /* finite double, in [lo, hi] when lo < hi */
    CLI_OPT_CUSTOM, /* the command's handler parses the value (or the flag) */
    CLI_OPT_TEXT    /* not an option: a heading or a paragraph of --help, printed as it is */
} cli_opt_kind;

typedef struct {
    const char *name;   /* long name without "--"; for CLI_OPT_TEXT, the text */
    char short_name;    /* 'o', 'q' or 0 */
    cli_opt_kind kind;
    const char *value;  /* what the value looks like in --help ("FILE"); NULL: a flag */
    const char *help;   /* one line, or several separated by '\n' */
    size_t offset;      /* where typed kinds store the value in the command's argument struct */
    double lo, hi;      /* range of CLI_OPT_INT and CLI_OPT_DOUBLE */
    int code;           /* passed to the handler for CLI_OPT_CUSTOM */
    const char *old_of; /* non-NULL: an old spelling of the option of this name, still accepted;
                         * its help is then what to write now (default "--" old_of) */
} cli_opt;

typedef struct cli_command_spec {
    const char *name;     /* "render", "photoelastic demodulate" */
    const char *synopsis; /* usage line(s) and description, printed before the options */
    const cli_opt *opts;
    size_t n_opts;
    const char *epilog;   /* printed after the options (exit status, examples); may be NULL */
    int column;           /* column of the help texts (default 23) */
    /* Parses a CLI_OPT_CUSTOM value; returns 0, or -1 after printing one error. */
    int (*handle)(void *args, int code, const char *arg);
    /* 1: a long job that reports progress on stderr; --help and docs/CLI.md then list the
     * --progress and -q/--quiet that main takes out of every command line (cli_progress.h). */
    int progress;
    /* Options that exclude each other: NULL-terminated, each entry the long names of one group
     * separated by spaces ("polarizer stokes polarization"); at most one of a group may be given. */
    const char *const *exclusive;
} cli_command_spec;

enum { CLI_MAX_OPTS = 96 };

/* What cli_opts_parse found besides the values it stored. */
typedef struct {
    int first_arg;                   /* argv index of the first positional argument */
    int n_args;                      /* positional arguments */
    unsigned char given[CLI_MAX_OPTS]; /* given[i]: option i of the table (or an old spelling of it) */
} cli_parsed;

/* Parses argv[1..argc-1] (argv[0] is the command's name). Returns 0, 1 after printing --help
 * (exit 0), or -1 after printing one error line (bad usage). Long names must be given whole (no
 * abbreviations); an option given twice (also under an old spelling) and two options of one
 * exclusive group are errors (docs/CLI.md, "Grammar"). */
int cli_opts_parse(const cli_command_spec *c, void *args, int argc, char **argv, cli_parsed *p);
/* 1 if the option with this long name (or one of its old spellings) was given. */
int cli_opts_given(const cli_command_spec *c, const cli_parsed *p, const char *name);
/* The --help text of a command. */
void cli_opts_help(const cli_command_spec *c, FILE *f);
/* The command's options as a Markdown table (docs/CLI.md). */
void cli_opts_markdown(const cli_command_spec *c, FILE *f);
/* The old spellings of the command as Markdown table rows "| command | old | new |". */
void cli_opts_markdown_old(const cli_command_spec *c, FILE *f);

#define CLI_OPTS_COUNT(a) (sizeof(a) / sizeof((a)[0]))

/* Table entries. OFF is offsetof(the command's argument struct, field). */
#define CLI_FLAG(NAME, SHORT, OFF, HELP) {.name = NAME, .short_name = SHORT, .kind = CLI_OPT_FLAG, .offset = OFF, .help = HELP}
#define CLI_STRING(NAME, SHORT, VALUE, OFF, HELP) \
    {.name = NAME, .short_name = SHORT, .kind = CLI_OPT_STRING, .value = VALUE, .offset = OFF, .help = HELP}
#define CLI_INT(NAME, VALUE, OFF, LO, HI, HELP) \
    {.name = NAME, .kind = CLI_OPT_INT, .value = VALUE, .offset = OFF, .lo = LO, .hi = HI, .help = HELP}
#define CLI_DOUBLE(NAME, VALUE, OFF, LO, HI, HELP) \
    {.name = NAME, .kind = CLI_OPT_DOUBLE, .value = VALUE, .offset = OFF, .lo = LO, .hi = HI, .help = HELP}
/* VALUE NULL: a flag handled by the command. */
#define CLI_CUSTOM(NAME, VALUE, CODE, HELP) {.name = NAME, .kind = CLI_OPT_CUSTOM, .value = VALUE, .code = CODE, .help = HELP}
/* An old spelling handled by the command; NOW is what to write instead. */
#define CLI_OLD(NAME, VALUE, CODE, OLD_OF, NOW) \
    {.name = NAME, .kind = CLI_OPT_CUSTOM, .value = VALUE, .code = CODE, .old_of = OLD_OF, .help = NOW}
#define CLI_TEXT(TEXT) {.name = TEXT, .kind = CLI_OPT_TEXT}

#endif
