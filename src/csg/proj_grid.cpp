// SPDX-License-Identifier: GPL-3.0-or-later
//
// A uniform grid of triangles projected along an axis (proj_grid.hpp says
// what it holds), free of CGAL: about one triangle per cell, cells of equal
// sides, triangles spanning more than 64 cells kept apart.
#include "proj_grid.hpp"

#include <algorithm>
#include <array>

namespace coons_csg {

ProjGrid::ProjGrid(const Soup &s, const std::vector<uint32_t> &tris, int d)
    : d1_((d + 1) % 3), d2_((d + 2) % 3)
{
    lo_[0] = lo_[1] = HUGE_VAL;
    double *hi = hi_;
    hi[0] = hi[1] = -HUGE_VAL;
    for (uint32_t t : tris)
        for (int k = 0; k < 3; k++) {
            const double *v = &s.xyz[3 * s.tri[3 * (size_t)t + k]];
            lo_[0] = std::min(lo_[0], v[d1_]), hi[0] = std::max(hi[0], v[d1_]);
            lo_[1] = std::min(lo_[1], v[d2_]), hi[1] = std::max(hi[1], v[d2_]);
        }
    double ex[2] = {hi[0] - lo_[0], hi[1] - lo_[1]};
    double side = std::sqrt(std::max(ex[0], 1e-300) * std::max(ex[1], 1e-300) /
                            std::max<size_t>(tris.size(), 1));
    for (int c = 0; c < 2; c++) {
        double n = ex[c] > 0 && side > 0 ? std::ceil(ex[c] / side) : 1;
        n_[c] = n < 1 || !(n < 4096) ? (n < 1 ? 1 : 4096) : (int)n;
        w_[c] = ex[c] > 0 ? ex[c] / n_[c] : 1.0;
    }
    std::vector<std::array<int, 4>> span(tris.size());
    std::vector<uint32_t> count((size_t)n_[0] * n_[1] + 1, 0);
    for (size_t i = 0; i < tris.size(); i++) {
        const uint32_t *q = &s.tri[3 * (size_t)tris[i]];
        double a[2] = {HUGE_VAL, HUGE_VAL}, b[2] = {-HUGE_VAL, -HUGE_VAL};
        for (int k = 0; k < 3; k++) {
            const double *v = &s.xyz[3 * q[k]];
            a[0] = std::min(a[0], v[d1_]), b[0] = std::max(b[0], v[d1_]);
            a[1] = std::min(a[1], v[d2_]), b[1] = std::max(b[1], v[d2_]);
        }
        std::array<int, 4> &sp = span[i];
        sp = {cell(a[0], 0), cell(b[0], 0), cell(a[1], 1), cell(b[1], 1)};
        if ((size_t)(sp[1] - sp[0] + 1) * (size_t)(sp[3] - sp[2] + 1) > 64) {
            big_.push_back(tris[i]);
            sp[0] = -1;
            continue;
        }
        for (int x = sp[0]; x <= sp[1]; x++)
            for (int y = sp[2]; y <= sp[3]; y++) count[(size_t)x * n_[1] + y + 1]++;
    }
    for (size_t c = 1; c < count.size(); c++) count[c] += count[c - 1];
    first_ = count;
    items_.resize(count.back());
    for (size_t i = 0; i < tris.size(); i++) {
        const std::array<int, 4> &sp = span[i];
        if (sp[0] < 0) continue;
        for (int x = sp[0]; x <= sp[1]; x++)
            for (int y = sp[2]; y <= sp[3]; y++) items_[count[(size_t)x * n_[1] + y]++] = tris[i];
    }
}

} // namespace coons_csg
