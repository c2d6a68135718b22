// SPDX-License-Identifier: GPL-3.0-or-later
//
// The fast path of the CGAL layer (see cgal_solid.cpp's file comment),
// compiled WITHOUT CGAL's assertions: chained corefinement of bodies that do
// not cross themselves on the inexact-constructions kernel, the exact
// self-intersection test (input checks and the final check of every result),
// the triangle-level test of which parts meet, and the welding of results.
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
#include <new>
#include <unordered_map>

#include "csg/cgal_common.hpp"

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

// Two triangles of a soup given by vertex indices intersect other than in
// what their shared indices allow (a shared edge, a shared vertex)?
bool pair_intersects(const std::vector<IK::Point_3> &P, const uint32_t *s, const uint32_t *t)
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
    if (shared == 0) return CGAL::do_intersect(IK::Triangle_3(a, b, c), IK::Triangle_3(d, e, f));
    if (shared >= 3) return true;
    if (shared == 2) {
        int so = 3 - si[0] - si[1], to = 3 - ti[0] - ti[1];
        const IK::Point_3 &p = P[s[si[0]]], &q = P[s[si[1]]], &x = P[s[so]], &y = P[t[to]];
        if (CGAL::orientation(p, q, x, y) != CGAL::COPLANAR) return false;
        return CGAL::coplanar_orientation(p, q, x, y) == CGAL::POSITIVE;
    }
    const IK::Point_3 &v = P[s[si[0]]];
    const IK::Point_3 &s1 = P[s[(si[0] + 1) % 3]], &s2 = P[s[(si[0] + 2) % 3]];
    const IK::Point_3 &t1 = P[t[(ti[0] + 1) % 3]], &t2 = P[t[(ti[0] + 2) % 3]];
    // Along some axis, one triangle's other vertices strictly below v and
    // the other's not below it: they meet only at v (exact comparisons;
    // this settles about half the pairs of a flat fan, whose orientation
    // tests below are exact zeros and cost an exact evaluation each).
    for (int c = 0; c < 3; c++) {
        double vc = v[c];
        if (s1[c] < vc && s2[c] < vc && t1[c] >= vc && t2[c] >= vc) return false;
        if (t1[c] < vc && t2[c] < vc && s1[c] >= vc && s2[c] >= vc) return false;
        if (s1[c] > vc && s2[c] > vc && t1[c] <= vc && t2[c] <= vc) return false;
        if (t1[c] > vc && t2[c] > vc && s1[c] <= vc && s2[c] <= vc) return false;
    }
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

