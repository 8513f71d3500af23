/* The command line's progress bar and wall clock (the library only reports progress through a
 * biref_progress_fn callback; drawing it is the caller's business). */
#ifndef BIREF_CLI_PROGRESS_H
#define BIREF_CLI_PROGRESS_H

#include <stdio.h>

/* A textual progress bar with ETA, redrawn at most every 0.1 s on f (normally stderr).
 * Usable directly as a biref_progress_fn (pass the bar as user). enabled = 0 makes every
 * call a no-op. */
typedef struct {
    FILE *f;
    int enabled;
    double t_start, t_last;
    int drawn;
    char label[32];
} biref_progress_bar;

void biref_progress_bar_init(biref_progress_bar *bar, FILE *f, int enabled, const char *label);
void biref_progress_bar_update(void *bar, int done, int total);
void biref_progress_bar_finish(biref_progress_bar *bar);

/* Monotonic wall clock in seconds. */
double biref_wall_seconds(void);

#endif
