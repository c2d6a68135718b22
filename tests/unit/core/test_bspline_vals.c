/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * White-box test of the inline B-spline bases of src/core/bspline.h that
 * coons__bspline_basis() takes for nd = 0 and nd = 1 and body2.c's batch of
 * points inlines: coons__bspline_vals (A2.2 in place),
 * coons__bspline_vals1 (values and first derivatives) and
 * coons__bernstein_vals, each bit for bit against the triangular algorithm
 * they replace (The NURBS Book A2.3, as bspline.c had it, copied here), and
 * coons__bspline_span_inl against a linear search: every degree 1..max,
 * knot vectors with repeated interior knots, parameters on and between the
 * knots and at both ends.
 */
#include <math.h>
#include <string.h>

#include "body_fixtures.h" /* tb_rng */
#include "bspline.h"

#define MAXP COONS_SPLINE_MAX_DEGREE

/* A2.3 with derivatives up to nd (the reference: bspline.c before the
 * inline variants). */
static void a23(const double *k, size_t span, int p, double x, int nd, double *ders)
{
    double ndu[MAXP + 1][MAXP + 1], left[MAXP + 1], right[MAXP + 1], a[2][MAXP + 1];
    ndu[0][0] = 1.0;
    for (int j = 1; j <= p; j++) {
        left[j] = x - k[span + 1 - (size_t)j];
        right[j] = k[span + (size_t)j] - x;
        double saved = 0.0;
        for (int r = 0; r < j; r++) {
            ndu[j][r] = right[r + 1] + left[j - r];
            double temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    for (int j = 0; j <= p; j++) ders[j] = ndu[j][p];
    for (int r = 0; r <= p; r++) {
        int s1 = 0, s2 = 1;
        a[0][0] = 1.0;
        for (int d = 1; d <= nd; d++) {
            double dv = 0.0;
            int rk = r - d, pk = p - d;
            if (r >= d) {
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
                dv = a[s2][0] * ndu[rk][pk];
            }
            int j1 = rk >= -1 ? 1 : -rk;
            int j2 = (r - 1 <= pk) ? d - 1 : p - r;
            for (int j = j1; j <= j2; j++) {
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
                dv += a[s2][j] * ndu[rk + j][pk];
            }
            if (r <= pk) {
                a[s2][d] = -a[s1][d - 1] / ndu[pk + 1][r];
                dv += a[s2][d] * ndu[r][pk];
            }
            ders[d * (p + 1) + r] = dv;
            int tmp = s1;
            s1 = s2;
            s2 = tmp;
        }
    }
    double f = (double)p;
    for (int d = 1; d <= nd; d++) {
        for (int j = 0; j <= p; j++) ders[d * (p + 1) + j] *= f;
        f *= (double)(p - d);
    }
}

/* Bernstein by the table b[m][j] (coons__bernstein's values). */
static void bern_table(int n, double t, double *out)
{
    double b[MAXP + 1][MAXP + 1], s = 1.0 - t;
    b[0][0] = 1.0;
    for (int m = 1; m <= n; m++) {
        b[m][0] = s * b[m - 1][0];
        for (int j = 1; j < m; j++) b[m][j] = s * b[m - 1][j] + t * b[m - 1][j - 1];
        b[m][m] = t * b[m - 1][m - 1];
    }
    for (int j = 0; j <= n; j++) out[j] = b[n][j];
}

static int same_bits(const double *a, const double *b, size_t n)
{
    return memcmp(a, b, n * sizeof(double)) == 0;
}

/* Knot vector of degree p over ncp points: clamped ends, interior knots
 * irregular, some repeated (kind 1) up to p times. */
static size_t knots(int p, int kind, double *k)
{
    const size_t ncp = (size_t)p + 1 + 6;
    size_t n = 0;
    for (int i = 0; i <= p; i++) k[n++] = -0.75;
    const double inner[6] = {-0.5, 0.1, 0.1, 0.30000000000000004, 1.7, 1.7};
    for (int i = 0; i < 6; i++) k[n++] = kind ? inner[i] : -0.75 + 0.37 * (i + 1);
    for (int i = 0; i <= p; i++) k[n++] = 2.5;
    return ncp;
}

static void test_bases_bitwise(void **state)
{
    (void)state;
    tb_rng rng = {77};
    for (int p = 1; p <= MAXP; p++)
        for (int kind = 0; kind < 2; kind++) {
            double k[MAXP + 1 + 6 + MAXP + 1];
            const size_t ncp = knots(p, kind, k);
            for (int m = 0; m < 120; m++) {
                /* the knots themselves, both ends, and between */
                double x = m < (int)(ncp + (size_t)p + 1) ? k[m] : -0.75 + 3.25 * tb_rand(&rng);
                if (m == 119) x = 2.5;
                const size_t span = coons__bspline_span(k, ncp, p, x);
                /* the span by a linear search (right end: the last non-empty) */
                size_t lin = (size_t)p;
                for (size_t i = (size_t)p; i < ncp; i++)
                    if (k[i] < k[i + 1] && (k[i] <= x || i == (size_t)p)) lin = i;
                assert_int_equal(span, lin);
                assert_int_equal(coons__bspline_span_inl(k, ncp, p, x), span);
                double want[3 * (MAXP + 1)], got[3 * (MAXP + 1)];
                a23(k, span, p, x, 0, want);
                coons__bspline_vals(k, span, p, x, got);
                if (!same_bits(want, got, (size_t)p + 1))
                    fail_msg("values: degree %d kind %d x %.17g", p, kind, x);
                a23(k, span, p, x, 1, want);
                memset(got, 0, sizeof got);
                coons__bspline_vals1(k, span, p, x, got);
                if (!same_bits(want, got, 2 * ((size_t)p + 1)))
                    fail_msg("first derivatives: degree %d kind %d x %.17g", p, kind, x);
                /* and through the library's basis for nd 0, 1, 2 */
                for (int nd = 0; nd <= 2; nd++) {
                    a23(k, span, p, x, nd, want);
                    coons__bspline_basis(k, span, p, x, nd, got);
                    if (!same_bits(want, got, (size_t)(nd + 1) * ((size_t)p + 1)))
                        fail_msg("coons__bspline_basis nd %d: degree %d kind %d x %.17g", nd, p,
                                 kind, x);
                }
            }
        }
}

static void test_bernstein_bitwise(void **state)
{
    (void)state;
    tb_rng rng = {78};
    for (int n = 0; n <= MAXP; n++)
        for (int m = 0; m < 100; m++) {
            double t = m == 0 ? 0.0 : m == 1 ? 1.0 : m == 2 ? 0.5 : tb_rand(&rng);
            double want[MAXP + 1], got[MAXP + 1], lib[3 * (MAXP + 1)];
            bern_table(n, t, want);
            coons__bernstein_vals(n, t, got);
            if (!same_bits(want, got, (size_t)n + 1)) fail_msg("Bernstein degree %d t %.17g", n, t);
            coons__bernstein(n, t, 0, lib);
            assert_true(same_bits(want, lib, (size_t)n + 1));
        }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bases_bitwise),
        cmocka_unit_test(test_bernstein_bitwise),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
