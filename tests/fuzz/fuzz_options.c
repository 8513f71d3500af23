/* libFuzzer target: the command line's option parsing. The input is a command line: its first
 * byte picks a command's option table, the rest are the arguments separated by NUL bytes. Each
 * table is parsed as its command parses it (cli_opts_parse with the command's handler, into a
 * zeroed argument buffer), after the --progress/--quiet pre-pass; then the value parsers shared
 * by the commands get every argument. Their messages go to /dev/null. Traps on a broken promise: a
 * result other than -1, 0 or 1, a parsed number that is not finite or whose text is not decimal,
 * a window that is empty. */
#include <complex.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "cli_light.h"
#include "cli_polarizer.h"
#include "cli_values.h"
#include "commands.h"

enum { MAX_ARGS = 64 };

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc, (void)argv;
    /* The parsers' messages and --help go to the stdio streams, which are pointed elsewhere;
     * libFuzzer and the sanitizers keep writing their reports to file descriptor 2. */
    FILE *null = fopen("/dev/null", "w");
    if (!null) abort();
    stderr = null;
    stdout = null;
    return 0;
}

/* The value parsers on one argument: what they accept is finite. */
static void values(const char *text)
{
    double v, w[4], S[4];
    long n;
    if (!cli_parse_double("f", "--x", text, &v) && (!isfinite(v) || !cli_number_syntax_ok(text, 0))) __builtin_trap();
    if (!cli_parse_int("f", "--x", text, -5, 5, &n) && (n < -5 || n > 5 || !cli_number_syntax_ok(text, 1)))
        __builtin_trap();
    if (!cli_parse_list("f", "--x", text, w, 3))
        for (int i = 0; i < 3; i++)
            if (!isfinite(w[i])) __builtin_trap();
    if (!cli_parse_window("f", "--x", text, w) && !(w[0] < w[1] && w[2] < w[3] && isfinite(w[1] - w[0]) && isfinite(w[3] - w[2])))
        __builtin_trap();
    if (!cli_parse_linear_polarizer("f", "--x", text, &v) && !(fabs(v) < 360.0)) __builtin_trap();
    if (!cli_parse_polarizer_state("f", "--x", text, S) || !cli_parse_stokes("f", "--x", text, S))
        for (int i = 0; i < 4; i++)
            if (!isfinite(S[i])) __builtin_trap();
    double complex P[2][2];
    if (cli_parse_general_analyzer("f", "--x", text, P) > 0)
        for (int i = 0; i < 4; i++)
            if (!isfinite(creal(P[i / 2][i % 2])) || !isfinite(cimag(P[i / 2][i % 2]))) __builtin_trap();
    double two[2];
    if (!cli_parse_polarization("f", "--x", text, two) && !(isfinite(two[0]) && isfinite(two[1]))) __builtin_trap();
    if (!cli_parse_range_nm("f", "--x", text, two) && !(two[0] < two[1])) __builtin_trap();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const cli_command_spec *const SPECS[] = {&CLI_SLAB,   &CLI_SPECTRUM, &CLI_ACCURACY, &CLI_RENDER,
                                                    &CLI_DIFF,   &CLI_BENCH,    &CLI_FIGURE,   &CLI_GL_DATA,
                                                    &CLI_PHOTOELASTIC, &CLI_PHOTOELASTIC_DEMODULATE, &CLI_MATERIAL};
    if (size < 1 || size > 4096) return 0;
    const cli_command_spec *spec = SPECS[data[0] % (sizeof SPECS / sizeof *SPECS)];
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data + 1, size - 1);
    text[size - 1] = '\0';
    char *argv[MAX_ARGS + 2];
    int argc = 0;
    argv[argc++] = (char *)spec->name;
    for (char *p = text; p < text + size - 1 && argc <= MAX_ARGS; p += strlen(p) + 1) argv[argc++] = p;
    argv[argc] = NULL;
    for (int i = 1; i < argc; i++) values(argv[i]);
    char *copy[MAX_ARGS + 2];
    memcpy(copy, argv, sizeof copy);
    int n = cli_progress_options(argc, copy);
    if (n > argc || n < -1) __builtin_trap();
    if (n > 0) {
        /* Large enough for any command's argument struct, aligned for any field. */
        static max_align_t args[65536 / sizeof(max_align_t)];
        memset(args, 0, sizeof args);
        cli_parsed p;
        int r = cli_opts_parse(spec, args, n, copy, &p);
        if (r < -1 || r > 1 || (r == 0 && (p.first_arg < 0 || p.first_arg > n || p.n_args != n - p.first_arg)))
            __builtin_trap();
    }
    free(text);
    return 0;
}
