/* moraine: a minimal assertion helper for the C unit tests.
 * Each test program returns 0 when every CHECK passed and prints each failure
 * with its file and line. */
#ifndef MRN_TESTS_CHECK_H
#define MRN_TESTS_CHECK_H

#include <math.h>
#include <stdio.h>

static int check_failures = 0;
static int check_count = 0;

#define CHECK(cond)                                                             \
  do {                                                                          \
    check_count++;                                                              \
    if (!(cond)) {                                                              \
      check_failures++;                                                         \
      fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
    }                                                                           \
  } while (0)

/* |a - b| <= tol * max(1, |b|) */
#define CHECK_CLOSE(a, b, tol)                                                                     \
  do {                                                                                             \
    check_count++;                                                                                 \
    double check_a_ = (a), check_b_ = (b);                                                         \
    double check_s_ = fabs(check_b_) > 1.0 ? fabs(check_b_) : 1.0;                                 \
    if (!(fabs(check_a_ - check_b_) <= (tol) * check_s_)) {                                        \
      check_failures++;                                                                            \
      fprintf(stderr, "%s:%d: check failed: %s = %.17g, expected %s = %.17g (tol %g)\n", __FILE__, \
              __LINE__, #a, check_a_, #b, check_b_, (double)(tol));                                \
    }                                                                                              \
  } while (0)

#define CHECK_DONE()                                                                 \
  do {                                                                               \
    printf("%d checks, %d failed\n", check_count, check_failures);                   \
    return check_failures ? 1 : 0;                                                   \
  } while (0)

#endif
