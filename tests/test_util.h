/* Minimal test harness: each test executable is one ctest; failures are counted and printed. */
#ifndef BIREF_TEST_UTIL_H
#define BIREF_TEST_UTIL_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

static int test_failures;
static int test_checks;

#define CHECK(cond)                                                                      \
    do {                                                                                 \
        test_checks++;                                                                   \
        if (!(cond)) {                                                                   \
            test_failures++;                                                             \
            if (test_failures <= 20) fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
        }                                                                                \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                            \
    do {                                                                                 \
        double a_ = (a), b_ = (b);                                                       \
        test_checks++;                                                                   \
        if (!(fabs(a_ - b_) <= (tol))) {                                                 \
            test_failures++;                                                             \
            if (test_failures <= 20)                                                     \
                fprintf(stderr, "%s:%d: %s = %.12g vs %s = %.12g (|diff| %.3g > %.3g)\n", __FILE__, __LINE__, #a, a_, \
                        #b, b_, fabs(a_ - b_), (double)(tol));                           \
        }                                                                                \
    } while (0)

/* Whether BIREF_TEST_QUICK is set (the sanitizer run): smaller images, fewer random cases. */
static inline int test_quick(void) { return getenv("BIREF_TEST_QUICK") != NULL; }

static inline int test_report(const char *name)
{
    if (test_failures) {
        fprintf(stderr, "%s: %d of %d checks FAILED\n", name, test_failures, test_checks);
        return 1;
    }
    printf("%s: %d checks passed\n", name, test_checks);
    return 0;
}

/* Seeded xorshift64*: reproducible property tests on every platform. */
typedef struct { uint64_t s; } test_rng;
static inline double test_uniform(test_rng *r, double lo, double hi)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    uint64_t x = r->s * 2685821657736338717ULL;
    return lo + (hi - lo) * ((double)(x >> 11) / 9007199254740992.0);
}

/* Advances r by n draws: a case that continues another case's seeded sequence starts where that
 * case left it, so each case alone sees the same numbers as the cases run in order. */
static inline void test_skip(test_rng *r, long n)
{
    while (n-- > 0) (void)test_uniform(r, 0, 1);
}

/* A random direction, uniform on the sphere (rejection sampling in the unit ball, shell
 * 0.1 <= |A| <= 1), returned unnormalised: the library normalises optic axes itself. */
static inline void test_random_axis(test_rng *r, double A[3])
{
    double n;
    do {
        for (int i = 0; i < 3; i++) A[i] = test_uniform(r, -1, 1);
        n = sqrt(A[0] * A[0] + A[1] * A[1] + A[2] * A[2]);
    } while (n < 0.1 || n > 1);
}

/* A random unit-intensity Stokes vector: polarization ellipse of random orientation and
 * ellipticity, degree of polarization uniform in [0, 1]. */
static inline void test_random_stokes(test_rng *r, double S[4])
{
    double a = test_uniform(r, 0, M_PI), b = test_uniform(r, -M_PI / 2, M_PI / 2), dop = test_uniform(r, 0, 1);
    S[0] = 1.0;
    S[1] = dop * cos(b) * cos(2 * a);
    S[2] = dop * cos(b) * sin(2 * a);
    S[3] = dop * sin(b);
}

#endif
