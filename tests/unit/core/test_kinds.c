/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The type tables of the core (src/core/kinds.h, kinds.c): one row per
 * curve, patch and body type. White-box (linked against the static
 * library, whose internal symbols the shared one hides): every enum value
 * has a complete row of its own type and name, every constructor points
 * its record at the row of its type, each row's copy is deep, and the
 * breakpoints reach the volume code through the rows, and each row's grid
 * det J and partials agree with its point evaluation.
 */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "body_fixtures.h"
#include "patch_fixture.h"
#include "test_util.h"

#include "body_impl.h"
#include "curve_impl.h"
#include "patch_impl.h"

/* The library's allocations poisoned on free (a copy that shares data with
 * a freed original then reads 0xff bytes, NaN) and counted (every row's
 * free must release what its copy and constructor made). */
typedef union hdr {
    size_t n;
    max_align_t align;
} hdr;
static long live;

static void *p_malloc(size_t n)
{
    hdr *h = malloc(sizeof *h + n);
    if (!h) return NULL;
    h->n = n;
    live++;
    return h + 1;
}

static void p_free(void *p)
{
    if (!p) return;
    hdr *h = (hdr *)p - 1;
    memset(p, 0xff, h->n);
    live--;
    free(h);
}

static void *p_realloc(void *p, size_t n)
{
    if (!p) return p_malloc(n);
    void *q = p_malloc(n);
    if (!q) return NULL;
    size_t old = ((hdr *)p - 1)->n;
    memcpy(q, p, old < n ? old : n);
    p_free(p);
    return q;
}

static int setup(void **state)
{
    (void)state;
    live = 0;
    coons_set_allocator(p_malloc, p_realloc, p_free);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    coons_set_allocator(NULL, NULL, NULL);
    assert_int_equal(live, 0); /* nothing leaked */
    return 0;
}

/* ---- the tables ------------------------------------------------------ */

static void test_curve_rows(void **state)
{
    (void)state;
    int n = 0;
    for (int t = 0; coons_curve_type_name((coons_curve_type)t); t++, n++) {
        const coons__curve_kind *k = coons__curve_kind_of((coons_curve_type)t);
        assert_non_null(k);
        assert_int_equal(k->type, t);
        assert_non_null(k->eval);
        assert_non_null(k->bezier);
        assert_non_null(k->breaks);
        assert_non_null(k->copy);
        assert_non_null(k->free);
        coons_curve_type back;
        assert_int_equal(coons_curve_type_from_name(coons_curve_type_name((coons_curve_type)t),
                                                    &back, NULL),
                         COONS_OK);
        assert_int_equal(back, t);
    }
    assert_int_equal(n, 7);
    assert_null(coons__curve_kind_of((coons_curve_type)n));
    assert_null(coons__curve_kind_of((coons_curve_type)-1));
    assert_null(coons_curve_type_name((coons_curve_type)-1));
}

static void test_patch_rows(void **state)
{
    (void)state;
    int n = 0;
    for (int t = 0; coons_patch_type_name((coons_patch_type)t); t++, n++) {
        const coons__patch_kind *k = coons__patch_kind_of((coons_patch_type)t);
        assert_non_null(k);
        assert_int_equal(k->type, t);
        assert_non_null(k->eval);
        assert_non_null(k->grid);
        assert_non_null(k->control_bbox);
        assert_non_null(k->copy);
        assert_non_null(k->free);
        /* A Boolean-sum type has both lines, any other neither. */
        assert_int_equal(k->sline != NULL, k->tline != NULL);
        assert_int_equal(k->sline != NULL, k->eval == coons__boolsum_eval);
        coons_patch_type back;
        assert_int_equal(coons_patch_type_from_name(coons_patch_type_name((coons_patch_type)t),
                                                    &back, NULL),
                         COONS_OK);
        assert_int_equal(back, t);
    }
    assert_int_equal(n, COONS_PATCH_NETWORK + 1); /* the last patch type */
    assert_null(coons__patch_kind_of((coons_patch_type)n));
}

