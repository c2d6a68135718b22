/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Readers of the curves given by their points alone: line (2 points),
 * polyline (2 or more), bezier (2 or more, degree at most
 * COONS_SPLINE_MAX_DEGREE) and clamped-cubic (4 or more).
 */
#include "loader.h"

static const char *const KEYS[] = {"type", "points", NULL};

typedef coons_status (*make_fn)(const double *pts, size_t n, coons_curve **out,
                                coons_error *err);

static coons_status points_curve(coons__ld *L, coons__ld_obj *o, size_t min, int exact,
                                 size_t maxdir, make_fn make, coons_curve **out)
{
    size_t v[2];
    coons_status rc = coons__ld_keys(L, o, KEYS, v);
    if (!rc) rc = coons__ld_need(L, o->tok, v[1], "points", o->need);
    if (rc) return rc;
    coons__ld_netspec ns = {1, COONS__LD_POINT, NULL, min, exact, maxdir, o->what, "points"};
    double *pts = NULL;
    size_t shape[3];
    rc = coons__ld_net_key(L, v[1], "points", &ns, shape, &pts);
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        rc = coons__ld_built(L, o->tok, make(pts, shape[0], out, &e), o->what, &e);
    }
    coons__free(pts);
    return rc;
}

static coons_status make_line(const double *pts, size_t n, coons_curve **out, coons_error *err)
{
    (void)n;
    return coons_curve_new_line(pts, pts + 3, out, err);
}

/* Wrappers, not the constructors themselves: calls survive their renaming
 * to macros. */
static coons_status make_polyline(const double *pts, size_t n, coons_curve **out,
                                  coons_error *err)
{
    return coons_curve_new_polyline(pts, n, out, err);
}

static coons_status make_bezier(const double *pts, size_t n, coons_curve **out, coons_error *err)
{
    return coons_curve_new_bezier(pts, n, out, err);
}

static coons_status make_clamped(const double *pts, size_t n, coons_curve **out,
                                 coons_error *err)
{
    return coons_curve_new_clamped_cubic(pts, n, out, err);
}

coons_status coons__ld_read_line(coons__ld *L, coons__ld_obj *o, coons_curve **out)
{
    return points_curve(L, o, 2, 1, 0, make_line, out);
}

coons_status coons__ld_read_polyline(coons__ld *L, coons__ld_obj *o, coons_curve **out)
{
    return points_curve(L, o, 2, 0, 0, make_polyline, out);
}

coons_status coons__ld_read_bezier(coons__ld *L, coons__ld_obj *o, coons_curve **out)
{
    return points_curve(L, o, 2, 0, COONS_SPLINE_MAX_DEGREE + 1, make_bezier, out);
}

coons_status coons__ld_read_clamped_cubic(coons__ld *L, coons__ld_obj *o, coons_curve **out)
{
    return points_curve(L, o, 4, 0, 0, make_clamped, out);
}
