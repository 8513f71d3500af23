/* The command line's progress report and wall clock (the library only reports progress through a
 * biref_progress_fn callback; showing it is the caller's business).
 *
 * One policy for every long command: on a terminal, a bar redrawn in place; otherwise (a log file,
 * a pipe, CI) plain lines, the first once the job has run PROGRESS_QUIET_SECONDS, then every
 * PROGRESS_LINE_SECONDS or every tenth of the job. `--progress` shows progress from the start,
 * `-q`/`--quiet` shows none; both are accepted by every command (cli_progress_options). */
#ifndef BIREF_CLI_PROGRESS_H
#define BIREF_CLI_PROGRESS_H

#include <stdio.h>

#define PROGRESS_QUIET_SECONDS 2.0
#define PROGRESS_LINE_SECONDS 5.0

typedef enum { CLI_PROGRESS_AUTO, CLI_PROGRESS_ALWAYS, CLI_PROGRESS_NEVER } cli_progress_mode;

/* Takes --progress, --quiet and -q out of a command's argv (up to a "--"; argv[0] is the command's
 * name), sets the mode and returns the new argc (argv stays NULL-terminated); -1 after one error
 * line when they are given twice or together (they exclude each other). */
int cli_progress_options(int argc, char **argv);
void cli_progress_set_mode(cli_progress_mode mode);
cli_progress_mode cli_progress_get_mode(void);

/* The progress of one job. Usable directly as a biref_progress_fn (pass the bar as user); not
 * thread-safe (call it from one thread at a time). enabled = 0 makes every call a no-op, for
 * jobs whose caller has a reason of its own to stay silent. */
typedef struct {
    FILE *f;
    int enabled;
    int tty;         /* bar (1) or lines (0) */
    double t_start, t_last;
    int drawn;       /* something was printed */
    int last_tenth;  /* the tenth of the job the last line reported */
    int done, total; /* the last update */
    char label[48];
    char note[64];
} biref_progress_bar;

void biref_progress_bar_init(biref_progress_bar *bar, FILE *f, int enabled, const char *label);
void biref_progress_bar_update(void *bar, int done, int total);
/* Extra words shown after the percentage from the next update on (e.g. the current item). */
void biref_progress_bar_note(biref_progress_bar *bar, const char *note);
/* One line of its own (e.g. a finished step's result), under the same policy as the lines. */
void biref_progress_bar_message(biref_progress_bar *bar, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* Ends the bar's line, or prints "done in T s" after progress lines. */
void biref_progress_bar_finish(biref_progress_bar *bar);

/* Monotonic wall clock in seconds. */
double biref_wall_seconds(void);

#endif