static void test_body_rows(void **state)
{
    (void)state;
    int n = 0;
    for (int t = 0; coons_body_type_name((coons_body_type)t); t++, n++) {
        const coons__body_kind *k = coons__body_kind_of((coons_body_type)t);
        assert_non_null(k);
        assert_int_equal(k->type, t);
        assert_non_null(k->eval);
        assert_non_null(k->grid);
        /* a type that owns memory copies and frees it */
        assert_int_equal(k->copy != NULL, k->free != NULL);
        coons_body_type back;
        assert_int_equal(coons_body_type_from_name(coons_body_type_name((coons_body_type)t),
                                                   &back, NULL),
                         COONS_OK);
        assert_int_equal(back, t);
    }
    assert_int_equal(n, COONS_BODY_MORPH + 1); /* the last body type */
    assert_null(coons__body_kind_of((coons_body_type)n));
    coons_error err = COONS_ERROR_INIT;
    coons_body_type bt;
    assert_int_equal(coons_body_type_from_name("body3", &bt, &err), COONS_E_INVALID);
    assert_string_equal(err.message, "unknown body type \"body3\"");
}

/* ---- one object of every type ----------------------------------------- */

enum { NCURVES = 7, NPATCHES = 6 };

static void make_curves(coons_curve *c[NCURVES])
{
    coons_error err = COONS_ERROR_INIT;
    static const double P[5][3] = {{0, 0, 0}, {1, 0.5, 0}, {2, 0.2, 1}, {3, 1, 0.5}, {4, 0, 0}};
    static const double T0[3] = {1, 1, 0}, T1[3] = {0, 1, 1};
    static const double knots[8] = {0, 0, 0, 0.4, 0.7, 1, 1, 1}, w[5] = {1, 2, 0.5, 1, 1.5};
    assert_coons_ok(coons_curve_new_line(P[0], P[1], &c[COONS_CURVE_LINE], &err), &err);
    assert_coons_ok(coons_curve_new_polyline(P[0], 5, &c[COONS_CURVE_POLYLINE], &err), &err);
    assert_coons_ok(coons_curve_new_bezier(P[0], 4, &c[COONS_CURVE_BEZIER], &err), &err);
    assert_coons_ok(coons_curve_new_hermite(P[0], T0, P[2], T1, &c[COONS_CURVE_HERMITE], &err),
                    &err);
    assert_coons_ok(coons_curve_new_coons_cubic(P[0], 5, 1, &c[COONS_CURVE_COONS_CUBIC], &err),
                    &err);
    assert_coons_ok(coons_curve_new_clamped_cubic(P[0], 5, &c[COONS_CURVE_CLAMPED_CUBIC], &err),
                    &err);
    assert_coons_ok(coons_curve_new_bspline(2, P[0], 5, knots, w, &c[COONS_CURVE_BSPLINE], &err),
                    &err);
}

static void make_patches(coons_patch *p[NPATCHES])
{
    coons_error err = COONS_ERROR_INIT;
    fx_boundary b;
    fx_boundary_make(&b);
    double net[3 * 4 * 3];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 3; j++) {
            double *q = net + 3 * (i * 3 + j);
            q[0] = i;
            q[1] = j;
            q[2] = 0.3 * sin(i + 2.0 * j);
        }
    static const double ks[7] = {0, 0, 0, 0.5, 1, 1, 1};
    assert_coons_ok(coons_patch_new_bilinear(fx_corner[0], &p[COONS_PATCH_BILINEAR], &err), &err);
    assert_coons_ok(coons_patch_new_ruled(b.c[COONS_SIDE_T0], b.c[COONS_SIDE_T1], &p[COONS_PATCH_RULED], &err),
                    &err);
    assert_coons_ok(coons_patch_new_coons(fx_curves(&b), COONS_BLEND_CUBIC, COONS_TOL_DEFAULT,
                                          &p[COONS_PATCH_COONS], &err),
                    &err);
    assert_coons_ok(
        coons_patch_new_hermite_coons(fx_curves(&b), NULL, &p[COONS_PATCH_HERMITE_COONS], &err),
        &err);
    assert_coons_ok(coons_patch_new_bezier(net, 4, 3, &p[COONS_PATCH_BEZIER], &err), &err);
    assert_coons_ok(
        coons_patch_new_bspline(2, 2, net, 4, 3, ks, NULL, NULL, &p[COONS_PATCH_BSPLINE], &err),
        &err);
    fx_boundary_free(&b);
}