// Exact intersections of inputs whose own rounding noise differs (a NURBS
// point at x = 2e-16 against a wall at x = 0) give features narrower than
// doubles can hold, which rounding turns into overlaps. Vertices closer
// than 1e-11 of the part's size (far below any tolerance) are merged, and
// the triangles that this collapses or doubles (two opposite copies) go.
// With `fresh` (a flag per vertex), only the flagged vertices (those that
// corefinement made) move, each onto the first earlier vertex that stays
// within that distance; the others (input vertices, distinct and checked
// with their shells) are looked at only where a flagged one is near.
void merge_close(Soup &s, coons_csg_report &rep, const std::vector<char> *fresh)
{
    size_t nv = s.xyz.size() / 3;
    if (!nv) return;
    double lo[3], hi[3];
    bbox_empty(lo, hi);
    for (size_t v = 0; v < nv; v++) bbox_add(lo, hi, &s.xyz[3 * v]);
    double eps = 1e-11 * bbox_diag(lo, hi);
    if (!(eps > 0)) return;
    auto cell = [&](size_t v, int c) { return (int64_t)std::floor((s.xyz[3 * v + c] - lo[c]) / eps); };
    struct H {
        size_t operator()(const std::array<int64_t, 3> &k) const
        {
            return (size_t)(k[0] * 73856093 ^ k[1] * 19349663 ^ k[2] * 83492791);
        }
    };
    std::unordered_map<std::array<int64_t, 3>, std::vector<uint32_t>, H> grid;
    std::vector<uint32_t> rep_of(nv);
    for (size_t v = 0; v < nv; v++) rep_of[v] = (uint32_t)v;
    if (fresh) {
        // the cells next to a fresh vertex, then the fixed vertices in them
        std::unordered_map<std::array<int64_t, 3>, char, H> hot;
        for (size_t v = 0; v < nv; v++)
            if ((*fresh)[v])
                for (int dx = -1; dx <= 1; dx++)
                    for (int dy = -1; dy <= 1; dy++)
                        for (int dz = -1; dz <= 1; dz++)
                            hot[{cell(v, 0) + dx, cell(v, 1) + dy, cell(v, 2) + dz}] = 1;
        if (hot.empty()) return;
        for (size_t v = 0; v < nv; v++) {
            if ((*fresh)[v]) continue;
            std::array<int64_t, 3> k{cell(v, 0), cell(v, 1), cell(v, 2)};
            if (hot.count(k)) grid[k].push_back((uint32_t)v);
        }
    }
    for (size_t v = 0; v < nv; v++) {
        if (fresh && !(*fresh)[v]) continue;
        std::array<int64_t, 3> k{cell(v, 0), cell(v, 1), cell(v, 2)};
        uint32_t found = UINT32_MAX;
        for (int dx = -1; dx <= 1 && found == UINT32_MAX; dx++)
            for (int dy = -1; dy <= 1 && found == UINT32_MAX; dy++)
                for (int dz = -1; dz <= 1 && found == UINT32_MAX; dz++) {
                    auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
                    if (it == grid.end()) continue;
                    for (uint32_t w : it->second) {
                        double d = 0;
                        for (int c = 0; c < 3; c++) d = std::max(d, std::fabs(s.xyz[3 * v + c] - s.xyz[3 * w + c]));
                        if (d <= eps) {
                            found = w;
                            break;
                        }
                    }
                }
        if (found != UINT32_MAX) {
            rep_of[v] = found;
            rep.close_merged++;
        } else {
            grid[k].push_back((uint32_t)v);
        }
    }
    if (!rep.close_merged) return;
    std::vector<uint32_t> out;
    std::unordered_map<uint64_t, size_t> seen; // sorted vertex triple -> index in out/3
    std::vector<char> dead;
    auto key = [](uint32_t a, uint32_t b, uint32_t c) {
        uint32_t v[3] = {a, b, c};
        std::sort(v, v + 3);
        return ((uint64_t)v[0] * 2654435761u) ^ ((uint64_t)v[1] << 21) ^ ((uint64_t)v[2] << 42);
    };
    for (size_t t = 0; t < s.tri.size() / 3; t++) {
        uint32_t a = rep_of[s.tri[3 * t]], b = rep_of[s.tri[3 * t + 1]], c = rep_of[s.tri[3 * t + 2]];
        if (a == b || b == c || a == c) continue;
        uint64_t k = key(a, b, c);
        auto it = seen.find(k);
        if (it != seen.end() && !dead[it->second]) {
            const uint32_t *o = &out[3 * it->second];
            uint32_t x[3] = {a, b, c}, y[3] = {o[0], o[1], o[2]};
            std::sort(x, x + 3);
            std::sort(y, y + 3);
            if (x[0] == y[0] && x[1] == y[1] && x[2] == y[2]) {
                dead[it->second] = 1; // two copies: opposite ones cancel, equal ones are one
                bool same = (o[0] == a && o[1] == b) || (o[1] == a && o[2] == b) || (o[2] == a && o[0] == b);
                if (same) dead[it->second] = 0;
                continue;
            }
        }
        seen[k] = out.size() / 3;
        out.insert(out.end(), {a, b, c});
        dead.push_back(0);
    }
    s.tri.clear();
    for (size_t t = 0; t < out.size() / 3; t++)
        if (!dead[t]) s.tri.insert(s.tri.end(), out.begin() + 3 * t, out.begin() + 3 * t + 3);
}

