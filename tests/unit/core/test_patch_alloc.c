/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Allocation failure at every allocation point of every patch constructor,
 * of coons_patch_copy and of coons_patch_eval_grid: COONS_E_NOMEM, *out
 * NULL and nothing left allocated (libcbor's failing-malloc tests). */
#include <string.h>

#include "patch_fixture.h"

typedef struct ctx {
    fx_boundary b;
    coons_curve *cross[4];
    coons_patch *src; /* for copy and grid */
    double net[4][5][3], w[4][5];
} ctx;

typedef coons_status (*build_fn)(ctx *c, coons_patch **out, coons_error *err);

static coons_status b_bilinear(ctx *c, coons_patch **out, coons_error *err)
{
    (void)c;
    return coons_patch_new_bilinear(fx_corner[0], out, err);
}
static coons_status b_ruled(ctx *c, coons_patch **out, coons_error *err)
{
    return coons_patch_new_ruled(c->b.c[COONS_SIDE_T0], c->b.c[COONS_SIDE_S0], out, err);
}
static coons_status b_coons(ctx *c, coons_patch **out, coons_error *err)
{
    return coons_patch_new_coons(fx_curves(&c->b), COONS_BLEND_CUBIC, 0.0, out, err);
}
static coons_status b_hermite(ctx *c, coons_patch **out, coons_error *err)
{
    coons_hermite_options o = COONS_HERMITE_OPTIONS_INIT;
    o.twist = COONS_TWIST_ADINI;
    return coons_patch_new_hermite_coons(fx_curves(&c->b), &o, out, err);
}
static coons_status b_hermite_cross(ctx *c, coons_patch **out, coons_error *err)
{
    coons_hermite_options o = COONS_HERMITE_OPTIONS_INIT;
    for (int k = 0; k < 4; k++) o.cross[k] = c->cross[k];
    o.tol = 1e6; /* only allocation is under test here */
    return coons_patch_new_hermite_coons(fx_curves(&c->b), &o, out, err);
}
static coons_status b_bezier(ctx *c, coons_patch **out, coons_error *err)
{
    return coons_patch_new_bezier(&c->net[0][0][0], 4, 5, out, err);
}
static coons_status b_bspline(ctx *c, coons_patch **out, coons_error *err)
{
    return coons_patch_new_bspline(2, 3, &c->net[0][0][0], 4, 5, NULL, NULL, NULL, out, err);
}
static coons_status b_nurbs(ctx *c, coons_patch **out, coons_error *err)
{
    const double ks[7] = {0, 0, 0, 0.3, 1, 1, 1};
    const double kt[9] = {0, 0, 0, 0, 2, 5, 5, 5, 5};
    return coons_patch_new_bspline(2, 3, &c->net[0][0][0], 4, 5, ks, kt, &c->w[0][0], out, err);
}
static coons_status b_copy(ctx *c, coons_patch **out, coons_error *err)
{
    return coons_patch_copy(c->src, out, err);
}

/* Runs f with the n-th allocation failing for n = 0, 1, ... until it
 * succeeds; returns the number of allocations of the successful call. */
static long run_failing(build_fn f, ctx *c)
{
    for (long n = 0; n < 1000; n++) {
        coons_error err = COONS_ERROR_INIT;
        coons_patch *p = (coons_patch *)&err; /* must come back NULL on failure */
        coons_test_fail_after(n);
        coons_status rc = f(c, &p, &err);
        if (rc == COONS_OK) {
            coons_patch_free(p);
            long live = coons_test_live_allocs();
            coons_test_fail_after(-1);
            assert_int_equal(live, 0);
            return n;
        }
        long live = coons_test_live_allocs();
        coons_test_fail_after(-1);
        if (rc != COONS_E_NOMEM) fail_msg("allocation %ld failing gave %d: %s", n, rc, err.message);
        assert_int_equal(err.code, COONS_E_NOMEM);
        assert_null(p);
        assert_int_equal(live, 0);
    }
    fail_msg("never succeeded");
    return -1;
}

static void ctx_make(ctx *c)
{
    memset(c, 0, sizeof *c);
    fx_boundary_make(&c->b);
    coons_error err = COONS_ERROR_INIT;
    const double v[3] = {0.1, 0.2, 0.3}, w[3] = {-0.1, 0.0, 0.4};
    for (int k = 0; k < 4; k++)
        assert_coons_ok(coons_curve_new_line(v, w, &c->cross[k], &err), &err);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 5; j++) {
            c->net[i][j][0] = i;
            c->net[i][j][1] = j;
            c->net[i][j][2] = 0.1 * i * j;
            c->w[i][j] = 1.0 + 0.1 * j;
        }
}

