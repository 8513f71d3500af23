/* A one-line progress bar with ETA. The caller decides whether it is enabled (the CLI enables
 * it only when stderr is a terminal and --quiet is absent), so pipes and logs stay clean. */
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "cli_progress.h"

double biref_wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void biref_progress_bar_init(biref_progress_bar *bar, FILE *f, int enabled, const char *label)
{
    memset(bar, 0, sizeof *bar);
    bar->f = f;
    bar->enabled = enabled && f;
    bar->t_start = biref_wall_seconds();
    snprintf(bar->label, sizeof bar->label, "%s", label ? label : "");
}

void biref_progress_bar_update(void *user, int done, int total)
{
    biref_progress_bar *bar = user;
    if (!bar || !bar->enabled || total <= 0) return;
    double now = biref_wall_seconds();
    /* Redrawing every row would cost more than some rows; 10 Hz looks smooth. */
    if (done < total && bar->drawn && now - bar->t_last < 0.1) return;
    bar->t_last = now;
    bar->drawn = 1;
    double frac = (double)done / total, el = now - bar->t_start;
    enum { WIDTH = 30 };
    char cells[WIDTH + 1];
    int filled = (int)(frac * WIDTH);
    for (int i = 0; i < WIDTH; i++) cells[i] = i < filled ? '#' : '.';
    cells[WIDTH] = '\0';
    if (done > 0 && done < total)
        fprintf(bar->f, "\r%s [%s] %3d%%  ETA %.1f s   ", bar->label, cells, (int)(100 * frac),
                el * (1.0 - frac) / frac);
    else
        fprintf(bar->f, "\r%s [%s] %3d%%  %.1f s      ", bar->label, cells, (int)(100 * frac), el);
    fflush(bar->f);
}

void biref_progress_bar_finish(biref_progress_bar *bar)
{
    if (!bar || !bar->enabled || !bar->drawn) return;
    fputc('\n', bar->f);
    fflush(bar->f);
}
