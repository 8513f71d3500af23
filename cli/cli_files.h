/* Every file a command reads and writes, checked against each other before anything is written
 * (docs/CLI.md, "Files"): no output may be one of the inputs, no two outputs may be one file,
 * and no output may carry the extension of another format than the one written into it. The
 * outputs' directories are checked to be writable too, so that a typo fails before the work. */
#ifndef BIREF_CLI_FILES_H
#define BIREF_CLI_FILES_H

typedef struct {
    char *path;
    char *what;         /* how the command line named it: "-o", "--pfm", "SCENE", "--phase-steps image 2" */
    const char *format; /* outputs: "png", "pfm", "csv", "md", "js"; NULL: any name */
    int in_new_dir;     /* in a directory the command creates: its writability is checked there */
} cli_file;

typedef struct {
    cli_file *in, *out;
    int n_in, n_out, cap_in, cap_out;
    int nomem;
} cli_files;

void cli_files_init(cli_files *f);
void cli_files_free(cli_files *f);
/* An input file (NULL: nothing). */
void cli_files_read(cli_files *f, const char *what, const char *path);
/* An output file (NULL: nothing) of this format (NULL: any). */
void cli_files_write(cli_files *f, const char *what, const char *format, const char *path);
/* An output DIR/NAME in a directory the command creates if missing. */
void cli_files_write_in_dir(cli_files *f, const char *what, const char *format, const char *dir, const char *name);
/* The checks above. Returns 0, or after one error line CLI_EXIT_USAGE (a conflict, a wrong
 * extension) or CLI_EXIT_FAIL (an unwritable place, out of memory). */
int cli_files_check(const char *cmd, const cli_files *f);

#endif
