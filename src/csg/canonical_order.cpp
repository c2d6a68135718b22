// SPDX-License-Identifier: GPL-3.0-or-later
//
// The canonical order of a Boolean result (canonical_order in
// cgal_common.hpp), free of CGAL: vertices sorted by coordinates
// (point_less), each triangle rotated to start at its lowest vertex,
// triangles sorted. CGAL's output order depends on where its allocations
// land (handles compared by address); this order makes results
// independent of the heap and of threads.
#include <algorithm>
#include <array>

#include "cgal_common.hpp"

namespace coons_csg {

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

} // namespace coons_csg
