/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * An ordinary client of an installed libcoons: includes only <coons.h>,
 * builds objects through the public API and checks values computed here by
 * hand. tests/cli/test_install.py builds it against the installed library
 * with pkg-config (shared and static) and with CMake's find_package(coons),
 * then runs it. Exit status 0 means every check passed.
 */
#include <coons.h>

#include <stdio.h>
#include <string.h>

static int failures;

static double dist3(const double a[3], const double b[3])
{
    double s = 0.0;
    for (int i = 0; i < 3; i++)
        s += (a[i] - b[i]) * (a[i] - b[i]);
    return s; /* squared: no libm needed */
}

static void check_point(const char *what, const double got[3], const double want[3])
{
    if (!(dist3(got, want) <= 1e-24)) {
        printf("FAIL %s: got (%.17g %.17g %.17g), want (%.17g %.17g %.17g)\n", what, got[0],
               got[1], got[2], want[0], want[1], want[2]);
        failures++;
    }
}

static void check(const char *what, int ok)
{
    if (!ok) {
        printf("FAIL %s\n", what);
        failures++;
    }
}

/* The run-time library is the one the header describes. */
static void test_version(void)
{
    char expect[32];
    snprintf(expect, sizeof expect, "%d.%d.%d", COONS_VERSION_MAJOR, COONS_VERSION_MINOR,
             COONS_VERSION_PATCH);
    check("coons_version() == COONS_VERSION_NUMBER", coons_version() == COONS_VERSION_NUMBER);
    check("coons_version_string() == COONS_VERSION_STRING",
          strcmp(coons_version_string(), COONS_VERSION_STRING) == 0);
    check("COONS_VERSION_STRING is major.minor.patch", strcmp(COONS_VERSION_STRING, expect) == 0);
}

/* Quadratic Bezier: x(1/2) = P0/4 + P1/2 + P2/4, derivative 2(P2 - P0)/2 = P2 - P0. */
static void test_curve(void)
{
    const double pts[9] = {0, 0, 0, 1, 2, 0, 3, 3, 1};
    coons_curve *c = NULL;
    coons_error err = COONS_ERROR_INIT;
    coons_status st = coons_curve_bezier(pts, 3, &c, &err);
    check("coons_curve_bezier succeeds", st == COONS_OK && c != NULL);
    if (c) {
        double p[3], d[2][3];
        const double want[3] = {1.25, 1.75, 0.25}, want_d[3] = {3, 3, 1};
        coons_curve_eval(c, 0.5, p);
        check_point("bezier(1/2)", p, want);
        coons_curve_eval_derivs(c, 0.5, 1, d);
        check_point("bezier'(1/2)", d[1], want_d);
        check("coons_curve_get_type", coons_curve_get_type(c) == COONS_CURVE_BEZIER);
    }
    coons_curve_free(c);
    coons_curve_free(NULL); /* a harmless no-op */
}

/* A failing call returns a negative status, fills err and leaves *out NULL. */
static void test_error(void)
{
    const double one[3] = {1, 2, 3};
    coons_curve *c = NULL;
    coons_error err = COONS_ERROR_INIT;
    coons_status st = coons_curve_polyline(one, 1, &c, &err);
    check("polyline of 1 point is COONS_E_INVALID", st == COONS_E_INVALID);
    check("err.code is the status", err.code == (int)st);
    check("err.message is set", err.message[0] != '\0');
    check("no object on failure", c == NULL);
    check("coons_strerror", coons_strerror(st) != NULL && coons_strerror(st)[0] != '\0');
    /* err may be NULL. */
    check("NULL err accepted", coons_curve_polyline(one, 1, &c, NULL) == COONS_E_INVALID);
}

int main(void)
{
    test_version();
    test_curve();
    test_error();
    if (failures) {
        printf("%d check(s) failed\n", failures);
        return 1;
    }
    printf("consumer: all checks passed (libcoons %s)\n", coons_version_string());
    return 0;
}
