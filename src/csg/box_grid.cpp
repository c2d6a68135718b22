// SPDX-License-Identifier: GPL-3.0-or-later
//
// Hierarchical uniform grids of triangle boxes (box_grid.hpp says how they
// find the pairs of boxes that meet), free of CGAL. Cells are keyed by
// pack21 (cgal_common.hpp): at most 2^21 cells along an axis.
#include "box_grid.hpp"

#include <algorithm>
#include <cmath>

#include "cgal_common.hpp"

namespace coons_csg {

BoxGrid::BoxGrid(const std::vector<GridBox> &boxes, PairTest test, const void *ctx)
    : test_(test), ctx_(ctx), n_(boxes.size())
{
    bx_.reserve(n_);
    for (const GridBox &b : boxes) {
        BB q;
        for (int c = 0; c < 3; c++) q.lo[c] = b.lo[c], q.hi[c] = b.hi[c];
        q.t = b.t;
        q.old = b.old;
        bx_.push_back(q);
    }
    double emin = HUGE_VAL, span = 0, top[3];
    for (int c = 0; c < 3; c++) org_[c] = HUGE_VAL, top[c] = -HUGE_VAL;
    for (const BB &q : bx_) {
        for (int c = 0; c < 3; c++) {
            org_[c] = std::min(org_[c], q.lo[c]);
            top[c] = std::max(top[c], q.hi[c]);
        }
        double e = extent(q);
        if (e > 0) emin = std::min(emin, e);
    }
    for (int c = 0; c < 3; c++) span = std::max(span, top[c] - org_[c]);
    ok_ = std::isfinite(span);
    if (!ok_) return; // extents beyond doubles: the caller uses the reference
    // the finest level fits the smallest box, with at most 2^20 cells
    // along an axis (keys pack 21 bits per axis)
    double h = std::max(0.5 * emin, span / 1048576.0);
    if (!(h > 0) || !std::isfinite(h)) h = 1.0;
    int nlev = 1;
    for (BB &q : bx_) {
        double e = extent(q), hl = h;
        int L = 0;
        while (e > 2 * hl && L < 15) {
            hl *= 4;
            L++;
        }
        q.level = (unsigned char)L;
        nlev = std::max(nlev, L + 1);
    }
    inv_.assign(nlev, 1.0 / h);
    for (int L = 1; L < nlev; L++) inv_[L] = 0.25 * inv_[L - 1];
    cells_.resize(nlev);
    std::vector<size_t> per(nlev, 0);
    for (BB &q : bx_) {
        uint32_t hi[3];
        range(q, q.level, q.cell, hi);
        per[q.level] += (size_t)(hi[0] - q.cell[0] + 1) * (hi[1] - q.cell[1] + 1) * (hi[2] - q.cell[2] + 1);
    }
    for (int L = 0; L < nlev; L++) cells_[L].reserve(per[L]);
    for (size_t i = 0; i < n_; i++) {
        const BB &q = bx_[i];
        uint32_t hi[3];
        range(q, q.level, nullptr, hi);
        for (uint64_t z = q.cell[2]; z <= hi[2]; z++)
            for (uint64_t y = q.cell[1]; y <= hi[1]; y++)
                for (uint64_t x = q.cell[0]; x <= hi[0]; x++)
                    cells_[q.level].push_back({pack21(x, y, z), (uint32_t)i});
    }
    for (auto &E : cells_) {
        radix_sort(E);
        std::vector<size_t> g;
        for (size_t k = 0; k < E.size(); k++)
            if (k == 0 || E[k].key != E[k - 1].key) g.push_back(k);
        g.push_back(E.size());
        groups_.push_back(std::move(g));
    }
    for (int L = 0; L < nlev; L++)
        if (!cells_[L].empty()) used_.push_back(L);
}

size_t BoxGrid::run(size_t task) const
{
    size_t count = 0, cc = cell_chunks();
    if (task < cc) {
        size_t L = 0, t = task;
        while (t >= chunks(groups_[L].size() - 1)) t -= chunks(groups_[L++].size() - 1);
        const std::vector<Entry> &E = cells_[L];
        const std::vector<size_t> &g = groups_[L];
        size_t g1 = std::min(g.size() - 1, (t + 1) * kChunk);
        for (size_t gi = t * kChunk; gi < g1; gi++)
            for (size_t a = g[gi]; a < g[gi + 1]; a++) {
                const BB &A = bx_[E[a].box];
                for (size_t b = a + 1; b < g[gi + 1]; b++)
                    count += test(A, bx_[E[b].box], A.cell, E[a].key);
            }
        return count;
    }
    size_t i1 = std::min(n_, (task - cc + 1) * kChunk);
    for (size_t i = (task - cc) * kChunk; i < i1; i++) {
        const BB &A = bx_[i];
        for (int L : used_) {
            if (L <= A.level) continue;
            const std::vector<Entry> &E = cells_[L];
            uint32_t lo[3], hi[3];
            range(A, L, lo, hi);
            for (uint64_t z = lo[2]; z <= hi[2]; z++)
                for (uint64_t y = lo[1]; y <= hi[1]; y++)
                    for (uint64_t x = lo[0]; x <= hi[0]; x++) {
                        uint64_t k = pack21(x, y, z);
                        auto it = std::lower_bound(E.begin(), E.end(), k,
                                                   [](const Entry &e, uint64_t v) { return e.key < v; });
                        for (; it != E.end() && it->key == k; ++it)
                            count += test(A, bx_[it->box], lo, k);
                    }
        }
    }
    return count;
}

double BoxGrid::extent(const BB &q)
{
    return std::max(q.hi[0] - q.lo[0], std::max(q.hi[1] - q.lo[1], q.hi[2] - q.lo[2]));
}

size_t BoxGrid::cell_chunks() const
{
    size_t k = 0;
    for (const auto &g : groups_) k += chunks(g.size() - 1);
    return k;
}

// The cell index along c of x at level L (monotone in x, so the cell of
// the larger of two coordinates is the larger of their cells).
uint32_t BoxGrid::index(double x, int c, int L) const
{
    double q = std::floor((x - org_[c]) * inv_[L]);
    return q > 0 ? (uint32_t)std::min(q, 2097151.0) : 0;
}

void BoxGrid::range(const BB &q, int L, uint32_t *lo, uint32_t hi[3]) const
{
    for (int c = 0; c < 3; c++) {
        if (lo) lo[c] = index(q.lo[c], c, L);
        hi[c] = index(q.hi[c], c, L);
    }
}

// Keys sorted (the order inside a cell does not matter: every pair in
// it is looked at): least significant 16 bits first, skipping the
// digits all keys share; small sets by std::sort.
void BoxGrid::radix_sort(std::vector<Entry> &E)
{
    auto by_key = [](const Entry &a, const Entry &b) { return a.key < b.key; };
    if (E.size() < 4096) {
        std::sort(E.begin(), E.end(), by_key);
        return;
    }
    std::vector<Entry> tmp(E.size());
    std::vector<size_t> cnt(1u << 16);
    for (int shift = 0; shift < 64; shift += 16) {
        std::fill(cnt.begin(), cnt.end(), 0);
        for (const Entry &e : E) cnt[(e.key >> shift) & 0xFFFF]++;
        if (cnt[(E[0].key >> shift) & 0xFFFF] == E.size()) continue;
        size_t sum = 0;
        for (size_t &c : cnt) {
            size_t k = c;
            c = sum;
            sum += k;
        }
        for (const Entry &e : E) tmp[cnt[(e.key >> shift) & 0xFFFF]++] = e;
        E.swap(tmp);
    }
}

// Boxes a and b meet, in cell `key` as their home (`acell`: a's low
// corner's cell at this level), and their triangles intersect: 1.
size_t BoxGrid::test(const BB &a, const BB &b, const uint32_t *acell, uint64_t key) const
{
    if (a.old && b.old) return 0; // two kept triangles
    for (int c = 0; c < 3; c++)
        if (a.hi[c] < b.lo[c] || b.hi[c] < a.lo[c]) return 0;
    uint64_t home = pack21(std::max(acell[0], b.cell[0]), std::max(acell[1], b.cell[1]),
                           std::max(acell[2], b.cell[2]));
    if (home != key) return 0;
    return test_(ctx_, a.t, b.t) ? 1 : 0;
}

} // namespace coons_csg
