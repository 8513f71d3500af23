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

/* 1 if NAME is one of the space-separated words of GROUP. */
static int in_group(const char *group, const char *name)
{
    const size_t n = strlen(name);
    for (const char *g = group; *g;) {
        const char *end = strchr(g, ' ');
        size_t len = end ? (size_t)(end - g) : strlen(g);
        if (len == n && !strncmp(g, name, n)) return 1;
        if (!end) break;
        g = end + 1;
    }
    return 0;
}

/* An option given twice, or with another of its exclusive group: one error. Returns -1 then. */
static int check_repeat(const cli_command_spec *c, const unsigned char *given, size_t i)
{
    const char *name = c->opts[i].name;
    if (given[i]) {
        char sh[8] = "";
        if (c->opts[i].short_name) snprintf(sh, sizeof sh, "-%c/", c->opts[i].short_name);
        return cli_error(c->name, "%s--%s given twice (see biref %s --help)", sh, name, c->name), -1;
    }
    for (const char *const *g = c->exclusive; g && *g; g++) {
        if (!in_group(*g, name)) continue;
        for (size_t j = 0; j < c->n_opts && j < CLI_MAX_OPTS; j++)
            if (j != i && given[j] && in_group(*g, c->opts[j].name))
                return cli_error(c->name, "--%s and --%s exclude each other", c->opts[j].name, name), -1;
    }
    return 0;
}

/* The text of the long option getopt_long just returned ("--name" or "--name=value"), which
 * must spell the name whole: getopt_long would take any unambiguous prefix. */
static int whole_name(const cli_command_spec *c, char **argv, const char *name)
{
    const char *text = optarg && optind >= 2 && optarg == argv[optind - 1] ? argv[optind - 2] : argv[optind - 1];
    if (strncmp(text, "--", 2)) return 0;
    const char *eq = strchr(text + 2, '=');
    size_t len = eq ? (size_t)(eq - text - 2) : strlen(text + 2);
    if (len == strlen(name) && !strncmp(text + 2, name, len)) return 0;
    cli_error(c->name, "unknown option '%.*s' (did you mean --%s? see biref %s --help)", (int)len + 2, text, name,
              c->name);
    return -1;
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
    /* Two passes: the structure of the command line first (unknown, abbreviated, repeated and
     * excluding options, --help), then the values, so that a repeated option is reported as such
     * whatever its values. optind = 0 makes getopt_long start afresh (GNU). */
    for (int pass = 0; pass < 2; pass++) {
        unsigned char seen[CLI_MAX_OPTS] = {0};
        optind = 0;
        int ch;
        while ((ch = getopt_long(argc, argv, shortopts, longopts, NULL)) != -1) {
            if (pass == 0 && (ch == CODE_HELP || ch >= CODE_BASE) &&
                whole_name(c, argv, ch == CODE_HELP ? "help" : c->opts[ch - CODE_BASE].name))
                return -1;
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
            const size_t cur = current_index(c, i);
            if (pass == 0 && check_repeat(c, seen, cur)) return -1;
            if (pass == 1 && store(c, &c->opts[i], args, optarg)) return -1;
            seen[cur] = 1;
        }
        memcpy(p->given, seen, sizeof seen);
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
