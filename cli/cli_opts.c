#include "cli_opts.h"

#include <getopt.h>
#include <string.h>

#include "cli_common.h"

enum { CODE_BASE = 1000, CODE_HELP = 999 };

/* Taken out of the command line by main before the command parses it (cli_progress_options). */
static const cli_opt PROGRESS_OPTS[] = {
    CLI_FLAG("progress", 0, 0, "progress from the start, also when stderr is not a terminal"),
    CLI_FLAG("quiet", 'q', 0,
             "no progress on stderr (default: a bar on a terminal, otherwise a\n"
             "line every few seconds once the job has run 2 s)"),
};

/* The table entry an old spelling stands for (itself for a current name). */
static size_t current_index(const cli_command_spec *c, size_t i)
{
    if (!c->opts[i].old_of) return i;
    for (size_t j = 0; j < c->n_opts; j++)
        if (c->opts[j].kind != CLI_OPT_TEXT && !c->opts[j].old_of && !strcmp(c->opts[j].name, c->opts[i].old_of))
            return j;
    return i;
}

static int store(const cli_command_spec *c, const cli_opt *o, void *args, const char *arg)
{
    char name[80];
    snprintf(name, sizeof name, "--%s", o->name);
    char *field = (char *)args + o->offset;
    switch (o->kind) {
    case CLI_OPT_FLAG: *(int *)field = 1; return 0;
    case CLI_OPT_STRING: *(const char **)field = arg; return 0;
    case CLI_OPT_INT: return cli_parse_int(c->name, name, arg, (long)o->lo, (long)o->hi, (long *)field);
    case CLI_OPT_DOUBLE: {
        double v;
        if (cli_parse_double(c->name, name, arg, &v)) return -1;
        if (o->lo < o->hi && !(v >= o->lo && v <= o->hi)) {
            cli_error(c->name, "%s: must be between %g and %g, got %g", name, o->lo, o->hi, v);
            return -1;
        }
        *(double *)field = v;
        return 0;
    }
    case CLI_OPT_CUSTOM: return c->handle(args, o->code, arg);
    default: return 0;
    }
}

int cli_opts_parse(const cli_command_spec *c, void *args, int argc, char **argv, cli_parsed *p)
{
    struct option longopts[CLI_MAX_OPTS + 2];
    char shortopts[2 * CLI_MAX_OPTS + 4] = ":h";
    size_t nl = 0, ns = 2;
    memset(p, 0, sizeof *p);
    for (size_t i = 0; i < c->n_opts && i < CLI_MAX_OPTS; i++) {
        const cli_opt *o = &c->opts[i];
        if (o->kind == CLI_OPT_TEXT) continue;
        int has_arg = o->value ? required_argument : no_argument;
        longopts[nl++] = (struct option){o->name, has_arg, 0, CODE_BASE + (int)i};
        if (o->short_name) {
            shortopts[ns++] = o->short_name;
            if (o->value) shortopts[ns++] = ':';
        }
    }
    longopts[nl++] = (struct option){"help", no_argument, 0, CODE_HELP};
    longopts[nl] = (struct option){0, 0, 0, 0};
    shortopts[ns] = '\0';
    opterr = 0;
    optind = 1;
    int ch;
    while ((ch = getopt_long(argc, argv, shortopts, longopts, NULL)) != -1) {
        if (ch == 'h' || ch == CODE_HELP) {
            cli_opts_help(c, stdout);
            return 1;
        }
        size_t i = c->n_opts;
        if (ch >= CODE_BASE) {
            i = (size_t)(ch - CODE_BASE);
        } else {
            for (size_t j = 0; j < c->n_opts; j++)
                if (c->opts[j].kind != CLI_OPT_TEXT && c->opts[j].short_name && c->opts[j].short_name == ch) i = j;
        }
        if (i >= c->n_opts) {
            cli_getopt_error(c->name, ch, argv);
            return -1;
        }
        if (store(c, &c->opts[i], args, optarg)) return -1;
        p->given[current_index(c, i)] = 1;
    }
    p->first_arg = optind;
    p->n_args = argc - optind;
    return 0;
}

int cli_opts_given(const cli_command_spec *c, const cli_parsed *p, const char *name)
{
    for (size_t i = 0; i < c->n_opts && i < CLI_MAX_OPTS; i++)
        if (c->opts[i].kind != CLI_OPT_TEXT && !c->opts[i].old_of && !strcmp(c->opts[i].name, name)) return p->given[i];
    return 0;
}

