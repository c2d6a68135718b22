// SPDX-License-Identifier: GPL-3.0-or-later
//
// A uniform grid of triangles projected along an axis (proj_grid.cpp), free
// of CGAL: the candidates of the ray parity and coplanar-cover tests of the
// near chain (cgal_fast.cpp).
#ifndef COONS_PROJ_GRID_HPP
#define COONS_PROJ_GRID_HPP

#include <cmath>

#include "cgal_common.hpp"

namespace coons_csg {

// Triangles of a shell in the cells of a uniform grid over their
// projection along axis d (dropping coordinate d): the candidates whose
// projected closed box holds a point are those of its cell (a box that
// holds the point overlaps its cell, cells being found by the same
// monotone function of the coordinates) and the few large ones, kept
// apart.
class ProjGrid {
  public:
    // The triangles `tris` of s, projected along axis d.
    ProjGrid(const Soup &s, const std::vector<uint32_t> &tris, int d);

    // Calls f(t) for every candidate triangle t at point q (3-D, q[d]
    // ignored); stops early when f returns false.
    template <class F> bool each(const double *q, F f) const
    {
        for (uint32_t t : big_)
            if (!f(t)) return false;
        if (!(q[d1_] >= lo_[0] && q[d1_] <= hi_[0] && q[d2_] >= lo_[1] && q[d2_] <= hi_[1]))
            return true;
        size_t c = (size_t)cell(q[d1_], 0) * n_[1] + cell(q[d2_], 1);
        for (uint32_t i = first_[c]; i < first_[c + 1]; i++)
            if (!f(items_[i])) return false;
        return true;
    }

  private:
    int cell(double x, int c) const
    {
        double q = std::floor((x - lo_[c]) / w_[c]);
        return q < 0 ? 0 : q > n_[c] - 1 ? n_[c] - 1 : (int)q;
    }
    int d1_, d2_, n_[2];
    double lo_[2], hi_[2], w_[2];
    std::vector<uint32_t> first_, items_, big_;
};

} // namespace coons_csg

#endif
