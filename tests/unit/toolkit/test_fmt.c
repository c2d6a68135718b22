/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The number formatter of the text writers (src/io/write/fmt.c, compiled into
 * this test because it is internal): every double and float reads back to
 * the same bits, the text is the shortest that does (checked against the
 * C library, an independent implementation), and the notation is plain. */
#include "fmt.c"

#include <float.h>

#include "test_util.h"

static uint64_t rng = 0x243f6a8885a308d3ull;
static uint64_t next_u64(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng;
}

static coons__fmt_scope scope;
static int setup(void **state)
{
    (void)state;
    return coons__fmt_begin(&scope) ? 0 : -1;
}
static int teardown(void **state)
{
    (void)state;
    coons__fmt_end(&scope);
    return 0;
}

static void assert_double_roundtrip(double v, char *out)
{
    size_t n = coons__fmt_double(out, v);
    assert_int_equal(n, strlen(out));
    assert_true(n < COONS__FMT_MAX);
    char *end;
    double back = strtod(out, &end);
    if (*end || memcmp(&back, &v, sizeof v) != 0)
        fail_msg("%a printed as '%s' reads back as %a", v, out, back);
}

/* Fewest significant digits with which printf's correctly rounded %.*e
 * reads back to v: the reference for "shortest". */
static int libc_shortest_double(double v)
{
    char buf[64];
    for (int p = 1; p <= 17; p++) {
        snprintf(buf, sizeof buf, "%.*e", p - 1, v);
        if (strtod(buf, NULL) == v) return p;
    }
    return 99;
}
static int libc_shortest_float(float v)
{
    char buf[64];
    for (int p = 1; p <= 9; p++) {
        snprintf(buf, sizeof buf, "%.*e", p - 1, (double)v);
        if (strtof(buf, NULL) == v) return p;
    }
    return 99;
}

/* Significant digits in our text: digits from the first non-zero one,
 * without trailing zeros of an integer. */
static int our_digits(const char *s)
{
    char m[64];
    snprintf(m, sizeof m, "%s", s);
    char *e = strchr(m, 'e');
    if (e) *e = '\0';
    if (!strchr(m, '.')) {
        size_t l = strlen(m);
        while (l > 1 && m[l - 1] == '0') m[--l] = '\0';
    }
    int n = 0, started = 0;
    for (const char *c = m; *c; c++) {
        if (*c >= '1' && *c <= '9') started = 1;
        if (started && *c >= '0' && *c <= '9') n++;
    }
    return n;
}

/* Given awkward doubles, when formatted, then the exact expected texts
 * appear and each reads back bit for bit. */
static void test_awkward_doubles(void **state)
{
    (void)state;
    static const struct {
        double v;
        const char *text;
    } cases[] = {
        {0.1, "0.1"},
        {-0.0, "-0"},
        {0.0, "0"},
        {1e-300, "1e-300"},
        {9007199254740993.0, "9007199254740992"}, /* 2^53+1 rounds to 2^53 */
        {9007199254740994.0, "9007199254740994"}, /* 2^53+2 */
        {4.9406564584124654e-324, "5e-324"},      /* smallest subnormal */
        {2.2250738585072009e-308, "2.225073858507201e-308"}, /* largest subnormal */
        {2.2250738585072014e-308, "2.2250738585072014e-308"}, /* DBL_MIN */
        {1.7976931348623157e308, "1.7976931348623157e308"},
        {1.0 / 3.0, "0.3333333333333333"},
        {100.0, "100"},
        {1e21, "1e21"},
        {123456.0, "123456"},
        {-1.5e-7, "-1.5e-7"},
        {0.000125, "1.25e-4"},
        {0.00125, "0.00125"},
        {5e-324 * 3, "1.5e-323"},
    };
    char out[COONS__FMT_MAX];
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        assert_double_roundtrip(cases[i].v, out);
        assert_string_equal(out, cases[i].text);
    }
}

/* Given a million random bit patterns (all exponents, subnormals included),
 * every finite double reads back exactly and is never longer than libc's
 * shortest correctly rounded form. */
static void test_random_doubles(void **state)
{
    (void)state;
    char out[COONS__FMT_MAX];
    long checked = 0;
    for (long i = 0; i < 300000; i++) {
        uint64_t u = next_u64();
        if (i % 3 == 0) u >>= next_u64() % 64; /* many small and subnormal values */
        double v;
        memcpy(&v, &u, sizeof v);
        if (!isfinite(v)) continue;
        assert_double_roundtrip(v, out);
        if (i % 10 == 0 && v != 0.0) {
            int ref = libc_shortest_double(v), ours = our_digits(out);
            if (ours > ref) fail_msg("%a: '%s' has %d digits, %d suffice", v, out, ours, ref);
            checked++;
        }
    }
    assert_true(checked > 15000);
}

