/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Shared helpers of the cmocka tests. cmocka 1.1.5's assert_float_equal
 * casts to float, so doubles are compared here. */
#ifndef COONS_TEST_UTIL_H
#define COONS_TEST_UTIL_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <coons.h>

void assert_near_impl(double a, double b, double eps, const char *ea, const char *eb,
                      const char *file, int line);
void assert_vec3_near_impl(const double *a, const double *b, double eps, const char *ea,
                           const char *eb, const char *file, int line);

/* |a-b| <= eps */
#define assert_near(a, b, eps) assert_near_impl((a), (b), (eps), #a, #b, __FILE__, __LINE__)
#define assert_vec3_near(a, b, eps) \
    assert_vec3_near_impl((a), (b), (eps), #a, #b, __FILE__, __LINE__)
/* Asserts a call returned COONS_OK, printing the error message if not. */
#define assert_coons_ok(call, errp)                                                  \
    do {                                                                             \
        int rc_ = (call);                                                            \
        if (rc_ != COONS_OK) fail_msg("%s -> %d: %s", #call, rc_, (errp)->message); \
    } while (0)

/* Loads the model at `rel` (a path inside the source tree), asserting it
 * loads. */
coons_model *test_source_model(const char *rel);

/* Failing allocator: after coons_test_fail_after(n) the (n+1)-th allocation
 * through the library's hooks fails; n < 0 disables. Installs itself. */
void coons_test_fail_after(long n);
long coons_test_alloc_count(void);
/* Blocks allocated minus blocks freed through the hooks since the last
 * coons_test_fail_after(n >= 0): 0 after a call that cleaned up. */
long coons_test_live_allocs(void);

#endif
