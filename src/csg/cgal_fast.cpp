// SPDX-License-Identifier: GPL-3.0-or-later
//
// The fast path of the CGAL layer (see cgal_solid.cpp's file comment),
// compiled WITHOUT CGAL's assertions: chained unions of bodies that do not
// cross themselves on the inexact-constructions kernel (corefinement of the
// triangles near the other shell only, patches classified here; the whole
// shells by CGAL's Boolean when that fails its checks), the exact
// self-intersection test (input checks and the final check of every result;
// its candidate pairs from the box grids of box_grid.cpp), and the
// triangle-level test of which parts meet. What needs no CGAL lives in its
// own files: welding (weld.cpp, slivers.cpp), canonical order
// (canonical_order.cpp), input identity (input_identity.cpp), the grids
// (box_grid.cpp, proj_grid.cpp).
// Every result made here is checked exactly before it is used (the final
// check), so CGAL's assertions, which cost about 40% of the corefinement
// chain, buy nothing; they stay on in cgal_solid.cpp, where they turn CGAL
// 5.5's crashes on some coplanar inputs of autorefinement into exceptions.
// No CGAL type crosses into cgal_solid.cpp (cgal_common.hpp).
#ifndef NDEBUG
#define NDEBUG
#endif
#define CGAL_NDEBUG
// CGAL's warnings would print to stderr; the library never prints.
#define CGAL_NO_WARNINGS
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <new>
#include <unordered_map>

#include "box_grid.hpp"
#include "cgal_common.hpp"
#include "proj_grid.hpp"
extern "C" {
#include "coons_test_hooks.h"
#include "union_find.h"
}

namespace PMP = CGAL::Polygon_mesh_processing;

