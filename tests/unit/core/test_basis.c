/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * White-box tests of src/core/basis.c (compiled into this test, see
 * tests/CMakeLists.txt): the Coons polynomials C0..C3 of seed 002, the cubic
 * Hermite basis H0..H3 of seed 001 (eq. 1.13) and the blending pairs of
 * seed 001 section 1.2. Expected values are the seeds' formulas written out
 * again here, hand-derived derivatives, and central finite differences.
 */
#include <math.h>

#include "basis.h"
#include "test_util.h"

/* Seed 002, slide "Coons cubic curve", written out independently. */
static double seed_C(int j, double t)
{
    switch (j) {
    case 0: return (1.0 - t) * (1.0 - t) * (1.0 - t) / 6.0;
    case 1: return (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0;
    case 2: return (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0;
    default: return t * t * t / 6.0;
    }
}

/* Seed 001 eq. 1.13: H0 value at 0, H1 slope at 0, H2 slope at 1, H3 value at 1
 * (the classical Ferguson cubics). */
static double seed_H(int j, double t)
{
    double s = 1.0 - t;
    switch (j) {
    case 0: return (1.0 + 2.0 * t) * s * s;
    case 1: return t * s * s;
    case 2: return -t * t * s;
    default: return t * t * (3.0 - 2.0 * t);
    }
}

#define NT 41

static void coons_at(double t, double b[12]) { coons__coons_basis(t, 2, b); }
static void hermite_at(double t, double b[12]) { coons__hermite_basis(t, 2, b); }

/* Given the basis at many t, when values are compared with the seed's
 * polynomials, then they agree to rounding. */
static void test_coons_values_match_seed(void **state)
{
    (void)state;
    for (int i = 0; i < NT; i++) {
        double t = (double)i / (NT - 1), b[12];
        coons_at(t, b);
        for (int j = 0; j < 4; j++) assert_near(b[j], seed_C(j, t), 1e-15);
    }
}

/* Given any t in [0,1], then C0+C1+C2+C3 = 1, the derivatives sum to 0, every
 * value is >= 0 and < 1 (seed 002 property 1: the curve passes through no
 * control point). */
static void test_coons_partition_of_unity(void **state)
{
    (void)state;
    for (int i = 0; i < NT; i++) {
        double t = (double)i / (NT - 1), b[12];
        coons_at(t, b);
        assert_near(b[0] + b[1] + b[2] + b[3], 1.0, 1e-15);
        assert_near(b[4] + b[5] + b[6] + b[7], 0.0, 1e-14);
        assert_near(b[8] + b[9] + b[10] + b[11], 0.0, 1e-14);
        for (int j = 0; j < 4; j++) {
            assert_true(b[j] >= 0.0);
            assert_true(b[j] < 1.0);
        }
    }
}

/* The end values that give seed 002 properties 2-4:
 * C(0) = (1,4,1,0)/6, C(1) = (0,1,4,1)/6, C'(0) = (-1/2,0,1/2,0),
 * C'(1) = (0,-1/2,0,1/2), C''(0) = (1,-2,1,0), C''(1) = (0,1,-2,1)
 * (hand derivatives of the seed polynomials). */
static void test_coons_end_values(void **state)
{
    (void)state;
    const double at0[12] = {1.0 / 6, 4.0 / 6, 1.0 / 6, 0, -0.5, 0, 0.5, 0, 1, -2, 1, 0};
    const double at1[12] = {0, 1.0 / 6, 4.0 / 6, 1.0 / 6, 0, -0.5, 0, 0.5, 0, 1, -2, 1};
    double b[12];
    coons_at(0.0, b);
    for (int j = 0; j < 12; j++) assert_near(b[j], at0[j], 1e-15);
    coons_at(1.0, b);
    for (int j = 0; j < 12; j++) assert_near(b[j], at1[j], 1e-15);
}

/* C_j(t) = C_{3-j}(1-t): the basis is symmetric, so reversing the control
 * points reverses the curve. Derivatives change sign once per order. */
static void test_coons_symmetry(void **state)
{
    (void)state;
    for (int i = 0; i < NT; i++) {
        double t = (double)i / (NT - 1), a[12], r[12];
        coons_at(t, a);
        coons_at(1.0 - t, r);
        for (int j = 0; j < 4; j++) {
            assert_near(a[j], r[3 - j], 1e-15);
            assert_near(a[4 + j], -r[4 + 3 - j], 1e-14);
            assert_near(a[8 + j], r[8 + 3 - j], 1e-14);
        }
    }
}

/* Derivatives against central differences of the seed polynomials. */
static void check_derivs_fd(void (*basis)(double, double[12]), double (*f)(int, double))
{
    const double h = 1e-5;
    for (int i = 1; i < NT - 1; i++) {
        double t = (double)i / (NT - 1), b[12];
        basis(t, b);
        for (int j = 0; j < 4; j++) {
            double d1 = (f(j, t + h) - f(j, t - h)) / (2 * h);
            double d2 = (f(j, t + h) - 2 * f(j, t) + f(j, t - h)) / (h * h);
            assert_near(b[4 + j], d1, 1e-8);
            assert_near(b[8 + j], d2, 1e-4);
        }
    }
}

static void test_coons_derivatives_fd(void **state)
{
    (void)state;
    check_derivs_fd(coons_at, seed_C);
}

/* nd selects how much is written: nd = 0 leaves b[4..] untouched. */
static void test_order_argument(void **state)
{
    (void)state;
    double b[12];
    for (int j = 0; j < 12; j++) b[j] = 42.0;
    coons__coons_basis(0.3, 0, b);
    for (int j = 4; j < 12; j++) assert_near(b[j], 42.0, 0.0);
    coons__coons_basis(0.3, 1, b);
    for (int j = 8; j < 12; j++) assert_near(b[j], 42.0, 0.0);
    for (int j = 0; j < 12; j++) b[j] = 42.0;
    coons__hermite_basis(0.3, 1, b);
    for (int j = 8; j < 12; j++) assert_near(b[j], 42.0, 0.0);
    assert_near(b[0], seed_H(0, 0.3), 1e-15);
}

static void test_hermite_values_match_seed(void **state)
{
    (void)state;
    for (int i = 0; i < NT; i++) {
        double t = (double)i / (NT - 1), b[12];
        hermite_at(t, b);
        for (int j = 0; j < 4; j++) assert_near(b[j], seed_H(j, t), 1e-15);
        /* the two value functions blend: H0 + H3 = 1 */
        assert_near(b[0] + b[3], 1.0, 1e-15);
        assert_near(b[4] + b[7], 0.0, 1e-14);
    }
}

/* The defining end conditions: H0 is 1 at 0 with zero slopes; H1 has slope
 * 1 at 0; H2 slope 1 at 1; H3 is 1 at 1; every other end value or slope 0. */
static void test_hermite_end_conditions(void **state)
{
    (void)state;
    double b0[12], b1[12];
    hermite_at(0.0, b0);
    hermite_at(1.0, b1);
    const double v0[4] = {1, 0, 0, 0}, v1[4] = {0, 0, 0, 1};
    const double d0[4] = {0, 1, 0, 0}, d1[4] = {0, 0, 1, 0};
    for (int j = 0; j < 4; j++) {
        assert_near(b0[j], v0[j], 0.0);
        assert_near(b1[j], v1[j], 1e-15);
        assert_near(b0[4 + j], d0[j], 0.0);
        assert_near(b1[4 + j], d1[j], 1e-15);
    }
    /* second derivatives by hand: H0'' = 12t-6, H1'' = 6t-4, H2'' = 6t-2, H3'' = 6-12t */
    const double s0[4] = {-6, -4, -2, 6}, s1[4] = {6, 2, 4, -6};
    for (int j = 0; j < 4; j++) {
        assert_near(b0[8 + j], s0[j], 1e-15);
        assert_near(b1[8 + j], s1[j], 1e-14);
    }
}

static void test_hermite_derivatives_fd(void **state)
{
    (void)state;
    check_derivs_fd(hermite_at, seed_H);
}

/* Blending pairs (seed 001 section 1.2.1): both sum to 1 with f(0) = 1,
 * f(1) = 0; the cubic one f = 1 - 3t^2 + 2t^3 has zero slope at both ends. */
static void test_blends(void **state)
{
    (void)state;
    const double h = 1e-5;
    for (int kind = 0; kind < 2; kind++) {
        coons_blend k = kind ? COONS_BLEND_CUBIC : COONS_BLEND_LINEAR;
        for (int i = 0; i < NT; i++) {
            double t = (double)i / (NT - 1), b[6], bp[6], bm[6];
            coons__blend(k, t, 2, b);
            assert_near(b[0] + b[1], 1.0, 1e-15);
            assert_near(b[2] + b[3], 0.0, 1e-15);
            assert_near(b[4] + b[5], 0.0, 1e-15);
            double f = kind ? 1.0 - 3.0 * t * t + 2.0 * t * t * t : 1.0 - t;
            assert_near(b[0], f, 1e-15);
            coons__blend(k, t + h, 0, bp);
            coons__blend(k, t - h, 0, bm);
            assert_near(b[2], (bp[0] - bm[0]) / (2 * h), 1e-8);
            assert_near(b[4], (bp[0] - 2 * b[0] + bm[0]) / (h * h), 1e-4);
        }
        double e[6];
        coons__blend(k, 0.0, 2, e);
        assert_near(e[0], 1.0, 0.0);
        assert_near(e[1], 0.0, 0.0);
        coons__blend(k, 1.0, 2, e);
        assert_near(e[0], 0.0, 0.0);
        assert_near(e[1], 1.0, 0.0);
        if (kind) {
            coons__blend(k, 0.0, 1, e);
            assert_near(e[2], 0.0, 0.0);
            coons__blend(k, 1.0, 1, e);
            assert_near(e[2], 0.0, 0.0);
        } else {
            assert_near(e[2], -1.0, 0.0);
            assert_near(e[4], 0.0, 0.0);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_coons_values_match_seed),
        cmocka_unit_test(test_coons_partition_of_unity),
        cmocka_unit_test(test_coons_end_values),
        cmocka_unit_test(test_coons_symmetry),
        cmocka_unit_test(test_coons_derivatives_fd),
        cmocka_unit_test(test_order_argument),
        cmocka_unit_test(test_hermite_values_match_seed),
        cmocka_unit_test(test_hermite_end_conditions),
        cmocka_unit_test(test_hermite_derivatives_fd),
        cmocka_unit_test(test_blends),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