/* Given awkward floats, when formatted, then they read back exactly
 * (strtof) and have the expected text. */
static void test_awkward_floats(void **state)
{
    (void)state;
    static const struct {
        float v;
        const char *text;
    } cases[] = {
        {0.1f, "0.1"},       {-0.0f, "-0"},           {1e-45f, "1e-45"},
        {FLT_MAX, "3.4028235e38"}, {FLT_MIN, "1.1754944e-38"}, {16777217.0f, "16777216"},
        {0.3f, "0.3"},       {2.0f / 3.0f, "0.6666667"}, {-1e-5f, "-1e-5"},
        {123.456f, "123.456"}, {1.0f, "1"},           {1e10f, "1e10"},
    };
    char out[COONS__FMT_MAX];
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        size_t n = coons__fmt_float(out, cases[i].v);
        assert_int_equal(n, strlen(out));
        assert_string_equal(out, cases[i].text);
        float back = strtof(out, NULL);
        assert_memory_equal(&back, &cases[i].v, sizeof back);
    }
}

/* Given 1.5 million random float bit patterns, every finite one reads back
 * exactly and is never longer than libc's shortest correctly rounded form
 * (fmt.c could in principle give one more digit for a text within 1e-6 of
 * a rounding boundary without hitting it exactly; none occurs here). */
static void test_random_floats(void **state)
{
    (void)state;
    char out[COONS__FMT_MAX];
    long checked = 0;
    for (long i = 0; i < 1500000; i++) {
        uint32_t u = (uint32_t)next_u64();
        float v;
        memcpy(&v, &u, sizeof v);
        if (!isfinite(v)) continue;
        coons__fmt_float(out, v);
        char *end;
        float back = strtof(out, &end);
        if (*end || memcmp(&back, &v, sizeof v) != 0)
            fail_msg("%a printed as '%s' reads back as %a", (double)v, out, (double)back);
        if (i % 8 == 0 && v != 0.0f) {
            int ref = libc_shortest_float(v), ours = our_digits(out);
            if (ours > ref) fail_msg("%a: '%s' has %d digits, %d suffice", (double)v, out, ours, ref);
            checked++;
        }
    }
    assert_true(checked > 150000);
}

/* Coordinate-like floats (uniform in [-1000, 1000], and in [-1, 1] like
 * normal components), the ASCII STL writer's daily bread: exact and
 * shortest too. */
static void test_coordinate_floats(void **state)
{
    (void)state;
    char out[COONS__FMT_MAX];
    for (long i = 0; i < 400000; i++) {
        double u = (double)(next_u64() >> 11) / 9007199254740992.0;
        float v = (float)(i % 2 ? 2000.0 * u - 1000.0 : 2.0 * u - 1.0);
        coons__fmt_float(out, v);
        float back = strtof(out, NULL);
        if (memcmp(&back, &v, sizeof v) != 0)
            fail_msg("%a printed as '%s' reads back as %a", (double)v, out, (double)back);
        if (i % 4 == 0 && v != 0.0f) {
            int ref = libc_shortest_float(v), ours = our_digits(out);
            if (ours > ref) fail_msg("%a: '%s' has %d digits, %d suffice", (double)v, out, ours, ref);
        }
    }
}

/* Notation: only digits, '-', one '.', 'e': no '+', no locale characters,
 * no leading zeros in exponents. */
static void test_notation(void **state)
{
    (void)state;
    char out[COONS__FMT_MAX];
    for (long i = 0; i < 100000; i++) {
        uint64_t u = next_u64();
        double v;
        memcpy(&v, &u, sizeof v);
        if (!isfinite(v)) continue;
        coons__fmt_double(out, v);
        int dots = 0;
        for (const char *c = out; *c; c++) {
            assert_true((*c >= '0' && *c <= '9') || *c == '-' || *c == '.' || *c == 'e');
            dots += *c == '.';
        }
        assert_true(dots <= 1);
        const char *e = strchr(out, 'e');
        if (e) {
            if (e[1] == '-') e++;
            assert_true(e[1] != '0');
        }
    }
}

static void test_u64(void **state)
{
    (void)state;
    char out[32];
    out[coons__fmt_u64(out, 0)] = '\0';
    assert_string_equal(out, "0");
    out[coons__fmt_u64(out, 4294967295u)] = '\0';
    assert_string_equal(out, "4294967295");
    out[coons__fmt_u64(out, UINT64_MAX)] = '\0';
    assert_string_equal(out, "18446744073709551615");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_awkward_doubles), cmocka_unit_test(test_random_doubles),
        cmocka_unit_test(test_awkward_floats),  cmocka_unit_test(test_random_floats),
        cmocka_unit_test(test_coordinate_floats),
        cmocka_unit_test(test_notation),        cmocka_unit_test(test_u64),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
