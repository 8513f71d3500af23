/* Progress on stderr for every long command (policy in cli_progress.h). Jobs shorter than
 * PROGRESS_QUIET_SECONDS print nothing when stderr is not a terminal, so scripts and tests of quick
 * commands keep an empty stderr; long ones leave a trace in logs, which is how a user tells a slow
 * job from a hung one. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli_progress.h"

static cli_progress_mode g_mode = CLI_PROGRESS_AUTO;

void cli_progress_set_mode(cli_progress_mode mode) { g_mode = mode; }
cli_progress_mode cli_progress_get_mode(void) { return g_mode; }

int cli_progress_options(int argc, char **argv)
{
    int n = 0, i = 0, given = 0; /* given: 0, or the mode already set */
    for (; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--")) break;
        const int progress = i > 0 && !strcmp(a, "--progress"), quiet = i > 0 && (!strcmp(a, "--quiet") || !strcmp(a, "-q"));
        if (!progress && !quiet) {
            argv[n++] = argv[i];
            continue;
        }
        const int mode = progress ? CLI_PROGRESS_ALWAYS : CLI_PROGRESS_NEVER;
        if (given) {
            fprintf(stderr, "biref %s: error: %s\n", argv[0],
                    given != mode ? "--progress and --quiet exclude each other"
                    : progress    ? "--progress given twice"
                                  : "--quiet given twice");
            return -1;
        }
        given = mode;
        g_mode = (cli_progress_mode)mode;
    }
    for (; i < argc; i++) argv[n++] = argv[i];
    argv[n] = NULL;
    return n;
}

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
    bar->enabled = enabled && f && g_mode != CLI_PROGRESS_NEVER;
    bar->tty = f && isatty(fileno(f));
    bar->t_start = biref_wall_seconds();
    bar->last_tenth = -1;
    snprintf(bar->label, sizeof bar->label, "%s", label ? label : "");
}

void biref_progress_bar_note(biref_progress_bar *bar, const char *note)
{
    if (bar) snprintf(bar->note, sizeof bar->note, "%s", note ? note : "");
}

/* Lines (not a terminal): nothing during the first seconds unless --progress. */
static int lines_due(const biref_progress_bar *bar, double now)
{
    return g_mode == CLI_PROGRESS_ALWAYS || now - bar->t_start >= PROGRESS_QUIET_SECONDS;
}

static void draw_bar(biref_progress_bar *bar, double now)
{
    const double frac = bar->total > 0 ? (double)bar->done / bar->total : 0.0, el = now - bar->t_start;
    enum { WIDTH = 30 };
    char cells[WIDTH + 1];
    const int filled = (int)(frac * WIDTH);
    for (int i = 0; i < WIDTH; i++) cells[i] = i < filled ? '#' : '.';
    cells[WIDTH] = '\0';
    if (bar->done > 0 && bar->done < bar->total)
        fprintf(bar->f, "\r%s [%s] %3d%%  ETA %.1f s  %s   ", bar->label, cells, (int)(100 * frac),
                el * (1.0 - frac) / frac, bar->note);
    else
        fprintf(bar->f, "\r%s [%s] %3d%%  %.1f s  %s     ", bar->label, cells, (int)(100 * frac), el, bar->note);
    fflush(bar->f);
}

static void print_line(biref_progress_bar *bar, double now)
{
    const double frac = bar->total > 0 ? (double)bar->done / bar->total : 0.0, el = now - bar->t_start;
    fprintf(bar->f, "biref %s: %3d%%  %.1f s", bar->label, (int)(100 * frac), el);
    if (bar->done > 0 && bar->done < bar->total) fprintf(bar->f, ", about %.0f s left", el * (1.0 - frac) / frac);
    fprintf(bar->f, "%s%s\n", bar->note[0] ? "  " : "", bar->note);
    fflush(bar->f);
}

void biref_progress_bar_update(void *user, int done, int total)
{
    biref_progress_bar *bar = user;
    if (!bar || !bar->enabled || total <= 0) return;
    bar->done = done;
    bar->total = total;
    const double now = biref_wall_seconds();
    if (bar->tty) {
        /* Redrawing every row would cost more than some rows; 10 Hz looks smooth. */
        if (done < total && bar->drawn && now - bar->t_last < 0.1) return;
        draw_bar(bar, now);
    } else {
        /* A line every PROGRESS_LINE_SECONDS, or at each new tenth (at most one a second); the
         * end is reported by biref_progress_bar_finish. */
        const int tenth = (int)(10.0 * done / total);
        if (done >= total || !lines_due(bar, now)) return;
        const double since = now - bar->t_last;
        if (bar->drawn && since < PROGRESS_LINE_SECONDS && !(tenth > bar->last_tenth && since >= 1.0)) return;
        bar->last_tenth = tenth;
        print_line(bar, now);
    }
    bar->t_last = now;
    bar->drawn = 1;
}

void biref_progress_bar_message(biref_progress_bar *bar, const char *fmt, ...)
{
    if (!bar || !bar->enabled) return;
    const double now = biref_wall_seconds();
    if (!bar->tty && !lines_due(bar, now)) return;
    if (bar->tty && bar->drawn) fprintf(bar->f, "\r%*s\r", 100, "");
    fprintf(bar->f, "biref %s: ", bar->label);
    va_list ap;
    va_start(ap, fmt);
    vfprintf(bar->f, fmt, ap);
    va_end(ap);
    fputc('\n', bar->f);
    if (bar->tty && bar->drawn) draw_bar(bar, now);
    fflush(bar->f);
}

void biref_progress_bar_finish(biref_progress_bar *bar)
{
    if (!bar || !bar->enabled || !bar->drawn) return;
    const double now = biref_wall_seconds();
    if (bar->tty)
        fputc('\n', bar->f);
    else {
        fprintf(bar->f, "biref %s: done in %.1f s\n", bar->label, now - bar->t_start);
    }
    fflush(bar->f);
}