namespace coons_csg {

typedef CGAL::Exact_predicates_inexact_constructions_kernel IK;
typedef CGAL::Surface_mesh<IK::Point_3> IMesh;

namespace {

// Is e (in the plane of v, c, d) in the closed angle c-v-d, off v?
bool in_wedge(const IK::Point_3 &v, const IK::Point_3 &c, const IK::Point_3 &d,
              const IK::Point_3 &e)
{
    CGAL::Orientation o1 = CGAL::coplanar_orientation(v, c, d, e);
    CGAL::Orientation o2 = CGAL::coplanar_orientation(v, d, c, e);
    if (o1 == CGAL::NEGATIVE || o2 == CGAL::NEGATIVE) return false;
    if (o1 == CGAL::COLLINEAR) return (e - v) * (c - v) > 0;
    if (o2 == CGAL::COLLINEAR) return (e - v) * (d - v) > 0;
    return true;
}

// p without its coordinate c (exact).
inline IK::Point_2 drop(const IK::Point_3 &p, int c)
{
    return c == 0 ? IK::Point_2(p.y(), p.z()) : c == 1 ? IK::Point_2(p.z(), p.x()) : IK::Point_2(p.x(), p.y());
}

// The axis along which the normal of abc is largest (rounded: any axis
// would be right, this one makes the projection least degenerate).
inline int main_axis(const IK::Point_3 &a, const IK::Point_3 &b, const IK::Point_3 &c)
{
    double u[3] = {b.x() - a.x(), b.y() - a.y(), b.z() - a.z()};
    double v[3] = {c.x() - a.x(), c.y() - a.y(), c.z() - a.z()};
    double n[3] = {std::fabs(u[1] * v[2] - u[2] * v[1]), std::fabs(u[2] * v[0] - u[0] * v[2]),
                   std::fabs(u[0] * v[1] - u[1] * v[0])};
    return n[0] >= n[1] && n[0] >= n[2] ? 0 : n[1] >= n[2] ? 1 : 2;
}

// Exact sufficient tests in one axis projection (the points' coordinates
// dropped one at a time, so the 2-D predicates are exact): when the
// projections meet only where the shared indices allow, so do the
// triangles, since a triangle whose projection has area maps one to one
// onto it. These settle, with filtered 2-D orientations, the nearly
// coplanar pairs (neighbours on a flat or nearly flat stretch, facing walls
// of a thin part) whose 3-D orientations are nearly zero and would be
// evaluated exactly.
//  - no shared vertex: a side of one has the other strictly beyond it;
//  - a shared edge pq: the other vertices strictly on either side of pq;
//  - a shared vertex v: a side through v of one has the other's two other
//    vertices strictly beyond it (two angles at v meet only at v).
bool apart_in_projection(const IK::Point_3 *a, int shared, const int *si, const int *ti)
{
    int c = main_axis(a[0], a[1], a[2]);
    IK::Point_2 q[6];
    for (int i = 0; i < 6; i++) q[i] = drop(a[i], c);
    auto beyond = [&](int p0, int p1, int inside, int x, int y, int z) {
        CGAL::Orientation o = CGAL::orientation(q[p0], q[p1], q[inside]);
        if (o == CGAL::COLLINEAR) return false;
        CGAL::Orientation w = -o;
        return CGAL::orientation(q[p0], q[p1], q[x]) == w && CGAL::orientation(q[p0], q[p1], q[y]) == w &&
               (z < 0 || CGAL::orientation(q[p0], q[p1], q[z]) == w);
    };
    if (shared == 0) {
        for (int k = 0; k < 3; k++)
            if (beyond(k, (k + 1) % 3, (k + 2) % 3, 3, 4, 5) ||
                beyond(3 + k, 3 + (k + 1) % 3, 3 + (k + 2) % 3, 0, 1, 2))
                return true;
        return false;
    }
    if (shared == 2) {
        int p0 = si[0], p1 = si[1], x = 3 - si[0] - si[1], y = 3 + 3 - ti[0] - ti[1];
        CGAL::Orientation ox = CGAL::orientation(q[p0], q[p1], q[x]);
        CGAL::Orientation oy = CGAL::orientation(q[p0], q[p1], q[y]);
        return ox != CGAL::COLLINEAR && oy != CGAL::COLLINEAR && ox != oy;
    }
    // one shared vertex: s's is si[0], t's is ti[0]; q[3 + ti[0]] == q[si[0]]
    int v = si[0], s1 = (v + 1) % 3, s2 = (v + 2) % 3;
    int t1 = 3 + (ti[0] + 1) % 3, t2 = 3 + (ti[0] + 2) % 3;
    if (beyond(v, s1, s2, t1, t2, -1) || beyond(v, s2, s1, t1, t2, -1) ||
        beyond(v, t1, t2, s1, s2, -1) || beyond(v, t2, t1, s1, s2, -1))
        return true;
    // Both projections with area (each an angle at v of less than 180
    // degrees): they overlap exactly when a side of one enters the other's
    // angle, so when none does they meet only at v. This settles the pairs
    // of a flat fan whose sides through v lie on one line (two right angles
    // facing each other across v, as on a grid's squares), which the tests
    // above cannot (the others' vertices on the lines, not beyond them).
    if (CGAL::orientation(q[v], q[s1], q[s2]) == CGAL::COLLINEAR ||
        CGAL::orientation(q[v], q[t1], q[t2]) == CGAL::COLLINEAR)
        return false;
    // e (off v or on it) in the closed angle c-v-d (in_wedge in the plane)
    auto wedge = [&](int c, int d, int e) {
        CGAL::Orientation oc = CGAL::orientation(q[v], q[c], q[e]);
        CGAL::Orientation od = CGAL::orientation(q[v], q[d], q[e]);
        CGAL::Orientation dc = CGAL::orientation(q[v], q[c], q[d]); // d's side of vc, not collinear
        if (oc != CGAL::COLLINEAR && oc != dc) return false;        // beyond vc
        if (od != CGAL::COLLINEAR && od != -dc) return false;       // beyond vd
        int on = oc == CGAL::COLLINEAR ? c : od == CGAL::COLLINEAR ? d : -1;
        if (on < 0) return true;
        // e on the line through v and `on`: in the angle when on its ray
        // from v (exact signs of the differences; e == v: not off v)
        for (int k = 0; k < 2; k++) {
            double de = q[e][k] - q[v][k], dn = q[on][k] - q[v][k];
            if (de != 0 && dn != 0) return (de > 0) == (dn > 0);
        }
        return false;
    };
    return !(wedge(t1, t2, s1) || wedge(t1, t2, s2) || wedge(s1, s2, t1) || wedge(s1, s2, t2));
}

// Triangles s and t share one vertex v (s[si[0]] == t[ti[0]]). Along some
// axis, one triangle's other vertices strictly below v and the other's not
// below it: they meet only at v (exact comparisons; this settles about half
// the pairs of a flat fan, whose orientation tests are exact zeros and cost
// an exact evaluation each).
inline bool apart_along_axis(const std::vector<IK::Point_3> &P, const uint32_t *s, const uint32_t *t,
                             const int *si, const int *ti)
{
    const IK::Point_3 &v = P[s[si[0]]];
    const IK::Point_3 &s1 = P[s[(si[0] + 1) % 3]], &s2 = P[s[(si[0] + 2) % 3]];
    const IK::Point_3 &t1 = P[t[(ti[0] + 1) % 3]], &t2 = P[t[(ti[0] + 2) % 3]];
    for (int c = 0; c < 3; c++) {
        double vc = v[c];
        if (s1[c] < vc && s2[c] < vc && t1[c] >= vc && t2[c] >= vc) return true;
        if (t1[c] < vc && t2[c] < vc && s1[c] >= vc && s2[c] >= vc) return true;
        if (s1[c] > vc && s2[c] > vc && t1[c] <= vc && t2[c] <= vc) return true;
        if (t1[c] > vc && t2[c] > vc && s1[c] <= vc && s2[c] <= vc) return true;
    }
    return false;
}

// Two triangles of a soup given by vertex indices intersect other than in
// what their shared indices allow (a shared edge, a shared vertex)?
bool pair_intersects(const std::vector<IK::Point_3> &P, const uint32_t *s, const uint32_t *t,
                     bool project = true)
{
    int shared = 0, si[3] = {-1, -1, -1}, ti[3] = {-1, -1, -1};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (s[i] == t[j]) {
                si[shared] = i;
                ti[shared] = j;
                shared++;
            }
    const IK::Point_3 &a = P[s[0]], &b = P[s[1]], &c = P[s[2]];
    const IK::Point_3 &d = P[t[0]], &e = P[t[1]], &f = P[t[2]];
    if (shared >= 3) return true;
    if (project) {
        // the comparisons first: they cost less than the projection
        if (shared == 1 && apart_along_axis(P, s, t, si, ti)) return false;
        const IK::Point_3 six[6] = {a, b, c, d, e, f};
        if (apart_in_projection(six, shared, si, ti)) return false;
    }
    if (shared == 0) return CGAL::do_intersect(IK::Triangle_3(a, b, c), IK::Triangle_3(d, e, f));
    if (shared == 2) {
        int so = 3 - si[0] - si[1], to = 3 - ti[0] - ti[1];
        const IK::Point_3 &p = P[s[si[0]]], &q = P[s[si[1]]], &x = P[s[so]], &y = P[t[to]];
        if (CGAL::orientation(p, q, x, y) != CGAL::COPLANAR) return false;
        return CGAL::coplanar_orientation(p, q, x, y) == CGAL::POSITIVE;
    }
    const IK::Point_3 &v = P[s[si[0]]];
    const IK::Point_3 &s1 = P[s[(si[0] + 1) % 3]], &s2 = P[s[(si[0] + 2) % 3]];
    const IK::Point_3 &t1 = P[t[(ti[0] + 1) % 3]], &t2 = P[t[(ti[0] + 2) % 3]];
    if (!project && apart_along_axis(P, s, t, si, ti)) return false;
    // One triangle strictly on one side of the other's plane (but for v):
    // they meet only at v. This settles almost every pair of a fan.
    CGAL::Orientation a1 = CGAL::orientation(v, s1, s2, t1), a2 = CGAL::orientation(v, s1, s2, t2);
    if (a1 == a2 && a1 != CGAL::COPLANAR) return false;
    CGAL::Orientation b1 = CGAL::orientation(v, t1, t2, s1), b2 = CGAL::orientation(v, t1, t2, s2);
    if (b1 == b2 && b1 != CGAL::COPLANAR) return false;
    if (a1 == CGAL::COPLANAR && a2 == CGAL::COPLANAR) {
        // Coplanar, sharing v: each lies in its angle at v (< 180 degrees),
        // so they overlap exactly when a side of one enters the other's angle.
        return in_wedge(v, t1, t2, s1) || in_wedge(v, t1, t2, s2) || in_wedge(v, s1, s2, t1) ||
               in_wedge(v, s1, s2, t2);
    }
    IK::Triangle_3 S(v, s1, s2), T(v, t1, t2);
    if (CGAL::do_intersect(IK::Segment_3(s1, s2), T)) return true;
    if (CGAL::do_intersect(IK::Segment_3(t1, t2), S)) return true;
    for (const IK::Point_3 *e2 : {&s1, &s2})
        if (CGAL::orientation(v, t1, t2, *e2) == CGAL::COPLANAR && in_wedge(v, t1, t2, *e2))
            return true;
    for (const IK::Point_3 *e2 : {&t1, &t2})
        if (CGAL::orientation(v, s1, s2, *e2) == CGAL::COPLANAR && in_wedge(v, s1, s2, *e2))
            return true;
    return false;
}

} // namespace

// Exact collinearity of three points (for fix_slivers, slivers.cpp).
bool exact_collinear(const double *p, const double *q, const double *r)
{
    return CGAL::collinear(IK::Point_3(p[0], p[1], p[2]), IK::Point_3(q[0], q[1], q[2]),
                           IK::Point_3(r[0], r[1], r[2]));
}

namespace {

typedef CGAL::Box_intersection_d::Box_with_info_d<double, 3, size_t> Box;

// Drops the boxes of `boxes` that meet no box of `marks`, by a 64^3
// bitmap of the cells the marks touch over their common box (two boxes
// that meet share a point, hence the cell holding it): a box kept may still
// meet none, one dropped meets none.
void keep_touching(const std::vector<Box> &marks, std::vector<Box> &boxes)
{
    enum { G = 64 };
    double lo[3], hi[3];
    for (int c = 0; c < 3; c++) lo[c] = HUGE_VAL, hi[c] = -HUGE_VAL;
    for (const Box &b : marks)
        for (int c = 0; c < 3; c++) {
            lo[c] = std::min(lo[c], b.min_coord(c));
            hi[c] = std::max(hi[c], b.max_coord(c));
        }
    double w[3];
    for (int c = 0; c < 3; c++) w[c] = hi[c] > lo[c] ? (hi[c] - lo[c]) / G : 1.0;
    auto cell = [&](double x, int c) {
        double q = std::floor((x - lo[c]) / w[c]);
        return q < 0 ? 0 : q > G - 1 ? G - 1 : (int)q;
    };
    std::vector<char> hot(G * G * G, 0);
    auto cover = [&](const Box &b, bool mark) {
        int a[3], z[3];
        for (int c = 0; c < 3; c++) {
            if (b.max_coord(c) < lo[c] || b.min_coord(c) > hi[c]) return false;
            a[c] = cell(b.min_coord(c), c);
            z[c] = cell(b.max_coord(c), c);
        }
        for (int i = a[0]; i <= z[0]; i++)
            for (int j = a[1]; j <= z[1]; j++)
                for (int k = a[2]; k <= z[2]; k++) {
                    char &h = hot[((size_t)i * G + (size_t)j) * G + (size_t)k];
                    if (mark) h = 1;
                    else if (h) return true;
                }
        return false;
    };
    for (const Box &b : marks) cover(b, true);
    std::vector<Box> near;
    for (const Box &b : boxes)
        if (cover(b, false)) near.push_back(b);
    boxes.swap(near);
}

// Pairs among `fresh` and between `fresh` and `old` boxes that intersect,
// counted only when the low x end of their common box lies in [x0, x1).
size_t count_in_slab(const std::vector<IK::Point_3> &P, const uint32_t *tri,
                     std::vector<Box> &fresh, std::vector<Box> &old, double x0, double x1)
{
    size_t count = 0;
    auto test = [&](const Box &x, const Box &y) {
        double m = std::max(x.min_coord(0), y.min_coord(0));
        if (m < x0 || m >= x1) return;
        if (pair_intersects(P, tri + 3 * x.info(), tri + 3 * y.info(), false)) count++;
    };
    CGAL::box_self_intersection_d<CGAL::Sequential_tag>(fresh.begin(), fresh.end(), test);
    if (!old.empty() && !fresh.empty())
        CGAL::box_intersection_d<CGAL::Sequential_tag>(fresh.begin(), fresh.end(), old.begin(),
                                                       old.end(), test);
    return count;
}

// The reference for the tests (coons__csg_count_pairs): the candidate
// pairs by CGAL's box_intersection_d, by slabs along x, and the 3-D tests
// alone (no projection), as the check was before the grids.
size_t count_boxes_cgal(const std::vector<IK::Point_3> &P, const uint32_t *tri,
                        std::vector<Box> &fresh, std::vector<Box> &kept, unsigned threads)
{
    // Slabs along x with about as many box starts each; a pair is counted
    // in the slab that holds the low x end of the pair's common box.
    size_t total = fresh.size() + kept.size();
    unsigned ns = threads > 1 && total > 4096 ? threads : 1;
    std::vector<double> cut{-HUGE_VAL};
    if (ns > 1) {
        std::vector<double> lows;
        lows.reserve(total);
        for (const Box &b : fresh) lows.push_back(b.min_coord(0));
        for (const Box &b : kept) lows.push_back(b.min_coord(0));
        std::sort(lows.begin(), lows.end());
        for (unsigned k = 1; k < ns; k++) {
            double c = lows[total * k / ns];
            if (c > cut.back()) cut.push_back(c);
        }
    }
    cut.push_back(HUGE_VAL);
    size_t nslab = cut.size() - 1;
    if (nslab == 1) return count_in_slab(P, tri, fresh, kept, -HUGE_VAL, HUGE_VAL);
    std::vector<size_t> counts(nslab, 0);
    parallel_for(threads, nslab, [&](size_t j) {
        std::vector<Box> f, o;
        for (const Box &b : fresh)
            if (b.min_coord(0) < cut[j + 1] && b.max_coord(0) >= cut[j]) f.push_back(b);
        for (const Box &b : kept)
            if (b.min_coord(0) < cut[j + 1] && b.max_coord(0) >= cut[j]) o.push_back(b);
        counts[j] = count_in_slab(P, tri, f, o, cut[j], cut[j + 1]);
    });
    size_t count = 0;
    for (size_t c : counts) count += c;
    return count;
}

} // namespace

size_t count_self_intersections(const double *xyz, size_t nv, const uint32_t *tri, size_t nt,
                                size_t *degenerate, unsigned threads, const InputTriangles *old,
                                bool reference)
{
    // The points, then the boxes by chunks of triangles on the threads (each
    // chunk's boxes in triangle order, the chunks concatenated in order: the
    // same boxes in the same order for every thread count).
    const size_t chunk = 65536;
    const unsigned bt = nt > chunk ? threads : 1;
    std::vector<IK::Point_3> P(nv);
    parallel_for(nv > chunk ? threads : 1, (nv + chunk - 1) / chunk, [&](size_t k) {
        for (size_t i = k * chunk, i1 = std::min(nv, i + chunk); i < i1; i++)
            P[i] = IK::Point_3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    });
    size_t nchunk = (nt + chunk - 1) / chunk;
    std::vector<std::vector<Box>> cfresh(nchunk), ckept(nchunk);
    std::vector<size_t> cdeg(nchunk, 0);
    parallel_for(bt, nchunk, [&](size_t k) {
        std::vector<Box> &fr = cfresh[k], &kp = ckept[k];
        size_t t1 = std::min(nt, (k + 1) * chunk);
        fr.reserve(old ? 0 : t1 - k * chunk);
        for (size_t t = k * chunk; t < t1; t++) {
            const uint32_t *q = tri + 3 * t;
            bool is_old = old && old->count(tri_key(xyz + 3 * q[0], xyz + 3 * q[1], xyz + 3 * q[2]));
            if (q[0] == q[1] || q[1] == q[2] || q[0] == q[2]) continue;
            if (!is_old && CGAL::collinear(P[q[0]], P[q[1]], P[q[2]])) {
                // A zero-area triangle bounds nothing; it is counted, not tested.
                cdeg[k]++;
                continue;
            }
            CGAL::Bbox_3 bb = P[q[0]].bbox() + P[q[1]].bbox() + P[q[2]].bbox();
            (is_old ? kp : fr).emplace_back(bb, t);
        }
    });
    std::vector<Box> fresh, kept;
    {
        size_t nf = 0, nk = 0;
        for (size_t k = 0; k < nchunk; k++) nf += cfresh[k].size(), nk += ckept[k].size();
        fresh.reserve(nf);
        kept.reserve(nk);
        for (size_t k = 0; k < nchunk; k++) {
            fresh.insert(fresh.end(), cfresh[k].begin(), cfresh[k].end());
            kept.insert(kept.end(), ckept[k].begin(), ckept[k].end());
            if (degenerate) *degenerate += cdeg[k];
            std::vector<Box>().swap(cfresh[k]);
            std::vector<Box>().swap(ckept[k]);
        }
    }
    if (fresh.empty()) return 0;
    if (reference) return count_boxes_cgal(P, tri, fresh, kept, threads);
    if (!kept.empty()) {
        // Only kept boxes near a fresh one can take part.
        keep_touching(fresh, kept);
    }
    std::vector<GridBox> boxes(fresh.size() + kept.size());
    parallel_for(boxes.size() > chunk ? threads : 1, (boxes.size() + chunk - 1) / chunk, [&](size_t k) {
        for (size_t i = k * chunk, i1 = std::min(boxes.size(), i + chunk); i < i1; i++) {
            bool k_ = i >= fresh.size();
            const Box &b = k_ ? kept[i - fresh.size()] : fresh[i];
            boxes[i] = {{b.min_coord(0), b.min_coord(1), b.min_coord(2)},
                        {b.max_coord(0), b.max_coord(1), b.max_coord(2)},
                        (uint32_t)b.info(),
                        k_};
        }
    });
    struct Ctx {
        const std::vector<IK::Point_3> &P;
        const uint32_t *tri;
    } ctx{P, tri};
    PairTest test = [](const void *c, uint32_t s, uint32_t t) {
        const Ctx &x = *static_cast<const Ctx *>(c);
        return pair_intersects(x.P, x.tri + 3 * (size_t)s, x.tri + 3 * (size_t)t);
    };
    BoxGrid grid(boxes, test, &ctx, fresh.size() + kept.size() > 4096 ? threads : 1);
    if (!grid.ok()) return count_boxes_cgal(P, tri, fresh, kept, threads);
    size_t nt_ = grid.tasks();
    std::vector<size_t> counts(nt_, 0);
    parallel_for(fresh.size() + kept.size() > 4096 ? threads : 1, nt_,
                 [&](size_t k) { counts[k] = grid.run(k); });
    size_t count = 0;
    for (size_t c : counts) count += c;
    return count;
}

// The winding number of the closed part p around point q, from the solid
// angles of its triangles (van Oosterom and Strackee); q is off every box
// of p's triangles, so it is not near p's surface. NaN when the sum is not
// near an integer.
static double winding_number(const double *xyz, const uint32_t *tri, const Part &p,
                             const double *q)
{
    double sum = 0;
    for (size_t t = p.tri_first; t < p.tri_first + p.tri_count; t++) {
        double a[3], b[3], c[3];
        for (int d = 0; d < 3; d++) {
            a[d] = xyz[3 * tri[3 * t] + d] - q[d];
            b[d] = xyz[3 * tri[3 * t + 1] + d] - q[d];
            c[d] = xyz[3 * tri[3 * t + 2] + d] - q[d];
        }
        double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        double lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        double lc = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                     a[2] * (b[0] * c[1] - b[1] * c[0]);
        double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        double bc = b[0] * c[0] + b[1] * c[1] + b[2] * c[2];
        double ca = c[0] * a[0] + c[1] * a[1] + c[2] * a[2];
        sum += 2 * std::atan2(det, la * lb * lc + ab * lc + bc * la + ca * lb);
    }
    double w = sum / (4 * CGAL_PI);
    return std::fabs(w - std::nearbyint(w)) < 0.25 ? std::nearbyint(w) : NAN;
}

bool parts_interact(const double *xyz, const uint32_t *tri, const Part &a, const Part &b)
{
    for (int c = 0; c < 3; c++)
        if (a.hi[c] < b.lo[c] || b.hi[c] < a.lo[c]) return false;
    // The triangles of each inside the other's box.
    std::vector<Box> ba, bb;
    auto collect = [&](const Part &p, const Part &other, std::vector<Box> &out) {
        CGAL::Bbox_3 ob(other.lo[0], other.lo[1], other.lo[2], other.hi[0], other.hi[1], other.hi[2]);
        for (size_t t = p.tri_first; t < p.tri_first + p.tri_count; t++) {
            CGAL::Bbox_3 x;
            for (int k = 0; k < 3; k++) {
                const double *v = xyz + 3 * tri[3 * t + k];
                x += CGAL::Bbox_3(v[0], v[1], v[2], v[0], v[1], v[2]);
            }
            if (CGAL::do_overlap(x, ob)) out.emplace_back(x, t);
        }
    };
    collect(a, b, ba);
    collect(b, a, bb);
    if (!ba.empty() && !bb.empty()) {
        struct Met {};
        try {
            CGAL::box_intersection_d<CGAL::Sequential_tag>(
                ba.begin(), ba.end(), bb.begin(), bb.end(), [](const Box &, const Box &) { throw Met(); });
        } catch (const Met &) {
            return true;
        }
    }
    // Apart: unless one lies inside the other.
    if (a.vert_count && b.vert_count) {
        double wa = winding_number(xyz, tri, a, xyz + 3 * b.vert_first);
        double wb = winding_number(xyz, tri, b, xyz + 3 * a.vert_first);
        if (!(wa == 0) || !(wb == 0)) return true;
    }
    return false;
}

namespace {

// ---- Corefinement of the near triangles only (the near chain) ----
//
// Two closed shells a and b are united without handing their whole
// surfaces to CGAL: only the triangles whose boxes meet a box of the other
// shell (and the triangles around their vertices) are corefined, as two
// open meshes (PMP::corefine needs no closed input); the others cannot meet
// the other shell, so no edge between a near and a far triangle is split.
// The refined shells are cut into patches along the intersection edges;
// each patch is classified once: from a far triangle (off the other shell,
// since its box meets none of the other's) by the parity of an axis ray
// with exact predicates, or, for a patch of near triangles, first by
// whether it lies on a coplanar triangle of the other (a shared flat
// face). The union keeps the patches of each outside the other, and of
// coplanar patches facing the same way one copy. The result is accepted
// only when it is a closed, oriented 2-manifold whose volume lies between
// the larger input's and their sum; the caller checks it exactly as any
// fast union.

inline CGAL::Bbox_3 tri_bbox(const Soup &s, size_t t)
{
    CGAL::Bbox_3 x;
    for (int k = 0; k < 3; k++) {
        const double *v = &s.xyz[3 * s.tri[3 * t + k]];
        x += CGAL::Bbox_3(v[0], v[1], v[2], v[0], v[1], v[2]);
    }
    return x;
}

inline IK::Point_3 point(const Soup &s, uint32_t v)
{
    return IK::Point_3(s.xyz[3 * v], s.xyz[3 * v + 1], s.xyz[3 * v + 2]);
}

// Marks (1) the triangles of a and of b whose closed boxes meet a box of
// the other's, then the triangles around their vertices.
void mark_near(const Soup &a, const Soup &b, std::vector<char> &na, std::vector<char> &nb)
{
    size_t ta = a.tri.size() / 3, tb = b.tri.size() / 3;
    na.assign(ta, 0);
    nb.assign(tb, 0);
    // Each shell's boxes within the other's box.
    std::vector<CGAL::Bbox_3> xa(ta), xb(tb);
    CGAL::Bbox_3 A, B;
    for (size_t t = 0; t < ta; t++) A += xa[t] = tri_bbox(a, t);
    for (size_t t = 0; t < tb; t++) B += xb[t] = tri_bbox(b, t);
    std::vector<Box> ba, bb;
    for (size_t t = 0; t < ta; t++)
        if (CGAL::do_overlap(xa[t], B)) ba.emplace_back(xa[t], t);
    for (size_t t = 0; t < tb; t++)
        if (CGAL::do_overlap(xb[t], A)) bb.emplace_back(xb[t], t);
    if (ba.empty() || bb.empty()) return;
    // Most boxes lie far from the other shell's: bitmaps drop them first.
    keep_touching(bb, ba);
    keep_touching(ba, bb);
    if (ba.empty() || bb.empty()) return;
    CGAL::box_intersection_d<CGAL::Sequential_tag>(ba.begin(), ba.end(), bb.begin(), bb.end(),
                                                   [&](const Box &x, const Box &y) {
                                                       na[x.info()] = 1;
                                                       nb[y.info()] = 1;
                                                   });
    auto widen = [](const Soup &s, std::vector<char> &near) {
        std::vector<char> vm(s.xyz.size() / 3, 0);
        size_t nt = s.tri.size() / 3;
        for (size_t t = 0; t < nt; t++)
            if (near[t])
                for (int k = 0; k < 3; k++) vm[s.tri[3 * t + k]] = 1;
        for (size_t t = 0; t < nt; t++)
            if (vm[s.tri[3 * t]] || vm[s.tri[3 * t + 1]] || vm[s.tri[3 * t + 2]]) near[t] = 1;
    };
    widen(a, na);
    widen(b, nb);
}

typedef IMesh::Property_map<IMesh::Vertex_index, uint32_t> VertexIds;
typedef IMesh::Property_map<IMesh::Edge_index, bool> EdgeFlags;

// The near triangles of s as an open mesh; each vertex keeps its index in s.
bool near_mesh(const Soup &s, const std::vector<char> &near, IMesh &m, VertexIds &gid)
{
    gid = m.add_property_map<IMesh::Vertex_index, uint32_t>("v:gid", UINT32_MAX).first;
    std::vector<IMesh::Vertex_index> local(s.xyz.size() / 3, IMesh::null_vertex());
    for (size_t t = 0; t < near.size(); t++) {
        if (!near[t]) continue;
        IMesh::Vertex_index v[3];
        for (int k = 0; k < 3; k++) {
            uint32_t g = s.tri[3 * t + k];
            if (local[g] == IMesh::null_vertex()) {
                local[g] = m.add_vertex(point(s, g));
                gid[local[g]] = g;
            }
            v[k] = local[g];
        }
        if (CGAL::collinear(m.point(v[0]), m.point(v[1]), m.point(v[2])) ||
            m.add_face(v[0], v[1], v[2]) == IMesh::null_face())
            return false;
    }
    return true;
}

// A shell after corefinement: s's far triangles and m's (refined) ones,
// the new vertices appended to s's; `cut` the intersection edges.
struct Refined {
    Soup s;
    std::vector<char> near; // per triangle: from the corefined part
    std::unordered_set<uint64_t> cut;
};

void refined(const Soup &s, const std::vector<char> &near, const IMesh &m, VertexIds gid,
             EdgeFlags ecm, Refined &r)
{
    r.s.xyz = s.xyz;
    for (auto v : m.vertices())
        if (gid[v] == UINT32_MAX) {
            gid[v] = (uint32_t)(r.s.xyz.size() / 3);
            const IK::Point_3 &p = m.point(v);
            r.s.xyz.insert(r.s.xyz.end(), {p.x(), p.y(), p.z()});
        }
    size_t nt = near.size();
    r.s.tri.reserve(3 * (nt + m.num_faces()));
    for (size_t t = 0; t < nt; t++)
        if (!near[t]) r.s.tri.insert(r.s.tri.end(), &s.tri[3 * t], &s.tri[3 * t] + 3);
    r.near.assign(r.s.tri.size() / 3, 0);
    for (auto f : m.faces())
        for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) r.s.tri.push_back(gid[v]);
    r.near.resize(r.s.tri.size() / 3, 1);
    for (auto e : m.edges())
        if (ecm[e])
            r.cut.insert(edge_key(gid[m.source(m.halfedge(e))], gid[m.target(m.halfedge(e))]));
}

// The triangles around each vertex (compressed rows).
struct VertexFaces {
    std::vector<uint32_t> first, faces;
    explicit VertexFaces(const Soup &s) : first(s.xyz.size() / 3 + 1, 0), faces(s.tri.size())
    {
        for (uint32_t v : s.tri) first[v + 1]++;
        for (size_t v = 1; v < first.size(); v++) first[v] += first[v - 1];
        std::vector<uint32_t> at(first.begin(), first.end() - 1);
        for (size_t i = 0; i < s.tri.size(); i++) faces[at[s.tri[i]]++] = (uint32_t)(i / 3);
    }
};

// The triangle across edge (a, b) of triangle t: the only other one with
// the edge, which runs (b, a) there; UINT32_MAX when there is none, more
// than one, or one running (a, b) (not a closed oriented 2-manifold).
uint32_t across(const Soup &s, const VertexFaces &vf, uint32_t t, uint32_t a, uint32_t b)
{
    uint32_t found = UINT32_MAX;
    for (uint32_t i = vf.first[a]; i < vf.first[a + 1]; i++) {
        uint32_t u = vf.faces[i];
        if (u == t) continue;
        const uint32_t *q = &s.tri[3 * (size_t)u];
        for (int k = 0; k < 3; k++) {
            if (q[k] != a) continue;
            if (q[(k + 1) % 3] == b) return UINT32_MAX;
            if (q[(k + 2) % 3] == b) {
                if (found != UINT32_MAX) return UINT32_MAX;
                found = u;
            }
        }
    }
    return found;
}

// Patch of each triangle: triangles joined across edges not in r.cut.
// A far triangle misses the other shell, so no intersection edge ends at
// its vertices, and all triangles around such a vertex lie in one patch:
// far triangles are joined through their vertices (union-find over
// vertices, no adjacency needed); near triangles across their uncut edges
// (adjacency among the near ones), and to the vertices they share with far
// ones. False when the near triangles are not an oriented 2-manifold
// (r.s's far part comes unchanged from a checked closed shell).
bool make_patches(const Refined &r, std::vector<uint32_t> &patch, uint32_t &np)
{
    const Soup &s = r.s;
    size_t nt = s.tri.size() / 3, nv = s.xyz.size() / 3;
    Soup nearsoup; // the near triangles, with their indices in s
    std::vector<char> farv(nv, 0);
    for (size_t t = 0; t < nt; t++) {
        if (r.near[t]) {
            nearsoup.tri.insert(nearsoup.tri.end(), &s.tri[3 * t], &s.tri[3 * t] + 3);
        } else {
            for (int k = 0; k < 3; k++) farv[s.tri[3 * t + k]] = 1;
        }
    }
    nearsoup.xyz.resize(3 * nv); // only its size is used
    VertexFaces vf(nearsoup);
    size_t nn = nearsoup.tri.size() / 3;
    std::vector<uint32_t> up(nv + nn); // vertices, then near triangles
    for (size_t x = 0; x < up.size(); x++) up[x] = (uint32_t)x;
    auto join = [&](uint32_t x, uint32_t y) { coons__uf_union(up.data(), x, y); };
    for (size_t t = 0; t < nt; t++)
        if (!r.near[t]) {
            join(s.tri[3 * t], s.tri[3 * t + 1]);
            join(s.tri[3 * t], s.tri[3 * t + 2]);
        }
    for (size_t i = 0; i < nn; i++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = nearsoup.tri[3 * i + k], b = nearsoup.tri[3 * i + (k + 1) % 3];
            if (farv[a]) join((uint32_t)(nv + i), a);
            uint32_t u = across(nearsoup, vf, (uint32_t)i, a, b);
            if (u == UINT32_MAX) {
                // a border edge of the near part: its far neighbour's
                // vertices are far ones, joined above
                if (farv[a] && farv[b]) continue;
                return false;
            }
            if (!r.cut.count(edge_key(a, b))) join((uint32_t)(nv + i), (uint32_t)(nv + u));
        }
    patch.assign(nt, UINT32_MAX);
    std::vector<uint32_t> label(nv + nn, UINT32_MAX);
    np = 0;
    size_t ni = 0;
    for (size_t t = 0; t < nt; t++) {
        uint32_t root = coons__uf_find(up.data(), r.near[t] ? (uint32_t)(nv + ni++) : s.tri[3 * t]);
        if (label[root] == UINT32_MAX) label[root] = np++;
        patch[t] = label[root];
    }
    return true;
}

// Parity of the crossings of s by the ray from q along +axis d (exact
// predicates on the doubles): 1 inside, 0 outside, -1 when the ray is not
// generic (it meets an edge or a vertex of s, or q lies on s).
int ray_parity(const Soup &s, const ProjGrid *grid, const double *q, int d)
{
    const int d1 = (d + 1) % 3, d2 = (d + 2) % 3;
    const IK::Point_2 q2(q[d1], q[d2]);
    const IK::Point_3 Q(q[0], q[1], q[2]);
    int parity = 0;
    auto test = [&](uint32_t t) {
        const double *A = &s.xyz[3 * s.tri[3 * (size_t)t]], *B = &s.xyz[3 * s.tri[3 * (size_t)t + 1]],
                     *C = &s.xyz[3 * s.tri[3 * (size_t)t + 2]];
        if (A[d] < q[d] && B[d] < q[d] && C[d] < q[d]) return true;
        if ((A[d1] < q[d1] && B[d1] < q[d1] && C[d1] < q[d1]) ||
            (A[d1] > q[d1] && B[d1] > q[d1] && C[d1] > q[d1]) ||
            (A[d2] < q[d2] && B[d2] < q[d2] && C[d2] < q[d2]) ||
            (A[d2] > q[d2] && B[d2] > q[d2] && C[d2] > q[d2]))
            return true;
        const IK::Point_2 a(A[d1], A[d2]), b(B[d1], B[d2]), c(C[d1], C[d2]);
        CGAL::Orientation o1 = CGAL::orientation(a, b, q2), o2 = CGAL::orientation(b, c, q2),
                          o3 = CGAL::orientation(c, a, q2);
        bool pos = o1 == CGAL::POSITIVE || o2 == CGAL::POSITIVE || o3 == CGAL::POSITIVE;
        bool neg = o1 == CGAL::NEGATIVE || o2 == CGAL::NEGATIVE || o3 == CGAL::NEGATIVE;
        if (pos && neg) return true;
        if (o1 == CGAL::COLLINEAR || o2 == CGAL::COLLINEAR || o3 == CGAL::COLLINEAR) return false;
        // q strictly inside the projection, whose orientation o1 is the
        // sign of the normal's d component: the plane is met ahead exactly
        // when q lies on its negative side times that sign.
        CGAL::Orientation side = CGAL::orientation(IK::Point_3(A[0], A[1], A[2]),
                                                   IK::Point_3(B[0], B[1], B[2]),
                                                   IK::Point_3(C[0], C[1], C[2]), Q);
        if (side == CGAL::COPLANAR) return false;
        if (side != o1) parity ^= 1;
        return true;
    };
    bool generic = true;
    if (grid)
        generic = grid->each(q, test);
    else
        for (size_t t = 0; t < s.tri.size() / 3 && generic; t++) generic = test((uint32_t)t);
    return generic ? parity : -1;
}

// Does triangle f of s lie on a coplanar triangle of o (among `cand`)?
// 1: yes, facing the same way; 2: yes, facing the other way; 0: no; -1: f
// is too thin to tell (its rounded centroid is not strictly inside it).
template <class G> int coplanar_cover(const Soup &s, uint32_t f, const Soup &o, G near_grid)
{
    const uint32_t *v = &s.tri[3 * (size_t)f];
    IK::Point_3 a = point(s, v[0]), b = point(s, v[1]), c = point(s, v[2]);
    int d = main_axis(a, b, c);
    IK::Point_2 a2 = drop(a, d), b2 = drop(b, d), c2 = drop(c, d);
    double q[3];
    for (int k = 0; k < 3; k++) q[k] = (a[k] + b[k] + c[k]) / 3;
    IK::Point_2 q2 = drop(IK::Point_3(q[0], q[1], q[2]), d);
    CGAL::Orientation of = CGAL::orientation(a2, b2, c2);
    if (of == CGAL::COLLINEAR || CGAL::orientation(a2, b2, q2) != of ||
        CGAL::orientation(b2, c2, q2) != of || CGAL::orientation(c2, a2, q2) != of)
        return -1;
    CGAL::Bbox_3 fb = a.bbox() + b.bbox() + c.bbox();
    int cover = 0;
    near_grid(d).each(q, [&](uint32_t g) {
        if (!CGAL::do_overlap(fb, tri_bbox(o, g))) return true;
        const uint32_t *w = &o.tri[3 * (size_t)g];
        IK::Point_3 x = point(o, w[0]), y = point(o, w[1]), z = point(o, w[2]);
        if (CGAL::orientation(a, b, c, x) != CGAL::COPLANAR ||
            CGAL::orientation(a, b, c, y) != CGAL::COPLANAR ||
            CGAL::orientation(a, b, c, z) != CGAL::COPLANAR)
            return true;
        IK::Point_2 x2 = drop(x, d), y2 = drop(y, d), z2 = drop(z, d);
        CGAL::Orientation og = CGAL::orientation(x2, y2, z2);
        if (og == CGAL::COLLINEAR) return true;
        CGAL::Orientation o1 = CGAL::orientation(x2, y2, q2), o2 = CGAL::orientation(y2, z2, q2),
                          o3 = CGAL::orientation(z2, x2, q2);
        CGAL::Orientation out = og == CGAL::POSITIVE ? CGAL::NEGATIVE : CGAL::POSITIVE;
        if (o1 == out || o2 == out || o3 == out) return true;
        cover = og == of ? 1 : 2;
        return false;
    });
    return cover;
}

enum Verdict { V_UNKNOWN = -1, V_OUT = 0, V_IN = 1, V_SAME = 2, V_OPPOSITE = 3 };

// The verdict of each patch of r against the closed shell o.
bool classify(const Refined &r, const std::vector<uint32_t> &patch, uint32_t np,
              const Refined &o, std::vector<int> &verdict)
{
    enum { TRIES = 8 };
    std::vector<std::vector<uint32_t>> cand(np);
    size_t nt = patch.size();
    for (int pass = 0; pass < 2; pass++)
        for (size_t t = 0; t < nt; t++) {
            std::vector<uint32_t> &c = cand[patch[t]];
            if ((pass == 0) == !r.near[t] && c.size() < TRIES) c.push_back((uint32_t)t);
        }
    // Grids of o's triangles along each axis (for the rays) and of its
    // near ones (for the coplanar test), made when first needed.
    std::vector<uint32_t> all, onear;
    for (size_t g = 0; g < o.near.size(); g++)
        if (o.near[g]) onear.push_back((uint32_t)g);
    std::unique_ptr<ProjGrid> rays[3], flats[3];
    auto ray_grid = [&](int d) {
        if (all.empty())
            for (size_t g = 0; g < o.near.size(); g++) all.push_back((uint32_t)g);
        rays[d].reset(new ProjGrid(o.s, all, d));
    };
    auto flat = [&](int d) -> const ProjGrid & {
        if (!flats[d]) flats[d].reset(new ProjGrid(o.s, onear, d));
        return *flats[d];
    };
    size_t cast = 0;
    verdict.assign(np, V_UNKNOWN);
    for (uint32_t p = 0; p < np; p++) {
        for (uint32_t t : cand[p]) {
            if (r.near[t]) {
                int cov = coplanar_cover(r.s, t, o.s, flat);
                if (cov < 0) continue;
                if (cov > 0) {
                    verdict[p] = cov == 1 ? V_SAME : V_OPPOSITE;
                    break;
                }
            }
            const uint32_t *v = &r.s.tri[3 * (size_t)t];
            double q[3];
            for (int k = 0; k < 3; k++)
                q[k] = (r.s.xyz[3 * v[0] + k] + r.s.xyz[3 * v[1] + k] + r.s.xyz[3 * v[2] + k]) / 3;
            int in = -1;
            // The first rays scan all of o; a grid pays when there are many.
            for (int d = 0; d < 3 && in < 0; d++) {
                if (!rays[d] && ++cast > 64) ray_grid(d);
                in = ray_parity(o.s, rays[d].get(), q, d);
            }
            if (in >= 0) {
                verdict[p] = in ? V_IN : V_OUT;
                break;
            }
        }
        if (verdict[p] == V_UNKNOWN) return false;
    }
    return true;
}

double signed_volume(const Soup &s)
{
    double v = 0;
    for (size_t t = 0; t < s.tri.size() / 3; t++) {
        const double *a = &s.xyz[3 * s.tri[3 * t]], *b = &s.xyz[3 * s.tri[3 * t + 1]],
                     *c = &s.xyz[3 * s.tri[3 * t + 2]];
        v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return v / 6;
}

// Is s a closed oriented 2-manifold (each edge in exactly two triangles,
// once each way)? With `only`, the edges of the flagged triangles.
bool closed_oriented(const Soup &s, const std::vector<char> *only = nullptr)
{
    VertexFaces vf(s);
    for (size_t t = 0; t < s.tri.size() / 3; t++)
        for (int k = 0; k < 3 && (!only || (*only)[t]); k++)
            if (across(s, vf, (uint32_t)t, s.tri[3 * t + k], s.tri[3 * t + (k + 1) % 3]) ==
                UINT32_MAX)
                return false;
    return true;
}

} // namespace

// a ∪ b of two closed shells by corefinement of their near triangles;
// false when that cannot be done or its result fails the checks above.
bool near_union(const Soup &a, const Soup &b, Soup &out, coons_csg_report &rep)
{
    std::vector<char> na, nb;
    mark_near(a, b, na, nb);
    IMesh ma, mb;
    VertexIds ga, gb;
    if (!near_mesh(a, na, ma, ga) || !near_mesh(b, nb, mb, gb)) return false;
    EdgeFlags ea = ma.add_property_map<IMesh::Edge_index, bool>("e:cut", false).first;
    EdgeFlags eb = mb.add_property_map<IMesh::Edge_index, bool>("e:cut", false).first;
    if (ma.num_faces() && mb.num_faces())
        PMP::corefine(ma, mb, CGAL::parameters::edge_is_constrained_map(ea),
                      CGAL::parameters::edge_is_constrained_map(eb));
    Refined ra, rb;
    refined(a, na, ma, ga, ea, ra);
    refined(b, nb, mb, gb, eb, rb);
    std::vector<uint32_t> pa, pb;
    uint32_t npa, npb;
    if (!make_patches(ra, pa, npa) || !make_patches(rb, pb, npb)) return false;
    std::vector<int> va, vb;
    if (!classify(ra, pa, npa, rb, va) || !classify(rb, pb, npb, ra, vb)) return false;
    // The kept triangles; the vertices of the corefined parts that coincide
    // (intersection points, made once and put into both) become one.
    Soup u;
    size_t nva = ra.s.xyz.size() / 3;
    u.xyz = ra.s.xyz;
    u.xyz.insert(u.xyz.end(), rb.s.xyz.begin(), rb.s.xyz.end());
    std::vector<uint32_t> id(u.xyz.size() / 3);
    for (size_t v = 0; v < id.size(); v++) id[v] = (uint32_t)v;
    {
        std::vector<uint32_t> cand;
        std::vector<char> seen(id.size(), 0);
        auto add = [&](const Refined &r, size_t off) {
            for (size_t t = 0; t < r.near.size(); t++)
                if (r.near[t])
                    for (int k = 0; k < 3; k++) {
                        uint32_t v = (uint32_t)(r.s.tri[3 * t + k] + off);
                        if (!seen[v]) {
                            seen[v] = 1;
                            cand.push_back(v);
                        }
                    }
        };
        add(ra, 0);
        add(rb, nva);
        const double *x = u.xyz.data();
        // By value: -0 and 0 are one point (an input vertex at x = 0 and
        // the intersection point made at it may differ in sign).
        auto same = [x](uint32_t p, uint32_t q) {
            return x[3 * p] == x[3 * q] && x[3 * p + 1] == x[3 * q + 1] && x[3 * p + 2] == x[3 * q + 2];
        };
        std::sort(cand.begin(), cand.end(), [x](uint32_t p, uint32_t q) {
            for (int c = 0; c < 3; c++)
                if (x[3 * p + c] != x[3 * q + c]) return x[3 * p + c] < x[3 * q + c];
            return p < q;
        });
        for (size_t i = 1; i < cand.size(); i++)
            if (same(cand[i], cand[i - 1])) id[cand[i]] = id[cand[i - 1]];
    }
    size_t kept = 0;
    std::vector<char> from_near; // per kept triangle
    auto keep = [&](const Refined &r, const std::vector<uint32_t> &patch,
                    const std::vector<int> &verdict, size_t off, bool first) {
        for (size_t t = 0; t < patch.size(); t++) {
            int v = verdict[patch[t]];
            if (v == V_OUT || (first && v == V_SAME)) {
                for (int k = 0; k < 3; k++) u.tri.push_back(id[r.s.tri[3 * t + k] + off]);
                from_near.push_back(r.near[t]);
            }
        }
        for (int v : verdict)
            if (v == V_OUT || (first && v == V_SAME)) kept++;
    };
    keep(ra, pa, va, 0, true);
    keep(rb, pb, vb, nva, false);
    // Drop the vertices no kept triangle uses, in order.
    std::vector<uint32_t> renum(u.xyz.size() / 3, UINT32_MAX);
    for (uint32_t v : u.tri) renum[v] = 0;
    Soup w;
    for (size_t v = 0; v < renum.size(); v++)
        if (renum[v] != UINT32_MAX) {
            renum[v] = (uint32_t)(w.xyz.size() / 3);
            w.xyz.insert(w.xyz.end(), &u.xyz[3 * v], &u.xyz[3 * v] + 3);
        }
    w.tri.reserve(u.tri.size());
    for (uint32_t v : u.tri) w.tri.push_back(renum[v]);
    // Closed and oriented: the far triangles kept are whole patches of a
    // checked shell, joined to the rest only along edges of near ones.
    if (w.tri.empty() || !closed_oriented(w, &from_near)) return false;
    double vA = signed_volume(a), vB = signed_volume(b), vU = signed_volume(w);
    double tol = 1e-9 * (std::fabs(vA) + std::fabs(vB));
    if (!(vA > 0 && vB > 0 && vU >= std::max(vA, vB) - tol && vU <= vA + vB + tol)) return false;
    rep.patches += npa + npb;
    rep.patches_kept += kept;
    out = std::move(w);
    return true;
}

// The fast path for bodies that do not cross themselves: chained unions
// on the inexact-constructions kernel (exact predicates, intersection
// points rounded as they are made), first by corefinement of the near
// triangles only (near_union), else of the whole shells by CGAL's Boolean.
// Such chains can leave crossings (BUILD-NOTES), so a result is accepted
// only when the exact check of the finished double mesh finds none;
// otherwise the exact path runs. Returns true with `s` filled, or false.
bool fast_union(const double *sxyz, const uint32_t *tri, const std::vector<Part> &parts,
                const std::vector<size_t> &ids, coons_csg_report &rep, Progress prog, double p0,
                double p1, unsigned threads, Soup &s)
{
    try {
        std::vector<Soup> shells(ids.size());
        for (size_t k = 0; k < ids.size(); k++) {
            const Part &p = parts[ids[k]];
            Soup &sh = shells[k];
            sh.xyz.assign(sxyz + 3 * p.vert_first, sxyz + 3 * (p.vert_first + p.vert_count));
            sh.tri.reserve(3 * p.tri_count);
            for (size_t i = 0; i < 3 * p.tri_count; i++)
                sh.tri.push_back(tri[3 * p.tri_first + i] - (uint32_t)p.vert_first);
            for (size_t t = 0; t < p.tri_count; t++)
                if (CGAL::collinear(point(sh, sh.tri[3 * t]), point(sh, sh.tri[3 * t + 1]),
                                    point(sh, sh.tri[3 * t + 2])))
                    return false;
            if (!closed_oriented(sh)) return false;
        }
        // The result, welded and checked; false when the check finds a
        // crossing or a zero-area triangle.
        auto finish = [&](Soup &r, coons_csg_report &scratch) {
            prog("verify", p0 + (p1 - p0) * 0.95);
            weld(r, sxyz, parts, ids, scratch);
            // The local final check: only pairs with a triangle that is
            // not an input triangle unchanged (new vertices, or moved by
            // merging and sliver fixing) are tested; the input shells were
            // checked clean, and corefinement split every input pair that
            // crosses.
            InputTriangles old;
            input_triangles(sxyz, tri, parts, ids, old);
            size_t degenerate = 0;
            return !count_self_intersections(r.xyz.data(), r.xyz.size() / 3, r.tri.data(),
                                             r.tri.size() / 3, &degenerate, threads, &old) &&
                   !degenerate;
        };
        if (!coons__csg_whole_corefinement_set()) {
            coons_csg_report scratch = rep;
            Soup acc = shells[0];
            bool ok = true;
            for (size_t k = 1; k < ids.size() && ok; k++) {
                prog("union", p0 + (p1 - p0) * k / ids.size());
                Soup next;
                ok = near_union(acc, shells[k], next, scratch);
                acc = std::move(next);
            }
            if (ok && finish(acc, scratch)) {
                rep = scratch;
                rep.fast_unions++;
                s = std::move(acc);
                return true;
            }
        }
        std::vector<IMesh> ms(ids.size());
        for (size_t k = 0; k < ids.size(); k++) {
            const Soup &sh = shells[k];
            std::vector<IMesh::Vertex_index> vs;
            for (size_t v = 0; v < sh.xyz.size() / 3; v++)
                vs.push_back(ms[k].add_vertex(point(sh, (uint32_t)v)));
            for (size_t t = 0; t < sh.tri.size() / 3; t++)
                if (ms[k].add_face(vs[sh.tri[3 * t]], vs[sh.tri[3 * t + 1]],
                                   vs[sh.tri[3 * t + 2]]) == IMesh::null_face())
                    return false;
            if (!CGAL::is_closed(ms[k])) return false;
        }
        IMesh acc = std::move(ms[0]);
        for (size_t k = 1; k < ids.size(); k++) {
            prog("union", p0 + (p1 - p0) * k / ids.size());
            if (!PMP::corefine_and_compute_union(acc, ms[k], acc)) return false;
        }
        Soup r;
        std::vector<uint32_t> id(acc.num_vertices(), UINT32_MAX);
        for (auto v : acc.vertices()) {
            id[v] = (uint32_t)(r.xyz.size() / 3);
            const IK::Point_3 &q = acc.point(v);
            r.xyz.insert(r.xyz.end(), {q.x(), q.y(), q.z()});
        }
        for (auto f : acc.faces())
            for (auto v : CGAL::vertices_around_face(acc.halfedge(f), acc)) r.tri.push_back(id[v]);
        coons_csg_report scratch = rep;
        if (!finish(r, scratch)) return false;
        rep = scratch;
        rep.fast_unions++;
        s = std::move(r);
        return true;
    } catch (const std::bad_alloc &) {
        throw;
    } catch (...) {
        return false;
    }
}

} // namespace coons_csg
