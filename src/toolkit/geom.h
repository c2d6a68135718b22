/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The geometry toolkit: the small vector maths, boxes, distances and
 * measures that every stage uses, each written once here.
 *
 * "The same place": two points of one mesh are one point when they lie
 * within coons__same_place_tol() of each other, 1e-9 of the diagonal of
 * the points' box (COONS__REL_TOL, the consistency tolerance of the model
 * format's "Consistency") plus a few ulps of the largest coordinate, so
 * that the test keeps its meaning for models far from the origin. Plain C,
 * header only: the distances run in the samplers' inner loops. */
#ifndef COONS_GEOM_H
#define COONS_GEOM_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>

/* The relative tolerance of "the same": 1e-9 of a model's (or mesh's) size. */
#define COONS__REL_TOL 1e-9

/* Small double[3] maths. */
static inline void v3_set(double o[3], double x, double y, double z) { o[0] = x; o[1] = y; o[2] = z; }
static inline void v3_copy(double o[3], const double a[3]) { o[0] = a[0]; o[1] = a[1]; o[2] = a[2]; }
static inline void v3_zero(double o[3]) { o[0] = o[1] = o[2] = 0.0; }
static inline void v3_add(double o[3], const double a[3], const double b[3]) { o[0] = a[0] + b[0]; o[1] = a[1] + b[1]; o[2] = a[2] + b[2]; }
static inline void v3_sub(double o[3], const double a[3], const double b[3]) { o[0] = a[0] - b[0]; o[1] = a[1] - b[1]; o[2] = a[2] - b[2]; }
static inline void v3_scale(double o[3], const double a[3], double s) { o[0] = a[0] * s; o[1] = a[1] * s; o[2] = a[2] * s; }
/* o += s * a */
static inline void v3_axpy(double o[3], double s, const double a[3]) { o[0] += s * a[0]; o[1] += s * a[1]; o[2] += s * a[2]; }
static inline double v3_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void v3_cross(double o[3], const double a[3], const double b[3])
{
    double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2], z = a[0] * b[1] - a[1] * b[0];
    o[0] = x; o[1] = y; o[2] = z;
}
static inline double v3_norm(const double a[3]) { return sqrt(v3_dot(a, a)); }
static inline double v3_dist(const double a[3], const double b[3])
{
    double d[3];
    v3_sub(d, a, b);
    return v3_norm(d);
}
static inline void v3_lerp(double o[3], const double a[3], const double b[3], double t)
{
    o[0] = a[0] + t * (b[0] - a[0]); o[1] = a[1] + t * (b[1] - a[1]); o[2] = a[2] + t * (b[2] - a[2]);
}
static inline int v3_finite(const double a[3]) { return isfinite(a[0]) && isfinite(a[1]) && isfinite(a[2]); }

/* Bounding boxes: lo = +inf, hi = -inf, then extend. */
static inline void bbox_empty(double lo[3], double hi[3])
{
    lo[0] = lo[1] = lo[2] = INFINITY;
    hi[0] = hi[1] = hi[2] = -INFINITY;
}
static inline void bbox_add(double lo[3], double hi[3], const double p[3])
{
    for (int i = 0; i < 3; i++) {
        if (p[i] < lo[i]) lo[i] = p[i];
        if (p[i] > hi[i]) hi[i] = p[i];
    }
}
/* The box's diagonal, without overflow or underflow of the squares: a box
 * of size 1e200 or 1e-300 has a finite, non-zero diagonal. */
static inline double bbox_diag(const double lo[3], const double hi[3])
{
    if (!(lo[0] <= hi[0])) return 0.0;
    double m = 0, q = 0;
    for (int i = 0; i < 3; i++) m = fmax(m, hi[i] - lo[i]);
    if (!(m > 0) || !isfinite(m)) return m > 0 ? m : 0.0;
    for (int i = 0; i < 3; i++) q += ((hi[i] - lo[i]) / m) * ((hi[i] - lo[i]) / m);
    return m * sqrt(q);
}

/* NaN maps to 0: a parameter must never reach an integer conversion as NaN. */
static inline double clamp01(double x) { return x > 0.0 ? (x < 1.0 ? x : 1.0) : 0.0; }

