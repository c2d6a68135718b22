// SPDX-License-Identifier: GPL-3.0-or-later
//
// Hierarchical uniform grids of triangle boxes (box_grid.cpp), free of CGAL:
// the candidate pairs of the self-intersection check
// (count_self_intersections in cgal_fast.cpp), each handed once to the
// caller's exact pair test.
#ifndef COONS_BOX_GRID_HPP
#define COONS_BOX_GRID_HPP

#include <cstddef>
#include <cstdint>
#include <vector>

namespace coons_csg {

// The closed box of triangle t; `old`: a kept (input) triangle, whose pairs
// with other kept ones are not tested.
struct GridBox {
    double lo[3], hi[3];
    uint32_t t;
    bool old;
};

// Do triangles s and t intersect (other than as their shared vertices
// allow)? ctx: the caller's data.
typedef bool (*PairTest)(const void *ctx, uint32_t s, uint32_t t);

// The pairs of boxes that meet (closed boxes, as CGAL's box_intersection_d),
// among the boxes that are not old and between them and the old ones, each
// tested once with the pair test: hierarchical uniform grids. Level L has
// cells of side h 4^L, h half the smallest box; a box lives at the first
// level where it is at most two cells long, in the cells it overlaps (at
// most 3 per axis), so that a cell holds boxes of about its own size however
// the sizes vary (a shell's fine lattice at a pole next to a flat face's
// large triangles). Two boxes of one level meet in the cells they share and
// are tested in one of them, the home cell: the one holding the low corner
// of their common box. A box looks for the boxes of the coarser levels in
// the cells of those levels that it overlaps, again in the home cell only.
// Shells sampled on lattices have few boxes per cell: on the union
// benchmark's shells this takes 0.15 s where box_intersection_d's segment
// tree took 0.33 s (with the projection tests of pair_intersects), with the
// same pairs.
class BoxGrid {
  public:
    // threads: how many build the grid (the same grid for every count).
    BoxGrid(const std::vector<GridBox> &boxes, PairTest test, const void *ctx, unsigned threads = 1);

    // False when the boxes' extents are beyond doubles (the caller then
    // uses box_intersection_d).
    bool ok() const { return ok_; }

    // Tasks for parallel_for: chunks of cells of each level, then chunks of
    // boxes (their look at the coarser levels).
    size_t tasks() const { return cell_chunks() + box_chunks(); }
    // The number of intersecting pairs that task `task` finds.
    size_t run(size_t task) const;

  private:
    // A box: its corners, the cell of its low corner at its own level, the
    // triangle, and whether it is a kept (old) one.
    struct BB {
        double lo[3], hi[3];
        uint32_t cell[3];
        uint32_t t;
        unsigned char level;
        bool old;
    };
    struct Entry {
        uint64_t key;
        uint32_t box;
    };
    static constexpr size_t kChunk = 4096;
    PairTest test_;
    const void *ctx_;
    size_t n_;
    bool ok_ = true;
    double org_[3];
    std::vector<BB> bx_;
    std::vector<double> inv_; // per level: 1 / cell side
    std::vector<std::vector<Entry>> cells_;
    std::vector<std::vector<size_t>> groups_; // per level: first entry of each cell, then the end
    std::vector<int> used_;                   // the levels that hold boxes

    static double extent(const BB &q);
    static size_t chunks(size_t n) { return (n + kChunk - 1) / kChunk; }
    size_t cell_chunks() const;
    size_t box_chunks() const { return used_.size() > 1 ? chunks(n_) : 0; }
    uint32_t index(double x, int c, int L) const;
    void range(const BB &q, int L, uint32_t *lo, uint32_t hi[3]) const;
    static void radix_sort(std::vector<Entry> &E, unsigned threads);
    size_t test(const BB &a, const BB &b, const uint32_t *acell, uint64_t key) const;
};

} // namespace coons_csg

#endif