// Rounding can flatten a thin exact triangle (a, b, c) so that one vertex
// m lies on the segment between the other two, p and q. Such a sliver is
// removed and the triangle across its long edge (q, p, d) is split at m into
// (q, m, d) and (m, p, d): the surface stays closed and oriented, and the
// split triangles lie in the plane of the old one.
void fix_slivers(Soup &s, coons_csg_report &rep)
{
    auto P = [&](uint32_t i) { return IK::Point_3(s.xyz[3 * i], s.xyz[3 * i + 1], s.xyz[3 * i + 2]); };
    for (int round = 0; round < 8; round++) {
        size_t nt = s.tri.size() / 3;
        bool any = false;
        for (size_t t = 0; t < nt && !any; t++)
            any = CGAL::collinear(P(s.tri[3 * t]), P(s.tri[3 * t + 1]), P(s.tri[3 * t + 2]));
        if (!any) return;
        std::unordered_map<uint64_t, size_t> edge; // directed edge -> triangle
        for (size_t t = 0; t < nt; t++)
            for (int k = 0; k < 3; k++)
                edge[((uint64_t)s.tri[3 * t + k] << 32) | s.tri[3 * t + (k + 1) % 3]] = t;
        std::vector<char> dead(nt, 0);
        std::vector<uint32_t> extra;
        size_t fixed = 0;
        for (size_t t = 0; t < nt; t++) {
            if (dead[t]) continue;
            uint32_t v[3] = {s.tri[3 * t], s.tri[3 * t + 1], s.tri[3 * t + 2]};
            if (!CGAL::collinear(P(v[0]), P(v[1]), P(v[2]))) continue;
            // k: index of the middle vertex m; the long edge is v[k+1] -> v[k+2].
            int k = -1;
            for (int i = 0; i < 3 && k < 0; i++)
                if (CGAL::collinear_are_ordered_along_line(P(v[(i + 1) % 3]), P(v[i]), P(v[(i + 2) % 3])))
                    k = i;
            if (k < 0) continue;
            uint32_t m = v[k], p = v[(k + 1) % 3], q = v[(k + 2) % 3];
            auto it = edge.find(((uint64_t)q << 32) | p);
            if (it == edge.end() || dead[it->second] || it->second == t) continue;
            size_t n = it->second;
            uint32_t d = UINT32_MAX;
            for (int i = 0; i < 3; i++)
                if (s.tri[3 * n + i] != q && s.tri[3 * n + i] != p) d = s.tri[3 * n + i];
            if (d == UINT32_MAX || d == m) continue;
            dead[t] = dead[n] = 1;
            extra.insert(extra.end(), {q, m, d, m, p, d});
            fixed++;
        }
        if (!fixed) return;
        rep.slivers_fixed += fixed;
        std::vector<uint32_t> keep;
        keep.reserve(s.tri.size());
        for (size_t t = 0; t < nt; t++)
            if (!dead[t]) keep.insert(keep.end(), s.tri.begin() + 3 * t, s.tri.begin() + 3 * t + 3);
        keep.insert(keep.end(), extra.begin(), extra.end());
        s.tri.swap(keep);
    }
}


namespace {

// The order of canonical_order(): by coordinates, ties (-0 and 0) by bytes.
inline bool point_less(const double *p, const double *q)
{
    for (int c = 0; c < 3; c++) {
        if (p[c] < q[c]) return true;
        if (q[c] < p[c]) return false;
    }
    return std::memcmp(p, q, 3 * sizeof(double)) < 0;
}

} // namespace

