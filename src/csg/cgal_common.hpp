// SPDX-License-Identifier: GPL-3.0-or-later
//
// What the two CGAL translation units share: cgal_solid.cpp (the exact
// path, compiled with CGAL's assertions, which turn CGAL 5.5's crashes on
// some coplanar inputs of autorefinement into exceptions) and cgal_fast.cpp
// (the fast path, compiled without them: its results are checked exactly
// afterwards anyway). No CGAL type crosses this interface, so the two units
// instantiate no template of their own types twice.
#ifndef COONS_CGAL_COMMON_HPP
#define COONS_CGAL_COMMON_HPP

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <unordered_set>
#include <vector>

extern "C" {
#include "coons_internal.h"
}

namespace coons_csg {

struct Failure : std::runtime_error {
    coons_status code;
    Failure(coons_status c, const std::string &m) : std::runtime_error(m), code(c) {}
};

struct Part {
    std::string name;
    size_t tri_first, tri_count, vert_first, vert_count;
    double lo[3], hi[3];
};

struct Progress {
    const coons_csg_options *o;
    void operator()(const char *stage, double f) const
    {
        if (o && o->progress) o->progress(o->userdata, stage, f < 0 ? 0 : (f > 1 ? 1 : f));
    }
};

// Output triangles of one group or part, in double coordinates.
struct Soup {
    std::vector<double> xyz;
    std::vector<uint32_t> tri;
};

// N doubles compared by their bytes (-0 and 0 differ), as a hash key.
template <int N> struct DoublesKey {
    double v[N];
    bool operator==(const DoublesKey &o) const { return std::memcmp(v, o.v, sizeof v) == 0; }
};
struct DoublesKeyHash {
    template <int N> size_t operator()(const DoublesKey<N> &k) const
    {
        uint64_t h = 0x9e3779b97f4a7c15ull;
        for (int i = 0; i < N; i++) {
            uint64_t w;
            std::memcpy(&w, &k.v[i], sizeof w);
            h = (h ^ w) * 0xff51afd7ed558ccdull;
            h ^= h >> 32;
        }
        return (size_t)h;
    }
};
// A point by its coordinates.
typedef DoublesKey<3> PointKey;
// A triangle by its three points, rotated to start at the smallest (by
// bytes): the same oriented triangle whatever its vertex indices.
typedef DoublesKey<9> TriKey;
TriKey tri_key(const double *a, const double *b, const double *c);
// The input triangles of a group: a result triangle found here was taken
// unchanged from an input shell (the local final check skips pairs of them).
typedef std::unordered_set<TriKey, DoublesKeyHash> InputTriangles;
void input_triangles(const double *xyz, const uint32_t *tri, const std::vector<Part> &parts,
                     const std::vector<size_t> &ids, InputTriangles &out);

// Runs f(i) for i in [0, n) on up to `threads` threads (the caller's among
// them); errors[i] receives what f(i) threw. Falls back to the calling
// thread alone when threads cannot be started.
template <class F>
void parallel_for(unsigned threads, size_t n, F f, std::vector<std::exception_ptr> &errors)
{
    errors.assign(n, nullptr);
    std::atomic<size_t> next(0);
    auto work = [&]() {
        for (size_t i; (i = next.fetch_add(1)) < n;) {
            try {
                f(i);
            } catch (...) {
                errors[i] = std::current_exception();
            }
        }
    };
    std::vector<std::thread> pool;
    unsigned extra = threads > 1 ? (unsigned)std::min<size_t>(threads, n) - 1 : 0;
    for (unsigned t = 0; t < extra; t++) {
        try {
            pool.emplace_back(work);
        } catch (const std::system_error &) {
            break;
        }
    }
    work();
    for (std::thread &t : pool) t.join();
}
// parallel_for, then the first error (by index) rethrown.
template <class F> void parallel_for(unsigned threads, size_t n, F f)
{
    std::vector<std::exception_ptr> errors;
    parallel_for(threads, n, f, errors);
    for (const std::exception_ptr &e : errors)
        if (e) std::rethrow_exception(e);
}

// Pairs of triangles of an indexed soup that intersect other than along
// shared edges or at shared vertices (exact predicates on the doubles);
// zero-area triangles are counted in *degenerate (may be NULL), not tested.
// With `old` (may be NULL), the local check: pairs of two triangles found
// in `old` are not tested, nor old triangles for degeneracy. The count does
// not depend on `threads`. `reference`: the candidate pairs by CGAL's
// box_intersection_d instead of the grids (the same pairs; for the tests).
size_t count_self_intersections(const double *xyz, size_t nv, const uint32_t *tri, size_t nt,
                                size_t *degenerate, unsigned threads,
                                const InputTriangles *old = nullptr, bool reference = false);

// Do parts a and b need Boolean work together: do boxes of their triangles
// meet, or does one lie inside the other (winding number of a vertex)?
bool parts_interact(const double *xyz, const uint32_t *tri, const Part &a, const Part &b);

// Three numbers of up to 21 bits in one key, x in the low bits: the cells
// of the box grids (box_grid.cpp); the hash of a vertex triple (weld.cpp).
inline uint64_t pack21(uint64_t x, uint64_t y, uint64_t z) { return x | y << 21 | z << 42; }
// An edge of vertex indices as one key: directed (a, b), or undirected.
inline uint64_t directed_edge_key(uint32_t a, uint32_t b) { return (uint64_t)a << 32 | b; }
inline uint64_t edge_key(uint32_t a, uint32_t b)
{
    return a < b ? directed_edge_key(a, b) : directed_edge_key(b, a);
}

// The order of canonical_order(): by coordinates, ties (-0 and 0) by bytes.
inline bool point_less(const double *p, const double *q)
{
    for (int c = 0; c < 3; c++) {
        if (p[c] < q[c]) return true;
        if (q[c] < p[c]) return false;
    }
    return std::memcmp(p, q, 3 * sizeof(double)) < 0;
}

// A Boolean's result finished (weld.cpp): canonical_order(), fresh_vertices()
// merged where close (merge_close), fix_slivers(); xyz, parts, ids: the
// input shells.
void weld(Soup &s, const double *xyz, const std::vector<Part> &parts, const std::vector<size_t> &ids,
          coons_csg_report &rep);
// Renumbers s canonically (canonical_order.cpp): vertices sorted by
// coordinates, each triangle rotated to start at its lowest vertex,
// triangles sorted. CGAL's output order depends on where its allocations
// land (handles compared by address), so results are made independent of
// the heap, and of threads.
void canonical_order(Soup &s);
// Vertices of s closer than 1e-11 of its size merged (weld.cpp); with
// `fresh`, only the flagged ones move.
void merge_close(Soup &s, coons_csg_report &rep, const std::vector<char> *fresh = nullptr);
// Per vertex of s (in canonical_order()): 1 unless it is bitwise a vertex of
// one of the parts `ids` (coordinates xyz), which corefinement keeps
// (input_identity.cpp).
std::vector<char> fresh_vertices(const Soup &s, const double *xyz, const std::vector<Part> &parts,
                                 const std::vector<size_t> &ids);
// Slivers that rounding flattened split away (slivers.cpp).
void fix_slivers(Soup &s, coons_csg_report &rep);
// Are p, q, r collinear? Exact (CGAL's predicate; cgal_fast.cpp).
bool exact_collinear(const double *p, const double *q, const double *r);

// The verified fast path (cgal_fast.cpp); true with s filled, or false.
bool fast_union(const double *sxyz, const uint32_t *tri, const std::vector<Part> &parts,
                const std::vector<size_t> &ids, coons_csg_report &rep, Progress prog, double p0,
                double p1, unsigned threads, Soup &s);

} // namespace coons_csg

#endif