static void test_records_point_at_their_row(void **state)
{
    (void)state;
    coons_curve *c[NCURVES];
    coons_patch *p[NPATCHES];
    coons_body *b[TB_MAX_BODIES];
    make_curves(c);
    make_patches(p);
    tb_all_bodies(b);
    for (int t = 0; t < NCURVES; t++) {
        assert_int_equal(coons_curve_kind(c[t]), t);
        assert_ptr_equal(c[t]->kind, coons__curve_kind_of((coons_curve_type)t));
    }
    for (int t = 0; t < NPATCHES; t++) {
        assert_int_equal(coons_patch_kind(p[t]), t);
        assert_ptr_equal(p[t]->kind, coons__patch_kind_of((coons_patch_type)t));
    }
    int seen[5] = {0};
    for (int m = 0; m < TB_MAX_BODIES; m++) {
        coons_body_type t = coons_body_kind(b[m]);
        assert_ptr_equal(b[m]->kind, coons__body_kind_of(t));
        seen[t] = 1;
    }
    for (int t = 0; t < 5; t++) assert_true(seen[t]);
    for (int t = 0; t < NCURVES; t++) coons_curve_free(c[t]);
    for (int t = 0; t < NPATCHES; t++) coons_patch_free(p[t]);
    for (int m = 0; m < TB_MAX_BODIES; m++) coons_body_free(b[m]);
}

/* ---- copies through the rows are deep ---------------------------------- */

static const double PAR[4] = {0.0, 0.3, 0.71, 1.0};

static void test_copies_are_deep(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_curve *c[NCURVES];
    coons_patch *p[NPATCHES];
    coons_body *b[TB_MAX_BODIES];
    make_curves(c);
    make_patches(p);
    tb_all_bodies(b);
    for (int t = 0; t < NCURVES; t++) {
        double before[4][3][3], after[3][3];
        for (int i = 0; i < 4; i++) coons_curve_eval_derivs(c[t], PAR[i], 2, before[i]);
        coons_curve *d = NULL;
        assert_coons_ok(coons_curve_copy(c[t], &d, &err), &err);
        coons_curve_free(c[t]); /* the copy must not share its data */
        for (int i = 0; i < 4; i++) {
            coons_curve_eval_derivs(d, PAR[i], 2, after);
            assert_memory_equal(before[i], after, sizeof after);
        }
        coons_curve_free(d);
    }
    for (int t = 0; t < NPATCHES; t++) {
        double before[4][6][3], after[6][3];
        for (int i = 0; i < 4; i++) coons_patch_eval_derivs(p[t], PAR[i], PAR[3 - i], 2, before[i]);
        coons_patch *d = NULL;
        assert_coons_ok(coons_patch_copy(p[t], &d, &err), &err);
        coons_patch_free(p[t]);
        for (int i = 0; i < 4; i++) {
            coons_patch_eval_derivs(d, PAR[i], PAR[3 - i], 2, after);
            assert_memory_equal(before[i], after, sizeof after);
        }
        coons_patch_free(d);
    }
    for (int m = 0; m < TB_MAX_BODIES; m++) {
        double before[4][3], jb[4][3][3], after[3], ja[3][3];
        for (int i = 0; i < 4; i++)
            coons_body_eval_jacobian(b[m], PAR[i], PAR[3 - i], PAR[(i + 1) % 4], before[i], jb[i]);
        coons_body *d = NULL;
        assert_coons_ok(coons_body_copy(b[m], &d, &err), &err);
        coons_body_free(b[m]);
        for (int i = 0; i < 4; i++) {
            coons_body_eval_jacobian(d, PAR[i], PAR[3 - i], PAR[(i + 1) % 4], after, ja);
            assert_memory_equal(before[i], after, sizeof after);
            assert_memory_equal(jb[i], ja, sizeof ja);
        }
        coons_body_free(d);
    }
}