static void ctx_free(ctx *c)
{
    fx_boundary_free(&c->b);
    for (int k = 0; k < 4; k++) coons_curve_free(c->cross[k]);
    coons_patch_free(c->src);
}

static const build_fn builders[] = {b_bilinear, b_ruled,  b_coons,  b_hermite, b_hermite_cross,
                                    b_bezier,   b_bspline, b_nurbs};
static const int n_builders = (int)(sizeof builders / sizeof builders[0]);

/* Given each constructor, when allocation n fails, then COONS_E_NOMEM and
 * no leak; the count of allocations shows every point was visited. */
static void test_constructors_fail_cleanly(void **state)
{
    (void)state;
    ctx c;
    ctx_make(&c);
    for (int k = 0; k < n_builders; k++) {
        long n = run_failing(builders[k], &c);
        assert_true(n >= 1);
    }
    /* a Coons patch copies 4 curves (each a record and its arrays) */
    assert_true(run_failing(b_coons, &c) >= 1 + 4 * 2);
    assert_true(run_failing(b_hermite_cross, &c) >= 1 + 8 * 2);
    ctx_free(&c);
}

/* Given a patch of each kind, when copying with allocation n failing,
 * then COONS_E_NOMEM and no leak. */
static void test_copy_fails_cleanly(void **state)
{
    (void)state;
    ctx c;
    ctx_make(&c);
    for (int k = 0; k < n_builders; k++) {
        coons_error err = COONS_ERROR_INIT;
        assert_coons_ok(builders[k](&c, &c.src, &err), &err);
        assert_true(run_failing(b_copy, &c) >= 1);
        coons_patch_free(c.src);
        c.src = NULL;
    }
    ctx_free(&c);
}

/* Given a patch of each kind, when the grid's scratch allocation fails,
 * then COONS_E_NOMEM and the next call works. */
static void test_grid_fails_cleanly(void **state)
{
    (void)state;
    ctx c;
    ctx_make(&c);
    const double s[3] = {0, 0.5, 1}, t[4] = {0, 0.2, 0.7, 1};
    double out[36];
    for (int k = 0; k < n_builders; k++) {
        coons_error err = COONS_ERROR_INIT;
        coons_patch *p = NULL;
        assert_coons_ok(builders[k](&c, &p, &err), &err);
        coons_test_fail_after(0);
        coons_status rc = coons_patch_eval_grid(p, s, 3, t, 4, out, &err);
        long live = coons_test_live_allocs();
        coons_test_fail_after(-1);
        assert_int_equal(rc, COONS_E_NOMEM);
        assert_int_equal(live, 0);
        coons_test_fail_after(1);
        rc = coons_patch_eval_grid(p, s, 3, t, 4, out, &err);
        live = coons_test_live_allocs();
        coons_test_fail_after(-1);
        assert_int_equal(rc, COONS_OK);
        assert_int_equal(live, 0);
        coons_patch_free(p);
    }
    ctx_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_constructors_fail_cleanly),
        cmocka_unit_test(test_copy_fails_cleanly),
        cmocka_unit_test(test_grid_fails_cleanly),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
