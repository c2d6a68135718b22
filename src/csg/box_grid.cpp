// SPDX-License-Identifier: GPL-3.0-or-later
//
// Hierarchical uniform grids of triangle boxes (box_grid.hpp says how they
// find the pairs of boxes that meet), free of CGAL. Cells are keyed by
// pack21 (cgal_common.hpp): at most 2^21 cells along an axis.
#include "box_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "cgal_common.hpp"

namespace coons_csg {

BoxGrid::BoxGrid(const std::vector<GridBox> &boxes, PairTest test, const void *ctx, unsigned threads)
    : test_(test), ctx_(ctx), n_(boxes.size())
{
    // Every pass below runs by chunks of boxes on the threads; what a pass
    // gathers (extremes, counts) is combined over the chunks in order, and
    // the entries are written where the serial loop would put them.
    const size_t nch = chunks(n_);
    const unsigned th = threads > 1 ? threads : 1;
    bx_.resize(n_);
    std::vector<std::array<double, 7>> ext(nch); // per chunk: org, top, emin
    parallel_for(th, nch, [&](size_t k) {
        std::array<double, 7> &x = ext[k];
        for (int c = 0; c < 3; c++) x[c] = HUGE_VAL, x[3 + c] = -HUGE_VAL;
        x[6] = HUGE_VAL;
        for (size_t i = k * kChunk, i1 = std::min(n_, i + kChunk); i < i1; i++) {
            const GridBox &b = boxes[i];
            BB &q = bx_[i];
            for (int c = 0; c < 3; c++) q.lo[c] = b.lo[c], q.hi[c] = b.hi[c];
            q.t = b.t;
            q.old = b.old;
            for (int c = 0; c < 3; c++) {
                x[c] = std::min(x[c], q.lo[c]);
                x[3 + c] = std::max(x[3 + c], q.hi[c]);
            }
            double e = extent(q);
            if (e > 0) x[6] = std::min(x[6], e);
        }
    });
    double emin = HUGE_VAL, span = 0, top[3];
    for (int c = 0; c < 3; c++) org_[c] = HUGE_VAL, top[c] = -HUGE_VAL;
    for (const std::array<double, 7> &x : ext) {
        for (int c = 0; c < 3; c++) {
            org_[c] = std::min(org_[c], x[c]);
            top[c] = std::max(top[c], x[3 + c]);
        }
        emin = std::min(emin, x[6]);
    }
    for (int c = 0; c < 3; c++) span = std::max(span, top[c] - org_[c]);
    ok_ = std::isfinite(span);
    if (!ok_) return; // extents beyond doubles: the caller uses the reference
    // the finest level fits the smallest box, with at most 2^20 cells
    // along an axis (keys pack 21 bits per axis)
    double h = std::max(0.5 * emin, span / 1048576.0);
    if (!(h > 0) || !std::isfinite(h)) h = 1.0;
    std::vector<int> top_level(nch, 0);
    parallel_for(th, nch, [&](size_t k) {
        for (size_t i = k * kChunk, i1 = std::min(n_, i + kChunk); i < i1; i++) {
            BB &q = bx_[i];
            double e = extent(q), hl = h;
            int L = 0;
            while (e > 2 * hl && L < 15) {
                hl *= 4;
                L++;
            }
            q.level = (unsigned char)L;
            top_level[k] = std::max(top_level[k], L);
        }
    });
    int nlev = 1;
    for (int L : top_level) nlev = std::max(nlev, L + 1);
    inv_.assign(nlev, 1.0 / h);
    for (int L = 1; L < nlev; L++) inv_[L] = 0.25 * inv_[L - 1];
    cells_.resize(nlev);
    // per chunk and level: the entries, then where the chunk's start
    std::vector<size_t> per(nch * (size_t)nlev, 0);
    parallel_for(th, nch, [&](size_t k) {
        for (size_t i = k * kChunk, i1 = std::min(n_, i + kChunk); i < i1; i++) {
            BB &q = bx_[i];
            uint32_t hi[3];
            range(q, q.level, q.cell, hi);
            per[k * nlev + q.level] +=
                (size_t)(hi[0] - q.cell[0] + 1) * (hi[1] - q.cell[1] + 1) * (hi[2] - q.cell[2] + 1);
        }
    });
    for (int L = 0; L < nlev; L++) {
        size_t sum = 0;
        for (size_t k = 0; k < nch; k++) {
            size_t c = per[k * nlev + L];
            per[k * nlev + L] = sum;
            sum += c;
        }
        cells_[L].resize(sum);
    }
    parallel_for(th, nch, [&](size_t k) {
        size_t *at = &per[k * nlev];
        for (size_t i = k * kChunk, i1 = std::min(n_, i + kChunk); i < i1; i++) {
            const BB &q = bx_[i];
            uint32_t hi[3];
            range(q, q.level, nullptr, hi);
            Entry *E = cells_[q.level].data();
            size_t &a = at[q.level];
            for (uint64_t z = q.cell[2]; z <= hi[2]; z++)
                for (uint64_t y = q.cell[1]; y <= hi[1]; y++)
                    for (uint64_t x = q.cell[0]; x <= hi[0]; x++) E[a++] = {pack21(x, y, z), (uint32_t)i};
        }
    });
    for (auto &E : cells_) {
        radix_sort(E, th);
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
// digits all keys share; small sets by std::sort. Each pass is stable and
// runs on the threads by contiguous parts (counts per part, each part's
// entries of a digit after the earlier parts'): the order the serial sort
// gives, for every thread count.
void BoxGrid::radix_sort(std::vector<Entry> &E, unsigned threads)
{
    auto by_key = [](const Entry &a, const Entry &b) { return a.key < b.key; };
    if (E.size() < 4096) {
        std::sort(E.begin(), E.end(), by_key);
        return;
    }
    const size_t D = 1u << 16;
    const size_t np = threads > 1 && E.size() >= 65536 ? threads : 1;
    const size_t n = E.size();
    std::vector<Entry> tmp(n);
    std::vector<size_t> cnt(np * D);
    for (int shift = 0; shift < 64; shift += 16) {
        parallel_for((unsigned)np, np, [&](size_t p) {
            size_t *c = &cnt[p * D];
            std::fill(c, c + D, 0);
            for (size_t i = n * p / np, i1 = n * (p + 1) / np; i < i1; i++) c[(E[i].key >> shift) & 0xFFFF]++;
        });
        size_t d0 = (E[0].key >> shift) & 0xFFFF, all = 0;
        for (size_t p = 0; p < np; p++) all += cnt[p * D + d0];
        if (all == n) continue;
        size_t sum = 0;
        for (size_t d = 0; d < D; d++)
            for (size_t p = 0; p < np; p++) {
                size_t k = cnt[p * D + d];
                cnt[p * D + d] = sum;
                sum += k;
            }
        parallel_for((unsigned)np, np, [&](size_t p) {
            size_t *c = &cnt[p * D];
            for (size_t i = n * p / np, i1 = n * (p + 1) / np; i < i1; i++)
                tmp[c[(E[i].key >> shift) & 0xFFFF]++] = E[i];
        });
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