/* ---- breakpoints through the rows --------------------------------------- */

static void expect_breaks(const coons_body *b, int d, const double *want, size_t n)
{
    double *v = NULL;
    size_t m = 0;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons__body_breaks(b, d, &v, &m, &err), &err);
    assert_int_equal(m, n);
    for (size_t i = 0; i < n; i++) assert_near(v[i], want[i], 1e-15);
    coons__free(v);
}

static void test_breaks_come_from_the_rows(void **state)
{
    (void)state;
    coons_body *b[TB_MAX_BODIES];
    tb_all_bodies(b);
    /* body0: no data between the corners */
    static const double ends[2] = {0, 1};
    for (int d = 0; d < 3; d++) expect_breaks(b[0], d, ends, 2);
    /* bspline volume (fixture 5): u knots 0.3, 0.6; v knots 0.2, 0.7; w uniform */
    static const double bu[4] = {0, 0.3, 0.6, 1}, bv[4] = {0, 0.2, 0.7, 1};
    expect_breaks(b[5], 0, bu, 4);
    expect_breaks(b[5], 1, bv, 4);
    static const double bw[3] = {0, 0.5, 1};
    expect_breaks(b[5], 2, bw, 3);
    /* body2 from 6 x 6 cubic B-spline faces (fixture 8): knots 1/3, 2/3 */
    static const double thirds[4] = {0, 1.0 / 3.0, 2.0 / 3.0, 1};
    for (int d = 0; d < 3; d++) expect_breaks(b[8], d, thirds, 4);
    for (int m = 0; m < TB_MAX_BODIES; m++) coons_body_free(b[m]);

    /* body1 whose edge u00 is a polyline with a corner at its middle */
    coons_curve *e[12];
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(tb_curved_edges(e, &err), &err);
    const double(*hex)[3] = tb_hex();
    double poly[9];
    for (int r = 0; r < 3; r++) {
        poly[r] = hex[0][r];
        poly[3 + r] = 0.5 * (hex[0][r] + hex[4][r]) + 0.2;
        poly[6 + r] = hex[4][r];
    }
    coons_curve_free(e[0]);
    assert_coons_ok(coons_curve_new_polyline(poly, 3, &e[0], &err), &err);
    coons_body *b1 = NULL;
    assert_coons_ok(coons_body_new_body1(e, COONS_BLEND_LINEAR,
                                         COONS_TOL_DEFAULT, &b1, &err),
                    &err);
    static const double half[3] = {0, 0.5, 1};
    expect_breaks(b1, 0, half, 3);
    expect_breaks(b1, 1, ends, 2);
    expect_breaks(b1, 2, ends, 2);
    coons_body_free(b1);
    for (int k = 0; k < 12; k++) coons_curve_free(e[k]);

    /* a closed Coons cubic of 5 points has 5 equal segments */
    static const double P[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 1}, {-1, 0.5, 0}};
    coons_curve *cc = NULL;
    assert_coons_ok(coons_curve_new_coons_cubic(P[0], 5, 1, &cc, &err), &err);
    coons__breaks B = {0};
    coons__curve_breaks(cc, &B);
    assert_int_equal(B.n, 4);
    for (size_t i = 0; i < 4; i++) assert_near(B.v[i], (double)(i + 1) / 5.0, 1e-15);
    coons__free(B.v);
    coons_curve_free(cc);
}