void canonical_order(Soup &s)
{
    size_t nv = s.xyz.size() / 3, nt = s.tri.size() / 3;
    std::vector<uint32_t> order(nv), rank(nv);
    for (size_t v = 0; v < nv; v++) order[v] = (uint32_t)v;
    const double *x = s.xyz.data();
    std::stable_sort(order.begin(), order.end(),
                     [x](uint32_t a, uint32_t b) { return point_less(x + 3 * a, x + 3 * b); });
    std::vector<double> xyz(3 * nv);
    for (size_t k = 0; k < nv; k++) {
        rank[order[k]] = (uint32_t)k;
        std::memcpy(&xyz[3 * k], x + 3 * order[k], 3 * sizeof(double));
    }
    std::vector<std::array<uint32_t, 3>> t(nt);
    for (size_t i = 0; i < nt; i++) {
        uint32_t a = rank[s.tri[3 * i]], b = rank[s.tri[3 * i + 1]], c = rank[s.tri[3 * i + 2]];
        if (b < a && b < c)
            t[i] = {b, c, a};
        else if (c < a && c < b)
            t[i] = {c, a, b};
        else
            t[i] = {a, b, c};
    }
    std::sort(t.begin(), t.end());
    s.xyz.swap(xyz);
    for (size_t i = 0; i < nt; i++)
        for (int k = 0; k < 3; k++) s.tri[3 * i + k] = t[i][k];
}

std::vector<char> fresh_vertices(const Soup &s, const double *xyz, const std::vector<Part> &parts,
                                 const std::vector<size_t> &ids)
{
    std::vector<const double *> in;
    for (size_t id : ids)
        for (size_t v = 0; v < parts[id].vert_count; v++)
            in.push_back(xyz + 3 * (parts[id].vert_first + v));
    std::sort(in.begin(), in.end(), point_less);
    size_t nv = s.xyz.size() / 3, j = 0;
    std::vector<char> fresh(nv, 1);
    for (size_t v = 0; v < nv; v++) {
        const double *p = &s.xyz[3 * v];
        while (j < in.size() && point_less(in[j], p)) j++;
        if (j < in.size() && !point_less(p, in[j])) fresh[v] = 0;
    }
    return fresh;
}

TriKey tri_key(const double *a, const double *b, const double *c)
{
    const double *q[3] = {a, b, c};
    int first = 0;
    for (int i = 1; i < 3; i++)
        if (std::memcmp(q[i], q[first], 3 * sizeof(double)) < 0) first = i;
    TriKey k;
    for (int i = 0; i < 3; i++) std::memcpy(k.v + 3 * i, q[(first + i) % 3], 3 * sizeof(double));
    return k;
}

void input_triangles(const double *xyz, const uint32_t *tri, const std::vector<Part> &parts,
                     const std::vector<size_t> &ids, InputTriangles &out)
{
    size_t n = 0;
    for (size_t id : ids) n += parts[id].tri_count;
    out.reserve(n);
    for (size_t id : ids) {
        const Part &p = parts[id];
        for (size_t t = p.tri_first; t < p.tri_first + p.tri_count; t++) {
            const uint32_t *q = tri + 3 * t;
            out.insert(tri_key(xyz + 3 * q[0], xyz + 3 * q[1], xyz + 3 * q[2]));
        }
    }
}

namespace {

typedef CGAL::Box_intersection_d::Box_with_info_d<double, 3, size_t> Box;

// Pairs among `fresh` and between `fresh` and `old` boxes that intersect,
// counted only when the low x end of their common box lies in [x0, x1).
size_t count_in_slab(const std::vector<IK::Point_3> &P, const uint32_t *tri,
                     std::vector<Box> &fresh, std::vector<Box> &old, double x0, double x1)
{
    size_t count = 0;
    auto test = [&](const Box &x, const Box &y) {
        double m = std::max(x.min_coord(0), y.min_coord(0));
        if (m < x0 || m >= x1) return;
        if (pair_intersects(P, tri + 3 * x.info(), tri + 3 * y.info())) count++;
    };
    CGAL::box_self_intersection_d<CGAL::Sequential_tag>(fresh.begin(), fresh.end(), test);
    if (!old.empty() && !fresh.empty())
        CGAL::box_intersection_d<CGAL::Sequential_tag>(fresh.begin(), fresh.end(), old.begin(),
                                                       old.end(), test);
    return count;
}

} // namespace

