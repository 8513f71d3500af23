/* Named test cases: each test program is a table of {name, function}; every case reports its
 * name and result, and `test_x NAME` runs one case alone. The checks are test_util.h's. */
#ifndef BIREF_TEST_CASES_H
#define BIREF_TEST_CASES_H

#include <stdio.h>
#include <string.h>

#include "test_util.h"

typedef struct {
    const char *name;
    void (*fn)(void);
} test_case;

#define TEST_COUNT(table) (sizeof(table) / sizeof((table)[0]))

/* Runs the cases (or only the one named by argv[1]); returns main's exit status. */
static inline int test_run_cases(const char *suite, const test_case *cases, size_t n, int argc, char **argv)
{
    const char *only = argc > 1 ? argv[1] : NULL;
    int ran = 0;
    for (size_t i = 0; i < n; i++) {
        if (only && strcmp(only, cases[i].name)) continue;
        const int before = test_failures, checks = test_checks;
        cases[i].fn();
        ran++;
        printf("%-44s %s (%d checks)\n", cases[i].name, test_failures == before ? "ok" : "FAILED",
               test_checks - checks);
        fflush(stdout);
    }
    if (only && !ran) {
        fprintf(stderr, "%s: no case named '%s'\n", suite, only);
        return 2;
    }
    return test_report(suite);
}

#endif