/* The grid paths of det J and of the partials (each row's det_grid, or
 * point by point where a row has none) agree with
 * coons_body_eval_jacobian() at every point of a grid: every sample body,
 * its affine image, and morphs (seed 000 section 4) of a body and another's
 * affine image on a smooth path, whose partials are the blend of the keys'
 * grid partials. */
static void expect_grid_jacobian(const coons_body *b, const char *what)
{
    static const double u[4] = {0.0, 0.3, 0.71, 1.0}, v[3] = {0.05, 0.5, 1.0}, w[2] = {0.0, 0.6};
    enum { NP = 4 * 3 * 2 };
    double det[NP], jac[9 * NP];
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons__body_det_grid(b, u, 4, v, 3, w, 2, det, &err), &err);
    assert_coons_ok(coons__body_jac_grid(b, u, 4, v, 3, w, 2, jac, &err), &err);
    for (int n = 0; n < NP; n++) {
        double p[3], J[3][3];
        double d = coons_body_eval_jacobian(b, u[n / 6], v[(n / 2) % 3], w[n % 2], p, J);
        double scale = 0;
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) scale = fmax(scale, fabs(J[r][c]));
        for (int c = 0; c < 3; c++)
            for (int r = 0; r < 3; r++)
                if (!(fabs(jac[9 * n + 3 * c + r] - J[r][c]) <= 1e-12 * (1 + scale)))
                    fail_msg("%s: point %d: partial %d component %d: grid %.17g, point %.17g",
                             what, n, c, r, jac[9 * n + 3 * c + r], J[r][c]);
        if (!(fabs(det[n] - d) <= 1e-11 * (1 + scale * scale * scale)))
            fail_msg("%s: point %d: det J grid %.17g, point %.17g", what, n, det[n], d);
    }
}

static void test_grid_jacobians(void **state)
{
    (void)state;
    coons_body *b[TB_MAX_BODIES], *x[TB_MAX_BODIES];
    tb_all_bodies(b);
    coons_error err = COONS_ERROR_INIT;
    /* a rotation about z with a scale, a shear and a shift: det 1.5 */
    const double A[12] = {0, -1.5, 0.2, 1, 1, 0, 0, -2, 0, 0, 1, 0.5};
    for (int m = 0; m < TB_MAX_BODIES; m++) {
        assert_coons_ok(coons_body_new_transformed(b[m], A, &x[m], &err), &err);
        expect_grid_jacobian(b[m], tb_body_label(m));
        expect_grid_jacobian(x[m], tb_body_label(m));
    }
    const double at[3] = {0.0, 0.4, 1.0};
    for (int m = 0; m < TB_MAX_BODIES; m++) {
        coons_body *keys[3] = {b[m], x[(m + 3) % TB_MAX_BODIES], b[(m + 7) % TB_MAX_BODIES]};
        coons_body *mo = NULL, *xm = NULL;
        assert_coons_ok(coons_body_new_morph(keys, 3, at, COONS_MORPH_SMOOTH, 0.55, &mo, &err),
                        &err);
        assert_coons_ok(coons_body_new_transformed(mo, A, &xm, &err), &err);
        expect_grid_jacobian(mo, "morph");
        expect_grid_jacobian(xm, "transformed morph");
        coons_body_free(xm);
        coons_body_free(mo);
    }
    for (int m = 0; m < TB_MAX_BODIES; m++) {
        coons_body_free(x[m]);
        coons_body_free(b[m]);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_curve_rows, setup, teardown),
        cmocka_unit_test_setup_teardown(test_patch_rows, setup, teardown),
        cmocka_unit_test_setup_teardown(test_body_rows, setup, teardown),
        cmocka_unit_test_setup_teardown(test_records_point_at_their_row, setup, teardown),
        cmocka_unit_test_setup_teardown(test_copies_are_deep, setup, teardown),
        cmocka_unit_test_setup_teardown(test_breaks_come_from_the_rows, setup, teardown),
        cmocka_unit_test_setup_teardown(test_grid_jacobians, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
