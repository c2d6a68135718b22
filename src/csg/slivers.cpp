// SPDX-License-Identifier: GPL-3.0-or-later
//
// Sliver repair after rounding (fix_slivers in cgal_common.hpp), free of
// CGAL: the one exact predicate it needs, collinearity of three points
// (exact_collinear), is CGAL's and lives in cgal_fast.cpp; the order of
// three collinear points along their line needs only comparisons of their
// coordinates.
#include <unordered_map>

#include "cgal_common.hpp"

namespace coons_csg {

namespace {

// Of three collinear points, does q lie between p and r (closed)? Compares
// coordinates only, so it is exact; as CGAL's
// collinear_are_ordered_along_line, which fix_slivers used before.
bool ordered_along_line(const double *p, const double *q, const double *r)
{
    for (int c = 0; c < 3; c++) {
        if (p[c] < q[c]) return !(r[c] < q[c]);
        if (q[c] < p[c]) return !(q[c] < r[c]);
    }
    return true; // p == q
}

} // namespace

// Rounding can flatten a thin exact triangle (a, b, c) so that one vertex
// m lies on the segment between the other two, p and q. Such a sliver is
// removed and the triangle across its long edge (q, p, d) is split at m into
// (q, m, d) and (m, p, d): the surface stays closed and oriented, and the
// split triangles lie in the plane of the old one.
void fix_slivers(Soup &s, coons_csg_report &rep)
{
    auto P = [&](uint32_t i) { return &s.xyz[3 * (size_t)i]; };
    for (int round = 0; round < 8; round++) {
        size_t nt = s.tri.size() / 3;
        bool any = false;
        for (size_t t = 0; t < nt && !any; t++)
            any = exact_collinear(P(s.tri[3 * t]), P(s.tri[3 * t + 1]), P(s.tri[3 * t + 2]));
        if (!any) return;
        std::unordered_map<uint64_t, size_t> edge; // directed edge -> triangle
        for (size_t t = 0; t < nt; t++)
            for (int k = 0; k < 3; k++)
                edge[directed_edge_key(s.tri[3 * t + k], s.tri[3 * t + (k + 1) % 3])] = t;
        std::vector<char> dead(nt, 0);
        std::vector<uint32_t> extra;
        size_t fixed = 0;
        for (size_t t = 0; t < nt; t++) {
            if (dead[t]) continue;
            uint32_t v[3] = {s.tri[3 * t], s.tri[3 * t + 1], s.tri[3 * t + 2]};
            if (!exact_collinear(P(v[0]), P(v[1]), P(v[2]))) continue;
            // k: index of the middle vertex m; the long edge is v[k+1] -> v[k+2].
            int k = -1;
            for (int i = 0; i < 3 && k < 0; i++)
                if (ordered_along_line(P(v[(i + 1) % 3]), P(v[i]), P(v[(i + 2) % 3])))
                    k = i;
            if (k < 0) continue;
            uint32_t m = v[k], p = v[(k + 1) % 3], q = v[(k + 2) % 3];
            auto it = edge.find(directed_edge_key(q, p));
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

} // namespace coons_csg
