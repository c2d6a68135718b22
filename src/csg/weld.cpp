// SPDX-License-Identifier: GPL-3.0-or-later
//
// Welding of a Boolean result (weld in cgal_common.hpp), free of CGAL:
// the result put in canonical order (canonical_order.cpp), its vertices
// closer than 1e-11 of its size merged (only those the Boolean made:
// fresh_vertices, input_identity.cpp), the triangles that this collapses or
// doubles dropped, then the slivers that rounding flattened split away
// (slivers.cpp). Both CGAL units finish their results here, the exact path
// (cgal_solid.cpp) and the fast path (cgal_fast.cpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "cgal_common.hpp"

namespace coons_csg {

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
    typedef std::array<uint32_t, 3> Triple;
    struct TripleHash {
        size_t operator()(const Triple &v) const { return (size_t)pack21(v[0], v[1], v[2]); }
    };
    std::unordered_map<Triple, size_t, TripleHash> seen; // sorted vertex triple -> index in out/3
    std::vector<char> dead;
    for (size_t t = 0; t < s.tri.size() / 3; t++) {
        uint32_t a = rep_of[s.tri[3 * t]], b = rep_of[s.tri[3 * t + 1]], c = rep_of[s.tri[3 * t + 2]];
        if (a == b || b == c || a == c) continue;
        Triple k{a, b, c};
        std::sort(k.begin(), k.end());
        auto it = seen.find(k);
        if (it != seen.end() && !dead[it->second]) {
            // two copies: opposite ones cancel, equal ones are one
            const uint32_t *o = &out[3 * it->second];
            bool same = (o[0] == a && o[1] == b) || (o[1] == a && o[2] == b) || (o[2] == a && o[0] == b);
            if (!same) dead[it->second] = 1;
            continue;
        }
        seen[k] = out.size() / 3;
        out.insert(out.end(), {a, b, c});
        dead.push_back(0);
    }
    s.tri.clear();
    for (size_t t = 0; t < out.size() / 3; t++)
        if (!dead[t]) s.tri.insert(s.tri.end(), out.begin() + 3 * t, out.begin() + 3 * t + 3);
}

void weld(Soup &s, const double *xyz, const std::vector<Part> &parts, const std::vector<size_t> &ids,
          coons_csg_report &rep)
{
    canonical_order(s);
    std::vector<char> fresh = fresh_vertices(s, xyz, parts, ids);
    merge_close(s, rep, &fresh);
    fix_slivers(s, rep);
}

} // namespace coons_csg