/* "-o, --output FILE" or "--json". */
static void option_label(const cli_opt *o, char *buf, size_t size)
{
    char sh[8] = "";
    if (o->short_name) snprintf(sh, sizeof sh, "-%c, ", o->short_name);
    snprintf(buf, size, "%s--%s%s%s", sh, o->name, o->value ? " " : "", o->value ? o->value : "");
}

static void help_entry(const cli_opt *o, int column, FILE *f)
{
    char label[160];
    option_label(o, label, sizeof label);
    int w = fprintf(f, "  %s", label);
    if (w >= column) { /* a long option: its help starts on the next line */
        fputc('\n', f);
        w = 0;
    }
    for (const char *h = o->help ? o->help : "";;) {
        const char *nl = strchr(h, '\n');
        int len = nl ? (int)(nl - h) : (int)strlen(h);
        fprintf(f, "%*s%.*s\n", column - w, "", len, h);
        w = 0;
        if (!nl) break;
        h = nl + 1;
    }
}

/* What an old spelling became: its help text, or the current option with the same value. */
static const char *replacement(const cli_opt *o, char *buf, size_t size)
{
    if (o->help) return o->help;
    snprintf(buf, size, "--%s%s%s", o->old_of, o->value ? " " : "", o->value ? o->value : "");
    return buf;
}

void cli_opts_help(const cli_command_spec *c, FILE *f)
{
    const int column = c->column ? c->column : 23;
    fputs(c->synopsis, f);
    int any_old = 0;
    for (size_t i = 0; i < c->n_opts; i++) {
        const cli_opt *o = &c->opts[i];
        if (o->kind == CLI_OPT_TEXT)
            fputs(o->name, f);
        else if (o->old_of)
            any_old = 1;
        else
            help_entry(o, column, f);
    }
    for (size_t i = 0; i < (c->progress ? CLI_OPTS_COUNT(PROGRESS_OPTS) : 0); i++) help_entry(&PROGRESS_OPTS[i], column, f);
    const cli_opt help = CLI_FLAG("help", 'h', 0, "this help");
    help_entry(&help, column, f);
    if (any_old) {
        fputs("\nOld spellings, accepted for one more release:\n", f);
        for (size_t i = 0; i < c->n_opts; i++) {
            const cli_opt *o = &c->opts[i];
            if (o->kind == CLI_OPT_TEXT || !o->old_of) continue;
            char now[160], buf[96];
            snprintf(now, sizeof now, "now %s", replacement(o, buf, sizeof buf));
            cli_opt shown = *o;
            shown.help = now;
            help_entry(&shown, column, f);
        }
    }
    fputc('\n', f);
    if (c->epilog) fputs(c->epilog, f);
}

/* Markdown table cell: the help text on one line, '|' escaped. */
static void markdown_cell(const char *s, FILE *f)
{
    int space = 0;
    for (; *s; s++) {
        if (*s == '\n' || *s == ' ') {
            space = 1;
            continue;
        }
        if (space) fputc(' ', f);
        space = 0;
        if (*s == '|') fputc('\\', f);
        fputc(*s, f);
    }
}

void cli_opts_markdown(const cli_command_spec *c, FILE *f)
{
    fprintf(f, "### biref %s\n\n| Option | Meaning |\n|---|---|\n", c->name);
    for (size_t i = 0; i < c->n_opts; i++) {
        const cli_opt *o = &c->opts[i];
        if (o->kind == CLI_OPT_TEXT || o->old_of) continue;
        char label[160];
        option_label(o, label, sizeof label);
        fputs("| `", f);
        markdown_cell(label, f);
        fputs("` | ", f);
        markdown_cell(o->help, f);
        fputs(" |\n", f);
    }
    for (size_t i = 0; i < (c->progress ? CLI_OPTS_COUNT(PROGRESS_OPTS) : 0); i++) {
        char label[160];
        option_label(&PROGRESS_OPTS[i], label, sizeof label);
        fprintf(f, "| `%s` | ", label);
        markdown_cell(PROGRESS_OPTS[i].help, f);
        fputs(" |\n", f);
    }
    fputs("| `-h, --help` | this help |\n\n", f);
}

void cli_opts_markdown_old(const cli_command_spec *c, FILE *f)
{
    for (size_t i = 0; i < c->n_opts; i++) {
        const cli_opt *o = &c->opts[i];
        if (o->kind == CLI_OPT_TEXT || !o->old_of) continue;
        char label[160], buf[96];
        option_label(o, label, sizeof label);
        fprintf(f, "| %s | `%s` | `%s` |\n", c->name, label, replacement(o, buf, sizeof buf));
    }
}
