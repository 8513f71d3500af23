#include "cli_files.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "cli_common.h"
#include "cli_render.h"
#include "same_file.h"

void cli_files_init(cli_files *f) { memset(f, 0, sizeof *f); }

void cli_files_free(cli_files *f)
{
    for (int i = 0; i < f->n_in; i++) free(f->in[i].path), free(f->in[i].what);
    for (int i = 0; i < f->n_out; i++) free(f->out[i].path), free(f->out[i].what);
    free(f->in);
    free(f->out);
    memset(f, 0, sizeof *f);
}

static void add(cli_files *f, int output, const char *what, const char *format, char *path, int in_new_dir)
{
    cli_file **list = output ? &f->out : &f->in;
    int *n = output ? &f->n_out : &f->n_in, *cap = output ? &f->cap_out : &f->cap_in;
    char *w = strdup(what);
    if (*n == *cap) {
        int c = *cap ? 2 * *cap : 8;
        cli_file *grown = realloc(*list, (size_t)c * sizeof *grown);
        if (grown) *list = grown, *cap = c;
    }
    if (!path || !w || *n == *cap) {
        free(path);
        free(w);
        f->nomem = 1;
        return;
    }
    (*list)[(*n)++] = (cli_file){path, w, format, in_new_dir};
}

void cli_files_read(cli_files *f, const char *what, const char *path)
{
    if (path) add(f, 0, what, NULL, strdup(path), 0);
}

void cli_files_write(cli_files *f, const char *what, const char *format, const char *path)
{
    if (path) add(f, 1, what, format, strdup(path), 0);
}

void cli_files_write_in_dir(cli_files *f, const char *what, const char *format, const char *dir, const char *name)
{
    size_t n = strlen(dir) + strlen(name) + 2;
    char *path = malloc(n);
    if (path) snprintf(path, n, "%s/%s", dir, name);
    add(f, 1, what, format, path, 1);
}

/* The formats biref writes, by file-name extension, and how messages name them. */
static const char *const FORMATS[][2] = {{"png", "a PNG image"}, {"pfm", "a PFM image"},  {"csv", "CSV"},
                                         {"md", "Markdown"},     {"js", "a JavaScript module"}, {"json", "JSON"}};
enum { N_FORMATS = sizeof FORMATS / sizeof *FORMATS };

static const char *format_text(const char *format)
{
    for (int i = 0; i < N_FORMATS; i++)
        if (!strcmp(format, FORMATS[i][0])) return FORMATS[i][1];
    return format;
}

/* An output whose name says another format than the one written: "x.pfm" holding a PNG. */
static const char *wrong_extension(const cli_file *o)
{
    const char *dot = strrchr(o->path, '.'), *slash = strrchr(o->path, '/');
    if (!o->format || !dot || (slash && dot < slash)) return NULL;
    for (int i = 0; i < N_FORMATS; i++)
        if (!strcasecmp(dot + 1, FORMATS[i][0])) return strcasecmp(dot + 1, o->format) ? dot : NULL;
    return NULL;
}

/* Character devices (/dev/null) are not files: they may take any number of outputs. */
static int is_device(const char *path)
{
    struct stat st;
    return strcmp(path, "-") && stat(path, &st) == 0 && S_ISCHR(st.st_mode);
}

static int parent_is_dir(const char *path)
{
    const char *slash = strrchr(path, '/');
    char *dir = slash ? strndup(path, (size_t)(slash - path) + 1) : strdup(".");
    struct stat st;
    int is_dir = dir && stat(dir, &st) == 0 && S_ISDIR(st.st_mode);
    free(dir);
    return is_dir;
}

int cli_files_check(const char *cmd, const cli_files *f)
{
    if (f->nomem) return cli_error(cmd, "out of memory"), CLI_EXIT_FAIL;
    for (int i = 0; i < f->n_out; i++) {
        const cli_file *o = &f->out[i];
        if (is_device(o->path)) continue;
        for (int j = 0; j < f->n_in; j++)
            if (biref_same_file(o->path, f->in[j].path))
                return cli_error(cmd, "%s (%s) would overwrite the input file %s (%s)", o->path, o->what, f->in[j].path,
                                 f->in[j].what),
                       CLI_EXIT_USAGE;
        for (int j = 0; j < i; j++)
            if (biref_same_file(o->path, f->out[j].path))
                return cli_error(cmd,
                                 strcmp(o->path, "-") ? "%s (%s) and %s (%s) are the same file"
                                                      : "%s (%s) and %s (%s) both go to standard output",
                                 f->out[j].path, f->out[j].what, o->path, o->what),
                       CLI_EXIT_USAGE;
    }
    for (int i = 0; i < f->n_out; i++) {
        const cli_file *o = &f->out[i];
        const char *ext = wrong_extension(o);
        if (ext)
            return cli_error(cmd, "%s (%s): writes %s, but the name ends in %s", o->path, o->what,
                             format_text(o->format), ext),
                   CLI_EXIT_USAGE;
    }
    for (int i = 0; i < f->n_out; i++) {
        int rc = f->out[i].in_new_dir && !parent_is_dir(f->out[i].path) ? 0 : cli_check_writable(cmd, f->out[i].path);
        if (rc) return rc;
    }
    return 0;
}