/* The tolerance within which two points of the box [lo, hi] are the same
 * point: COONS__REL_TOL of its diagonal plus 64 ulps of its largest
 * coordinate. */
static inline double coons__same_place_tol(const double lo[3], const double hi[3])
{
    double maxabs = 0;
    for (int d = 0; d < 3; d++) maxabs = fmax(maxabs, fmax(fabs(lo[d]), fabs(hi[d])));
    return COONS__REL_TOL * bbox_diag(lo, hi) + 64 * DBL_EPSILON * maxabs;
}

/* |o - t dir|^2: the squared distance of a point, o from a base point, to
 * the point at t along dir. */
static inline double coons__off_dist2(const double o[3], double t, const double dir[3])
{
    double q[3];
    v3_copy(q, o);
    v3_axpy(q, -t, dir);
    return v3_dot(q, q);
}

/* Squared distance from p to the segment ab (a point when a = b). */
static inline double coons__seg_dist2(const double p[3], const double a[3], const double b[3])
{
    double ab[3], ap[3];
    v3_sub(ab, b, a);
    v3_sub(ap, p, a);
    double l2 = v3_dot(ab, ab), t = l2 > 0 ? v3_dot(ap, ab) / l2 : 0;
    return coons__off_dist2(ap, clamp01(t), ab);
}

/* Squared distance from p to the triangle abc (closest point by Voronoi
 * regions: C. Ericson, "Real-Time Collision Detection", section 5.1.5);
 * also right for degenerate triangles, whose regions reduce to sides and
 * corners. */
static inline double coons__tri_dist2(const double p[3], const double a[3], const double b[3],
                                      const double c[3])
{
    double ab[3], ac[3], ap[3], q[3];
    v3_sub(ab, b, a);
    v3_sub(ac, c, a);
    v3_sub(ap, p, a);
    double d1 = v3_dot(ab, ap), d2 = v3_dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return v3_dot(ap, ap);
    double bp[3];
    v3_sub(bp, p, b);
    double d3 = v3_dot(ab, bp), d4 = v3_dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return v3_dot(bp, bp);
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return coons__off_dist2(ap, d1 / (d1 - d3), ab);
    double cp[3];
    v3_sub(cp, p, c);
    double d5 = v3_dot(ab, cp), d6 = v3_dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return v3_dot(cp, cp);
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return coons__off_dist2(ap, d2 / (d2 - d6), ac);
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        double bc[3];
        v3_sub(bc, c, b);
        return coons__off_dist2(bp, w, bc);
    }
    double den = va + vb + vc;
    if (!(den > 0)) /* degenerate (collinear): the nearest side */
        return fmin(coons__seg_dist2(p, a, b),
                    fmin(coons__seg_dist2(p, b, c), coons__seg_dist2(p, c, a)));
    double v = vb / den, w = vc / den;
    v3_copy(q, ap);
    v3_axpy(q, -v, ab);
    v3_axpy(q, -w, ac);
    return v3_dot(q, q);
}

/* Six times the signed volume enclosed by the triangles tri[0..nt-1]
 * (corner indices into xyz, three doubles a vertex), the divergence
 * theorem over tetrahedra from the first vertex (a closed, outward mesh
 * gives its volume times 6; from a vertex of the mesh rather than the
 * origin, the sum keeps its precision for meshes far from the origin). */
static inline double coons__signed_volume6(const double *xyz, const uint32_t *tri, size_t nt)
{
    if (!nt) return 0.0;
    const double *o = xyz;
    double v = 0.0;
    for (size_t t = 0; t < nt; t++) {
        double a[3], b[3], c[3], bc[3];
        v3_sub(a, xyz + 3 * (size_t)tri[3 * t], o);
        v3_sub(b, xyz + 3 * (size_t)tri[3 * t + 1], o);
        v3_sub(c, xyz + 3 * (size_t)tri[3 * t + 2], o);
        v3_cross(bc, b, c);
        v += v3_dot(a, bc);
    }
    return v;
}

#endif