size_t count_self_intersections(const double *xyz, size_t nv, const uint32_t *tri, size_t nt,
                                size_t *degenerate, unsigned threads, const InputTriangles *old)
{
    std::vector<IK::Point_3> P;
    P.reserve(nv);
    for (size_t i = 0; i < nv; i++) P.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    std::vector<Box> fresh, kept;
    fresh.reserve(old ? nt / 4 : nt);
    for (size_t t = 0; t < nt; t++) {
        const uint32_t *q = tri + 3 * t;
        bool is_old = old && old->count(tri_key(xyz + 3 * q[0], xyz + 3 * q[1], xyz + 3 * q[2]));
        if (q[0] == q[1] || q[1] == q[2] || q[0] == q[2]) continue;
        if (!is_old && CGAL::collinear(P[q[0]], P[q[1]], P[q[2]])) {
            // A zero-area triangle bounds nothing; it is counted, not tested.
            if (degenerate) (*degenerate)++;
            continue;
        }
        CGAL::Bbox_3 bb = P[q[0]].bbox() + P[q[1]].bbox() + P[q[2]].bbox();
        (is_old ? kept : fresh).emplace_back(bb, t);
    }
    if (fresh.empty()) return 0;
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

// The fast path for bodies that do not cross themselves: chained
// corefinement on the inexact-constructions kernel (exact predicates,
// intersection points rounded as they are made). Such chains can leave
// crossings (BUILD-NOTES), so the result is accepted only when the exact
// check of the finished double mesh finds none; otherwise the exact path
// runs. Returns true with `s` filled, or false.
bool fast_union(const double *sxyz, const uint32_t *tri, const std::vector<Part> &parts,
                const std::vector<size_t> &ids, coons_csg_report &rep, Progress prog, double p0,
                double p1, unsigned threads, Soup &s)
{
    try {
        std::vector<IMesh> ms(ids.size());
        for (size_t k = 0; k < ids.size(); k++) {
            const Part &p = parts[ids[k]];
            std::vector<IMesh::Vertex_index> vs;
            for (size_t v = 0; v < p.vert_count; v++) {
                const double *q = sxyz + 3 * (p.vert_first + v);
                vs.push_back(ms[k].add_vertex(IK::Point_3(q[0], q[1], q[2])));
            }
            for (size_t t = 0; t < p.tri_count; t++) {
                const uint32_t *q = tri + 3 * (p.tri_first + t);
                auto a = vs[q[0] - p.vert_first], b = vs[q[1] - p.vert_first], c = vs[q[2] - p.vert_first];
                if (CGAL::collinear(ms[k].point(a), ms[k].point(b), ms[k].point(c)) ||
                    ms[k].add_face(a, b, c) == IMesh::null_face())
                    return false;
            }
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
        prog("verify", p0 + (p1 - p0) * 0.95);
        canonical_order(r);
        coons_csg_report scratch = rep;
        std::vector<char> fresh = fresh_vertices(r, sxyz, parts, ids);
        merge_close(r, scratch, &fresh);
        fix_slivers(r, scratch);
        // The local final check: only pairs with a triangle that is not
        // an input triangle unchanged (new vertices, or moved by merging and
        // sliver fixing) are tested; the input shells were checked clean, and
        // corefinement split every input pair that crosses.
        InputTriangles old;
        input_triangles(sxyz, tri, parts, ids, old);
        size_t degenerate = 0;
        if (count_self_intersections(r.xyz.data(), r.xyz.size() / 3, r.tri.data(),
                                     r.tri.size() / 3, &degenerate, threads, &old) ||
            degenerate)
            return false;
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
