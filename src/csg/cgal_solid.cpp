// SPDX-License-Identifier: GPL-3.0-or-later
//
// Repair and union of body shells with CGAL (Surface_mesh, Polygon Mesh
// Processing, AABB tree; Debian's CGAL 5.5). One of the two translation
// units that include CGAL (the other, cgal_fast.cpp, holds the fast path,
// compiled without CGAL's assertions; cgal_common.hpp is their interface,
// free of CGAL types); it costs ~40 s and 1.6 GB to compile. Every extern "C"
// entry runs through coons::guard (cxx_guard.hpp); describe_failure() is the
// part of the boundary that knows CGAL's exception.
//
// The solid of a shell is where its winding number is non-zero (model
// format, "Solids and outputs"); the solid of a model is the union of its
// bodies' solids. Parts meet when boxes of their triangles meet or one lies
// inside the other (a winding number); parts that meet nothing need no
// Boolean. Groups of parts that meet are independent: with
// coons_csg_options.threads they run at once, and each result is put in a
// canonical order, so that it does not depend on threads or on the heap.
// Per group (GroupSolidifier):
//  0. a part that meets nothing and does not cross itself (exact check of
//     the double mesh, count_self_intersections) passes through unchanged;
//     the others are first snapped to a power-of-two grid near 1e-12 of the
//     input's size, so that sampling noise cannot create features narrower
//     than doubles;
//  1. parts that do not cross themselves are united by chained
//     corefinement on the inexact-constructions kernel (fast_union: of the
//     triangles near the other shell, else of the whole shells); the
//     result is kept only if the exact check of it finds nothing (a local
//     check: only pairs with a triangle that is not an input triangle
//     unchanged are tested; the inputs were checked, and corefinement
//     splits every input pair that crosses);
//  2. otherwise each part becomes an exact (Epeck) closed 2-manifold: as it
//     is, or repaired by the soup pass (Solidifier) when it crosses itself,
//     and the parts are united by chained exact corefinement;
//  3. the soup pass, also the fallback when corefinement refuses a group or
//     a repaired part is pinched: the shells go into one Epeck mesh without
//     reorienting anything (exactly degenerate triangles dropped);
//     PMP::experimental::autorefine splits triangles along every mutual
//     intersection; the faces are grouped into patches bounded by the new
//     edges, over which winding numbers are constant; one ray per patch,
//     from a face centroid into its front side, counts signed crossings per
//     body with exact predicates (retried when it grazes an edge), faces at
//     the ray's origin being coincident ones; a patch is kept when exactly
//     one of its sides lies in a solid, facing the other side;
//  4. an exact result is rounded to doubles once (round_soup), vertices
//     closer than 1e-11 of the size are merged and triangles the rounding
//     flattened are removed by an edge split, and the rounded mesh is
//     checked again with exact predicates (the same local check): a
//     crossing left is an error.
// Trials with chained corefinement unions (inexact kernel) left
// self-intersections, and exact results rounded later reintroduced some
// (BUILD-NOTES): the final checks make that an error instead of a silent
// result, and the snap and merge of steps 0 and 4 made it rare.

// CGAL checks its preconditions only without NDEBUG; with them, inputs it
// cannot handle throw instead of crashing (autorefinement in 5.5 segfaults
// on some coplanar configurations otherwise). Measured cost: see README.
#undef NDEBUG
// CGAL's warnings would print to stderr; the library never prints.
#define CGAL_NO_WARNINGS
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "cgal_common.hpp"
#include "cxx_guard.hpp"

extern "C" {
#include "coons_internal.h"
#include "coons_test_hooks.h"
#include "csg_records.h"
}

namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

using coons_csg::Failure;
using coons_csg::InputTriangles;
using coons_csg::Part;
using coons_csg::Progress;
using coons_csg::Soup;
using coons_csg::count_self_intersections;
using coons_csg::parallel_for;

typedef CGAL::Exact_predicates_exact_constructions_kernel EK;
typedef CGAL::Exact_predicates_inexact_constructions_kernel IK;
typedef EK::Point_3 EPoint;
typedef CGAL::Surface_mesh<EPoint> EMesh;
typedef CGAL::Surface_mesh<IK::Point_3> IMesh;
typedef EMesh::Face_index EFace;
typedef EMesh::Vertex_index EVert;

// Gives faces that autorefinement splits off the body of their parent.
struct BodyVisitor : PMP::Corefinement::Default_visitor<EMesh> {
    EMesh::Property_map<EFace, int> *body;
    int *parent;
    BodyVisitor(EMesh::Property_map<EFace, int> *b, int *p) : body(b), parent(p) {}
    void before_subface_creations(EFace f, EMesh &) { *parent = (*body)[f]; }
    void after_subface_created(EFace f, EMesh &) { (*body)[f] = *parent; }
};

struct LessXYZ {
    bool operator()(const EPoint &a, const EPoint &b) const
    {
        return CGAL::compare_xyz(a, b) == CGAL::SMALLER;
    }
};

struct ExactSoup {
    std::vector<EPoint> pts;
    std::vector<std::array<uint32_t, 3>> tri;
};

// A closed 2-manifold exact mesh from an indexed soup, or false.
bool exact_mesh(const ExactSoup &s, EMesh &m)
{
    m.clear();
    std::vector<EVert> vs;
    vs.reserve(s.pts.size());
    for (const EPoint &p : s.pts) vs.push_back(m.add_vertex(p));
    for (const auto &t : s.tri)
        if (CGAL::collinear(s.pts[t[0]], s.pts[t[1]], s.pts[t[2]]) ||
            m.add_face(vs[t[0]], vs[t[1]], vs[t[2]]) == EMesh::null_face())
            return false;
    for (EVert v : m.vertices())
        if (m.is_isolated(v) || m.is_border(v)) return false;
    return CGAL::is_closed(m);
}

// The exact pass over the parts `ids` of the input (see the file comment).
class Solidifier {
  public:
    Solidifier(const double *xyz, const uint32_t *tri, const std::vector<Part> &parts,
               const std::vector<size_t> &ids, coons_csg_report &rep, Progress prog,
               double p0, double p1)
        : xyz_(xyz), tri_(tri), parts_(parts), ids_(ids), rep_(rep), prog_(prog), p0_(p0),
          p1_(p1)
    {
    }

    bool run(EMesh &out, ExactSoup &soup)
    {
        build();
        prog_("autorefine", p0_ + 0.1 * (p1_ - p0_));
        auto ecm = mesh_.add_property_map<EMesh::Edge_index, bool>("e:constrained", false).first;
        int parent = -1;
        PMP::experimental::autorefine(mesh_, CGAL::parameters::edge_is_constrained_map(ecm)
                                                 .visitor(BodyVisitor(&body_, &parent)));
        prog_("classify", p0_ + 0.6 * (p1_ - p0_));
        make_patches(ecm);
        classify();
        prog_("assemble", p0_ + 0.9 * (p1_ - p0_));
        return assemble(out, soup);
    }

  private:
    const double *xyz_;
    const uint32_t *tri_;
    const std::vector<Part> &parts_;
    const std::vector<size_t> &ids_;
    coons_csg_report &rep_;
    Progress prog_;
    double p0_, p1_;
    EMesh mesh_;
    EMesh::Property_map<EFace, int> body_;    // index into ids_
    EMesh::Property_map<EFace, int> patch_;   // patch id
    std::vector<EFace> rep_face_;             // a face per patch
    std::vector<std::vector<EFace>> members_; // faces per patch
    std::vector<signed char> verdict_;        // per patch: 0 drop, +1 keep, -1 keep flipped
    std::vector<int> twin_of_;                // lowest coincident patch id, or -1
    EPoint lo_, hi_;

    void build()
    {
        body_ = mesh_.add_property_map<EFace, int>("f:body", -1).first;
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (size_t k = 0; k < ids_.size(); k++) {
            const Part &p = parts_[ids_[k]];
            size_t base = mesh_.number_of_vertices();
            for (size_t i = 0; i < p.vert_count; i++) {
                const double *q = xyz_ + 3 * (p.vert_first + i);
                mesh_.add_vertex(EPoint(q[0], q[1], q[2]));
            }
            std::vector<uint32_t> local(3 * p.tri_count);
            for (size_t t = 0; t < 3 * p.tri_count; t++)
                local[t] = tri_[3 * p.tri_first + t] - (uint32_t)p.vert_first;
            add_faces(base, p, local, (int)k);
            for (int c = 0; c < 3; c++) {
                lo[c] = std::min(lo[c], p.lo[c]);
                hi[c] = std::max(hi[c], p.hi[c]);
            }
        }
        double pad = 0.0;
        for (int c = 0; c < 3; c++) pad = std::max(pad, hi[c] - lo[c]);
        pad = pad * 0.5 + 1.0;
        lo_ = EPoint(lo[0] - pad, lo[1] - pad, lo[2] - pad);
        hi_ = EPoint(hi[0] + pad, hi[1] + pad, hi[2] + pad);
    }

    void add_faces(size_t base, const Part &p, const std::vector<uint32_t> &local, int body)
    {
        for (size_t t = 0; t < p.tri_count; t++) {
            uint32_t a = local[3 * t], b = local[3 * t + 1], c = local[3 * t + 2];
            EVert va(base + a), vb(base + b), vc(base + c);
            if (a == b || b == c || a == c ||
                CGAL::collinear(mesh_.point(va), mesh_.point(vb), mesh_.point(vc))) {
                rep_.degenerate_dropped++;
                continue;
            }
            EFace f = mesh_.add_face(va, vb, vc);
            if (f == EMesh::null_face()) {
                EVert x = mesh_.add_vertex(mesh_.point(va)), y = mesh_.add_vertex(mesh_.point(vb)),
                      z = mesh_.add_vertex(mesh_.point(vc));
                f = mesh_.add_face(x, y, z);
            }
            body_[f] = body;
        }
    }

    void make_patches(EMesh::Property_map<EMesh::Edge_index, bool> ecm)
    {
        patch_ = mesh_.add_property_map<EFace, int>("f:patch", -1).first;
        std::vector<EFace> stack;
        for (EFace f : mesh_.faces()) {
            if (patch_[f] >= 0) continue;
            int id = (int)members_.size();
            members_.emplace_back();
            stack.push_back(f);
            patch_[f] = id;
            while (!stack.empty()) {
                EFace g = stack.back();
                stack.pop_back();
                members_[id].push_back(g);
                for (auto h : CGAL::halfedges_around_face(mesh_.halfedge(g), mesh_)) {
                    if (ecm[mesh_.edge(h)]) continue;
                    auto o = mesh_.opposite(h);
                    if (mesh_.is_border(o)) continue;
                    EFace n = mesh_.face(o);
                    if (patch_[n] >= 0) continue;
                    patch_[n] = id;
                    stack.push_back(n);
                }
            }
            for (EFace g : members_[id])
                if (body_[g] < 0 || body_[g] != body_[members_[id][0]])
                    throw Failure(COONS_E_INTERNAL, "a refined patch has no single body");
        }
        rep_.patches += members_.size();
    }

    void tri_points(EFace f, EPoint &a, EPoint &b, EPoint &c) const
    {
        auto h = mesh_.halfedge(f);
        a = mesh_.point(mesh_.target(h));
        h = mesh_.next(h);
        b = mesh_.point(mesh_.target(h));
        h = mesh_.next(h);
        c = mesh_.point(mesh_.target(h));
    }

    double approx_area(EFace f) const
    {
        EPoint a, b, c;
        tri_points(f, a, b, c);
        IK::Point_3 x(CGAL::to_double(a.x()), CGAL::to_double(a.y()), CGAL::to_double(a.z()));
        IK::Point_3 y(CGAL::to_double(b.x()), CGAL::to_double(b.y()), CGAL::to_double(b.z()));
        IK::Point_3 z(CGAL::to_double(c.x()), CGAL::to_double(c.y()), CGAL::to_double(c.z()));
        return std::sqrt(CGAL::to_double(CGAL::squared_area(x, y, z)));
    }

    // Strictly inside triangle abc (c0 known to be in its plane)?
    // 1: inside, 0: outside, -1: on its boundary.
    static int in_triangle(const EPoint &a, const EPoint &b, const EPoint &c, const EK::Vector_3 &n,
                           const EPoint &p)
    {
        CGAL::Orientation o1 = CGAL::orientation(a, b, a + n, p);
        CGAL::Orientation o2 = CGAL::orientation(b, c, b + n, p);
        CGAL::Orientation o3 = CGAL::orientation(c, a, c + n, p);
        CGAL::Orientation r1 = CGAL::orientation(a, b, a + n, c);
        if (o1 == CGAL::COPLANAR || o2 == CGAL::COPLANAR || o3 == CGAL::COPLANAR) {
            bool out = (o1 != CGAL::COPLANAR && o1 != r1) || (o2 != CGAL::COPLANAR && o2 != r1) ||
                       (o3 != CGAL::COPLANAR && o3 != r1);
            return out ? 0 : -1;
        }
        return (o1 == r1 && o2 == r1 && o3 == r1) ? 1 : 0;
    }

    typedef CGAL::AABB_face_graph_triangle_primitive<EMesh> Prim;
    typedef CGAL::AABB_traits<EK, Prim> Traits;
    typedef CGAL::AABB_tree<Traits> Tree;

    // Casts one ray from face f of patch pid. Returns false when the ray
    // was not generic (grazes an edge or vertex, or the origin lies on an
    // edge of a coincident face): the caller tries again.
    bool cast(const Tree &tree, EFace f, int pid, unsigned &seed, std::vector<int> &wf,
              std::vector<int> &jump, int &twin)
    {
        EPoint a, b, c;
        tri_points(f, a, b, c);
        EK::Vector_3 n = CGAL::cross_product(b - a, c - a);
        EPoint o = CGAL::centroid(a, b, c);
        // Pseudo-random direction into the front side.
        double nd[3] = {CGAL::to_double(n.x()), CGAL::to_double(n.y()), CGAL::to_double(n.z())};
        double len = std::sqrt(nd[0] * nd[0] + nd[1] * nd[1] + nd[2] * nd[2]);
        if (!(len > 0)) return false;
        double dd[3];
        for (int k = 0; k < 3; k++) {
            seed = seed * 1103515245u + 12345u;
            dd[k] = nd[k] / len + 0.7 * (((seed >> 8) & 0xffff) / 65535.0 - 0.5);
        }
        EK::Vector_3 d(dd[0], dd[1], dd[2]);
        if (CGAL::sign(d * n) != CGAL::POSITIVE) return false;
        // Far end outside the padded box of everything.
        double span = CGAL::to_double(hi_.x() - lo_.x()) + CGAL::to_double(hi_.y() - lo_.y()) +
                      CGAL::to_double(hi_.z() - lo_.z());
        double dl = std::sqrt(dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2]);
        EPoint far = o + d * (4.0 * span / dl);
        EK::Segment_3 seg(o, far);
        std::vector<Tree::Primitive_id> hits;
        tree.all_intersected_primitives(seg, std::back_inserter(hits));
        std::fill(wf.begin(), wf.end(), 0);
        std::fill(jump.begin(), jump.end(), 0);
        jump[body_[f]] += 1;
        twin = -1;
        for (EFace g : hits) {
            if (g == f) continue;
            EPoint A, B, C;
            tri_points(g, A, B, C);
            CGAL::Orientation o1 = CGAL::orientation(A, B, C, o);
            CGAL::Orientation o2 = CGAL::orientation(A, B, C, far);
            EK::Vector_3 ng = CGAL::cross_product(B - A, C - A);
            if (o1 == CGAL::COPLANAR) {
                if (o2 == CGAL::COPLANAR) return false;
                int in = in_triangle(A, B, C, ng, o);
                if (in < 0) return false;
                if (in == 0) continue;
                // Coincident face: part of the jump across this patch.
                jump[body_[g]] += CGAL::sign(ng * n) == CGAL::POSITIVE ? 1 : -1;
                int tp = patch_[g];
                if (tp != pid && (twin < 0 || tp < twin)) twin = tp;
                continue;
            }
            if (o2 == CGAL::COPLANAR || o1 == o2) continue;
            CGAL::Orientation s1 = CGAL::orientation(o, far, A, B);
            CGAL::Orientation s2 = CGAL::orientation(o, far, B, C);
            CGAL::Orientation s3 = CGAL::orientation(o, far, C, A);
            if (s1 == CGAL::COPLANAR || s2 == CGAL::COPLANAR || s3 == CGAL::COPLANAR) {
                // Grazes an edge or vertex (or misses on the line): only
                // a miss when the others disagree strictly.
                bool miss = (s1 != CGAL::COPLANAR && s2 != CGAL::COPLANAR && s1 != s2) ||
                            (s2 != CGAL::COPLANAR && s3 != CGAL::COPLANAR && s2 != s3) ||
                            (s1 != CGAL::COPLANAR && s3 != CGAL::COPLANAR && s1 != s3);
                if (miss) continue;
                return false;
            }
            if (!(s1 == s2 && s2 == s3)) continue;
            wf[body_[g]] += CGAL::sign(d * ng) == CGAL::POSITIVE ? 1 : -1;
        }
        return true;
    }

    void classify()
    {
        Tree tree(faces(mesh_).first, faces(mesh_).second, mesh_);
        tree.accelerate_distance_queries();
        size_t np = members_.size();
        verdict_.assign(np, 0);
        twin_of_.assign(np, -1);
        std::vector<int> wf(ids_.size()), jump(ids_.size());
        unsigned seed = 12345u;
        for (size_t pid = 0; pid < np; pid++) {
            // Largest faces first: their centroids are far from other edges.
            std::vector<EFace> cand = members_[pid];
            std::partial_sort(cand.begin(), cand.begin() + std::min<size_t>(cand.size(), 4),
                              cand.end(), [&](EFace x, EFace y) { return approx_area(x) > approx_area(y); });
            bool done = false;
            int twin = -1;
            for (size_t ci = 0; ci < std::min<size_t>(cand.size(), 4) && !done; ci++)
                for (int attempt = 0; attempt < 16 && !done; attempt++)
                    done = cast(tree, cand[ci], (int)pid, seed, wf, jump, twin);
            if (!done)
                throw Failure(COONS_E_CSG, "a surface patch could not be classified: every ray "
                                           "from it grazed an edge");
            bool front = false, back = false;
            for (size_t k = 0; k < wf.size(); k++) {
                if (wf[k] != 0) front = true;
                if (wf[k] + jump[k] != 0) back = true;
            }
            if (front != back) verdict_[pid] = back ? 1 : -1;
            twin_of_[pid] = twin;
        }
        // Coincident kept patches: keep the one with the lowest id.
        for (size_t pid = 0; pid < np; pid++) {
            int t = twin_of_[pid];
            if (verdict_[pid] && t >= 0 && (size_t)t < pid && verdict_[t]) verdict_[pid] = 0;
        }
        for (size_t pid = 0; pid < np; pid++)
            if (verdict_[pid]) rep_.patches_kept++;
    }

    // Kept faces as an exact mesh: coincident vertices of different sheets
    // become one vertex (exact comparison). Returns false when the result
    // is not a 2-manifold surface (solids touching along a curve or at a
    // point); `soup` always receives the kept triangles.
    bool assemble(EMesh &out, ExactSoup &soup)
    {
        std::map<EPoint, uint32_t, LessXYZ> index;
        std::vector<uint32_t> vmap(mesh_.num_vertices(), UINT32_MAX); // index range
        auto vid = [&](EVert v) -> uint32_t {
            if (vmap[v] != UINT32_MAX) return vmap[v];
            const EPoint &p = mesh_.point(v);
            auto it = index.find(p);
            if (it != index.end()) return vmap[v] = it->second;
            uint32_t id = (uint32_t)soup.pts.size();
            soup.pts.push_back(p);
            index.emplace(p, id);
            return vmap[v] = id;
        };
        for (size_t pid = 0; pid < members_.size(); pid++) {
            if (!verdict_[pid]) continue;
            for (EFace f : members_[pid]) {
                std::array<uint32_t, 3> t;
                int i = 0;
                for (EVert v : CGAL::vertices_around_face(mesh_.halfedge(f), mesh_)) t[i++] = vid(v);
                if (verdict_[pid] < 0) std::swap(t[1], t[2]);
                soup.tri.push_back(t);
            }
        }
        return exact_mesh(soup, out);
    }
};

// The parts of m, with their boxes in the coordinates xyz (m's, scaled).
void collect_parts(const coons_mesh *m, const double *xyz, std::vector<Part> &parts)
{
    size_t np = coons_mesh_part_count(m);
    for (size_t i = 0; i < np; i++) {
        Part p;
        p.name = coons_mesh_part_name(m, i);
        coons_mesh_part_range(m, i, &p.tri_first, &p.tri_count, &p.vert_first, &p.vert_count);
        bbox_empty(p.lo, p.hi);
        for (size_t v = 0; v < p.vert_count; v++) bbox_add(p.lo, p.hi, xyz + 3 * (p.vert_first + v));
        parts.push_back(p);
    }
}


// "'a', 'b', ..." (the first 8 names of the parts ids) into buf, cut to
// its size; allocates nothing (it runs in the guard's catch path).
void names_into(char *buf, size_t size, const std::vector<Part> &parts,
                const std::vector<size_t> &ids) noexcept
{
    size_t len = 0;
    buf[0] = '\0';
    for (size_t k = 0; k <= ids.size() && k <= 8 && len + 1 < size; k++) {
        int w;
        if (k == ids.size()) break;
        if (k == 8)
            w = std::snprintf(buf + len, size - len, ", ...");
        else
            w = std::snprintf(buf + len, size - len, "%s'%s'", k ? ", " : "",
                              parts[ids[k]].name.c_str());
        if (w < 0) break;
        len += (size_t)w;
    }
}

void edge_stats(const Soup &s, coons_csg_report &rep)
{
    // Undirected edges sorted: runs of one are border edges, of more than
    // two non-manifold ones.
    std::vector<uint64_t> e;
    e.reserve(s.tri.size());
    for (size_t t = 0; t < s.tri.size() / 3; t++)
        for (int k = 0; k < 3; k++) e.push_back(coons_csg::edge_key(s.tri[3 * t + k], s.tri[3 * t + (k + 1) % 3]));
    std::sort(e.begin(), e.end());
    size_t border = 0, nonman = 0;
    for (size_t i = 0; i < e.size();) {
        size_t j = i;
        while (j < e.size() && e[j] == e[i]) j++;
        if (j - i == 1) border++;
        if (j - i > 2) nonman++;
        i = j;
    }
    rep.closed = border == 0;
    rep.nonmanifold_edges += nonman;
}

void soup_of(const EMesh &m, ExactSoup &e)
{
    e.pts.clear();
    e.tri.clear();
    // Indexed by vertex index: num_vertices() is their range, removed ones
    // included (an in-place corefinement leaves some); number_of_vertices()
    // counts only the live ones and was too short (heap overflow).
    std::vector<uint32_t> id(m.num_vertices(), UINT32_MAX);
    for (EVert v : m.vertices()) {
        id[v] = (uint32_t)e.pts.size();
        e.pts.push_back(m.point(v));
    }
    for (EFace f : m.faces()) {
        std::array<uint32_t, 3> t;
        int i = 0;
        for (EVert v : CGAL::vertices_around_face(m.halfedge(f), m)) t[i++] = id[v];
        e.tri.push_back(t);
    }
}

// The one rounding of an exact result to doubles; vertices that round to
// the same point become one, triangles that collapse are dropped.
// `sxyz`, `parts`, `ids`: the group's input shells; only the rounded
// vertices that are not bitwise one of their vertices (those the exact
// Booleans made) move when close vertices are welded.
void round_soup(const ExactSoup &e, Soup &out, coons_csg_report &rep, const double *sxyz,
                const std::vector<Part> &parts, const std::vector<size_t> &ids)
{
    std::unordered_map<coons_csg::PointKey, uint32_t, coons_csg::DoublesKeyHash> index;
    std::vector<uint32_t> id(e.pts.size());
    for (size_t i = 0; i < e.pts.size(); i++) {
        const EPoint &p = e.pts[i];
        coons_csg::PointKey k{{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
        for (double &x : k.v)
            if (x == 0.0) x = 0.0; // -0 and +0 are one vertex
        auto it = index.find(k);
        if (it != index.end()) {
            rep.rounding_merged++;
            id[i] = it->second;
            continue;
        }
        if (out.xyz.size() / 3 >= UINT32_MAX) throw Failure(COONS_E_LIMIT, "too many vertices");
        id[i] = (uint32_t)(out.xyz.size() / 3);
        out.xyz.insert(out.xyz.end(), k.v, k.v + 3);
        index.emplace(k, id[i]);
    }
    for (const auto &t : e.tri) {
        uint32_t a = id[t[0]], b = id[t[1]], c = id[t[2]];
        if (a == b || b == c || a == c) continue;
        out.tri.insert(out.tri.end(), {a, b, c});
    }
    coons_csg::weld(out, sxyz, parts, ids, rep);
}

// The triangles of part p, with vertex indices local to the part.
std::vector<uint32_t> local_triangles(const uint32_t *tri, const Part &p)
{
    std::vector<uint32_t> local(3 * p.tri_count);
    for (size_t t = 0; t < local.size(); t++)
        local[t] = tri[3 * p.tri_first + t] - (uint32_t)p.vert_first;
    return local;
}

// One group of parts whose boxes meet (run() returns true when the result
// was passed through unchanged: no rounding, no check needed):
//  - a part that meets nothing and does not cross itself passes through;
//  - otherwise each part becomes an exact closed 2-manifold solid (as it
//    is, or repaired by the soup pass), and the solids are united by
//    chained corefinement on the exact kernel, rounded once at the end;
//  - a repaired part that is not 2-manifold (a pinch) cannot enter a
//    corefinement: then the whole group goes through the soup pass at once.
class GroupSolidifier {
  public:
    GroupSolidifier(const double *xyz, const double *sxyz, const uint32_t *tri,
                    const std::vector<Part> &parts, const std::vector<size_t> &ids,
                    const coons_csg_options &o, coons_csg_report &rep, Progress prog, double p0,
                    double p1, unsigned threads)
        : xyz_(xyz), sxyz_(sxyz), tri_(tri), parts_(parts), ids_(ids), o_(o), rep_(rep),
          prog_(prog), p0_(p0), p1_(p1), threads_(threads), solids_(ids.size()),
          crossing_(ids.size())
    {
    }

    bool run(Soup &s)
    {
        bool clean = count_crossings();
        if (clean && ids_.size() > 1 &&
            coons_csg::fast_union(sxyz_, tri_, parts_, ids_, rep_, prog_, p0_, p1_, threads_, s))
            return true;
        ExactSoup result;
        bool manifold_all = true;
        if (make_solids(s, result, manifold_all)) return true;
        if (ids_.size() == 1 && !manifold_all) {
            // a pinched solid of one body: as it is
        } else if (!manifold_all) {
            soup_pass(result);
        } else {
            unite(result);
        }
        round_soup(result, s, rep_, sxyz_, parts_, ids_);
        return false;
    }

  private:
    const double *xyz_, *sxyz_;
    const uint32_t *tri_;
    const std::vector<Part> &parts_;
    const std::vector<size_t> &ids_;
    const coons_csg_options &o_;
    coons_csg_report &rep_;
    Progress prog_;
    double p0_, p1_;
    unsigned threads_;
    std::vector<EMesh> solids_;    // per part of the group
    std::vector<size_t> crossing_; // its self-intersecting pairs

    // Counts each part's self-intersections (a lone part without repair is
    // not looked at); true when none crosses itself.
    bool count_crossings()
    {
        bool clean = true;
        // The checks take the first tenth of the group's share, one part
        // after another, weighted by their triangles.
        size_t total = 0, done = 0;
        for (size_t id : ids_) total += parts_[id].tri_count;
        for (size_t k = 0; k < ids_.size(); k++) {
            const Part &p = parts_[ids_[k]];
            prog_("check", p0_ + 0.1 * (p1_ - p0_) * (double)done / (double)(total ? total : 1));
            done += p.tri_count;
            std::vector<uint32_t> local = local_triangles(tri_, p);
            crossing_[k] = o_.repair || ids_.size() > 1
                               ? count_self_intersections(xyz_ + 3 * p.vert_first, p.vert_count,
                                                          local.data(), p.tri_count, nullptr,
                                                          threads_)
                               : 0;
            rep_.intersecting_pairs += crossing_[k];
            if (crossing_[k]) clean = false;
        }
        prog_("check", p0_ + 0.1 * (p1_ - p0_));
        return clean;
    }

    // Each part as an exact closed 2-manifold in solids_, repaired when it
    // crosses itself. Returns true when a lone clean part passed through
    // (into s); clears manifold_all when a repaired part is pinched (for a
    // lone part, `result` then holds its repaired soup).
    bool make_solids(Soup &s, ExactSoup &result, bool &manifold_all)
    {
        for (size_t k = 0; k < ids_.size(); k++) {
            const Part &p = parts_[ids_[k]];
            std::vector<uint32_t> local = local_triangles(tri_, p);
            size_t pairs = crossing_[k];
            if (pairs == 0 && ids_.size() == 1) {
                rep_.passed_through++;
                s.xyz.assign(xyz_ + 3 * p.vert_first, xyz_ + 3 * (p.vert_first + p.vert_count));
                s.tri = local;
                return true;
            }
            ExactSoup es;
            if (pairs == 0) {
                for (size_t v = 0; v < p.vert_count; v++) {
                    const double *q = sxyz_ + 3 * (p.vert_first + v);
                    es.pts.emplace_back(q[0], q[1], q[2]);
                }
                for (size_t t = 0; t < p.tri_count; t++)
                    es.tri.push_back({local[3 * t], local[3 * t + 1], local[3 * t + 2]});
                if (exact_mesh(es, solids_[k])) continue;
                es = ExactSoup();
            }
            std::vector<size_t> one{ids_[k]};
            double q0 = p0_ + (p1_ - p0_) * k / (2.0 * ids_.size());
            Solidifier sol(sxyz_, tri_, parts_, one, rep_, prog_, q0,
                           q0 + (p1_ - p0_) / (2.0 * ids_.size()));
            if (!sol.run(solids_[k], es)) {
                manifold_all = false;
                if (ids_.size() == 1) result = es;
                break;
            }
        }
        return false;
    }

    // The whole group at once through the soup pass, into result.
    void soup_pass(ExactSoup &result)
    {
        Solidifier sol(sxyz_, tri_, parts_, ids_, rep_, prog_, p0_ + 0.5 * (p1_ - p0_), p1_);
        EMesh m;
        result = ExactSoup();
        sol.run(m, result);
    }

    // The solids united by chained exact corefinement; the soup pass when
    // corefinement refuses.
    void unite(ExactSoup &result)
    {
        std::string why;
        try {
            EMesh acc = std::move(solids_[0]);
            for (size_t k = 1; k < ids_.size(); k++) {
                prog_("union", p0_ + (p1_ - p0_) * (0.5 + 0.5 * k / ids_.size()));
                if (!PMP::corefine_and_compute_union(acc, solids_[k], acc))
                    throw Failure(COONS_E_CSG,
                                  "corefinement refused '" + parts_[ids_[k]].name + "'");
            }
            soup_of(acc, result);
        } catch (const std::bad_alloc &) {
            throw;
        } catch (const std::exception &e) {
            // CGAL 5.5's corefinement rejects some coplanar contacts that
            // the soup pass handles: try that before giving up.
            why = e.what();
        }
        if (!why.empty()) {
            rep_.fallbacks++;
            soup_pass(result);
        }
    }
};

// The input snapped to a grid of a power of two near 1e-12 of its size, for
// the parts that need exact work: sampling noise (a NURBS plane at
// z = 10.000000000000002 next to one at z = 10) otherwise makes
// near-coplanar contacts whose exact intersections are narrower than
// doubles, and the final rounding turns them into crossings. The snap
// moves no point by more than 1e-12 of the size.
std::vector<double> snapped(const double *xyz, size_t nv)
{
    std::vector<double> sxyz(xyz, xyz + 3 * nv);
    double lo[3], hi[3];
    bbox_empty(lo, hi);
    for (size_t v = 0; v < nv; v++) bbox_add(lo, hi, &sxyz[3 * v]);
    double diag = bbox_diag(lo, hi), mag = 0;
    for (int c = 0; c < 3; c++) mag = std::max(mag, std::max(std::fabs(lo[c]), std::fabs(hi[c])));
    if (diag > 0) {
        int e;
        std::frexp(std::max(diag, mag) * 1e-12, &e);
        double g = std::ldexp(1.0, e);
        for (double &x : sxyz) x = std::nearbyint(x / g) * g;
    }
    return sxyz;
}

// Groups of parts that meet, transitively (unite), or each part alone:
// parts meet when boxes of their triangles meet or one lies inside the
// other (coons_csg::parts_interact); the others need no Boolean together.
std::vector<std::vector<size_t>> group_parts(const double *xyz, const uint32_t *tri,
                                             const std::vector<Part> &parts, bool unite)
{
    std::vector<int> group(parts.size(), -1);
    std::vector<std::vector<size_t>> groups;
    for (size_t i = 0; i < parts.size(); i++) {
        if (group[i] >= 0) continue;
        group[i] = (int)groups.size();
        groups.push_back({i});
        if (!unite) continue;
        for (size_t q = 0; q < groups.back().size(); q++)
            for (size_t j = 0; j < parts.size(); j++)
                if (group[j] < 0 &&
                    coons_csg::parts_interact(xyz, tri, parts[groups.back()[q]], parts[j])) {
                    group[j] = group[i];
                    groups.back().push_back(j);
                }
    }
    return groups;
}

// The exact check of a rounded result: a crossing or a flat triangle that
// the rounding made is an error, never a silent result.
// Local: pairs of two triangles taken unchanged from the input shells
// (`old`) are not tested (the inputs were checked, and autorefinement or
// corefinement split every input pair that crosses).
void check_rounding(const Soup &s, const InputTriangles &old, unsigned threads)
{
    size_t degenerate = 0;
    size_t pairs = count_self_intersections(s.xyz.data(), s.xyz.size() / 3, s.tri.data(),
                                            s.tri.size() / 3, &degenerate, threads, &old);
    if (pairs || degenerate)
        throw Failure(COONS_E_CSG, "rounding the exact result to doubles made " +
                                       std::to_string(pairs) + " triangle pairs intersect and " +
                                       std::to_string(degenerate) + " triangles flat");
}

struct MeshFree {
    void operator()(coons_mesh *m) const { coons_mesh_free(m); }
};
typedef std::unique_ptr<coons_mesh, MeshFree> MeshPtr;

// The work of coons_mesh_solidify() (see the file comment). `parts` and
// `current` (the parts being worked on) stay with the caller, whose error
// message names them.
// Scale invariance: CGAL's filtered predicates and exact numbers (Mpzf)
// overflow on products of coordinates near 1e100 and lose their filters
// near 1e-100. The work is done on coordinates scaled by a power of two
// (exact) that makes the extent about 1, and the results scaled back
// (exact again): the same triangles, up to scale, at every size.
double unit_scale(const double *xyz, size_t nv)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (size_t i = 0; i < nv; i++)
        for (int d = 0; d < 3; d++) {
            lo[d] = std::min(lo[d], xyz[3 * i + d]);
            hi[d] = std::max(hi[d], xyz[3 * i + d]);
        }
    double ext = 0;
    for (int d = 0; d < 3; d++) ext = std::max(ext, hi[d] - lo[d]);
    return ext > 0 && std::isfinite(ext) ? std::ldexp(1.0, -std::ilogb(ext)) : 1.0;
}

std::vector<double> scaled(const double *xyz, size_t nv, double scale)
{
    std::vector<double> v(xyz, xyz + 3 * nv);
    for (double &x : v) x *= scale;
    return v;
}

coons_status solidify(const coons_mesh *in, const coons_csg_options &o, std::vector<Part> &parts,
                      std::vector<size_t> &current, coons_mesh **out, coons_csg_report *report,
                      coons_error *err)
{
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    Progress prog{&o};
    const double scale = unit_scale(coons_mesh_vertices(in), coons_mesh_vertex_count(in));
    const std::vector<double> unit = scaled(coons_mesh_vertices(in), coons_mesh_vertex_count(in), scale);
    const double *xyz = unit.data();
    const uint32_t *tri = coons_mesh_triangles(in);
    collect_parts(in, xyz, parts);
    // Until the groups are known, a failure concerns every part.
    for (size_t i = 0; i < parts.size(); i++) current.push_back(i);
    rep.parts_in = parts.size();
    rep.triangles_in = coons_mesh_triangle_count(in);
    if (coons__csg_failure_injected())
        throw CGAL::Failure_exception("libcoons", "injected", __FILE__, __LINE__,
                                      "injected failure (testing)");
    std::vector<double> sxyz = snapped(xyz, coons_mesh_vertex_count(in));
    std::vector<std::vector<size_t>> groups = group_parts(xyz, tri, parts, o.unite != 0);
    rep.groups = groups.size();

    coons_mesh *made = nullptr;
    coons_status rc = coons_mesh_new(&made, err);
    if (rc) return rc;
    MeshPtr res(made);
    // Groups that do not meet are independent: with threads, they run at
    // once (progress is then reported from this thread as groups finish);
    // each has its own report and result, gathered in group order, so the
    // result does not depend on the number of threads.
    const size_t ng = groups.size();
    const unsigned threads = o.threads > 1 ? o.threads : 1;
    std::vector<Soup> results(ng);
    std::vector<coons_csg_report> reps(ng);
    for (coons_csg_report &r : reps) coons_csg_report_init(&r);
    auto one_group = [&](size_t gi, Progress pr, unsigned inner) {
        double p0 = (double)gi / ng, p1 = (double)(gi + 1) / ng;
        pr("check", p0);
        Soup &s = results[gi];
        GroupSolidifier g(xyz, sxyz.data(), tri, parts, groups[gi], o, reps[gi], pr, p0, p1,
                          inner);
        if (!g.run(s)) {
            pr("verify", p0 + (p1 - p0) * 0.95);
            InputTriangles old;
            coons_csg::input_triangles(sxyz.data(), tri, parts, groups[gi], old);
            check_rounding(s, old, inner);
        }
        edge_stats(s, reps[gi]);
    };
    if (threads > 1 && ng > 1) {
        unsigned inner = threads / (unsigned)std::min<size_t>(threads, ng);
        prog("check", 0.0);
        std::vector<std::exception_ptr> errors;
        parallel_for(threads, ng, [&](size_t gi) { one_group(gi, Progress{nullptr}, inner); },
                     errors);
        for (size_t gi = 0; gi < ng; gi++) {
            if (errors[gi]) {
                current = groups[gi];
                std::rethrow_exception(errors[gi]);
            }
            prog("check", (double)(gi + 1) / ng);
        }
    } else {
        for (size_t gi = 0; gi < ng; gi++) {
            current = groups[gi];
            one_group(gi, prog, threads);
        }
    }
    Soup all;
    rep.closed = ng > 0;
    for (size_t gi = 0; gi < ng; gi++) {
        const coons_csg_report &r = reps[gi];
        rep.degenerate_dropped += r.degenerate_dropped;
        rep.intersecting_pairs += r.intersecting_pairs;
        rep.passed_through += r.passed_through;
        rep.patches += r.patches;
        rep.patches_kept += r.patches_kept;
        rep.fast_unions += r.fast_unions;
        rep.fallbacks += r.fallbacks;
        rep.rounding_merged += r.rounding_merged;
        rep.close_merged += r.close_merged;
        rep.slivers_fixed += r.slivers_fixed;
        rep.nonmanifold_edges += r.nonmanifold_edges;
        rep.closed = rep.closed && r.closed;
        Soup &s = results[gi];
        for (double &x : s.xyz) x /= scale;
        if (o.unite) {
            uint32_t base = (uint32_t)(all.xyz.size() / 3);
            all.xyz.insert(all.xyz.end(), s.xyz.begin(), s.xyz.end());
            for (uint32_t v : s.tri) all.tri.push_back(v + base);
        } else {
            rc = coons_mesh_add_part(res.get(), parts[groups[gi][0]].name.c_str(), s.xyz.data(),
                                     s.xyz.size() / 3, s.tri.data(), s.tri.size() / 3, err);
            if (rc) return rc;
        }
        std::vector<double>().swap(s.xyz);
        std::vector<uint32_t>().swap(s.tri);
    }
    if (o.unite) {
        rc = coons_mesh_add_part(res.get(), o.name ? o.name : "union", all.xyz.data(),
                                 all.xyz.size() / 3, all.tri.data(), all.tri.size() / 3, err);
        if (rc) return rc;
    }
    rep.triangles_out = coons_mesh_triangle_count(res.get());
    prog("done", 1.0);
    if (report) *report = rep;
    *out = res.release();
    return COONS_OK;
}

// Where a CGAL::Failure_exception's what() ("LIB ERROR: KIND!\nExpr: E\n
// File: F\nLine: N\nExplanation: M", Expr and Explanation optional) holds
// its message M, or else its expression E: read in place, since the
// accessors return std::string copies and this runs in the catch path.
void cgal_reason(const char *what, const char **text, int *len) noexcept
{
    static const char line_tag[] = "\nLine: ", expl_tag[] = "\nExplanation: ";
    static const char expr_tag[] = "\nExpr: ", file_tag[] = "\nFile: ";
    const char *line = nullptr;
    for (const char *p = std::strstr(what, line_tag); p; p = std::strstr(p + 1, line_tag)) {
        const char *q = p + sizeof line_tag - 1;
        while (*q >= '0' && *q <= '9') q++;
        if (*q == '\0' || std::strncmp(q, expl_tag, sizeof expl_tag - 1) == 0) {
            line = p;
            if (*q) {
                *text = q + sizeof expl_tag - 1;
                *len = (int)std::strlen(*text);
                return;
            }
            break;
        }
    }
    *text = "";
    *len = 0;
    const char *expr = std::strstr(what, expr_tag);
    if (!expr || !line || expr > line) return;
    expr += sizeof expr_tag - 1;
    const char *end = nullptr;
    for (const char *p = std::strstr(expr, file_tag); p && p < line; p = std::strstr(p + 1, file_tag))
        end = p;
    if (!end) return;
    *text = expr;
    *len = (int)(end - expr);
}

// The guard's describe() for coons_mesh_solidify(): names the bodies being
// worked on; a Failure carries its own status.
coons_status describe_failure(coons_error *err, const std::exception &e,
                              const std::vector<Part> &parts,
                              const std::vector<size_t> &current) noexcept
{
    char names[COONS_ERROR_MESSAGE_MAX];
    names_into(names, sizeof names, parts, current);
    if (const Failure *f = dynamic_cast<const Failure *>(&e)) {
        if (current.empty()) return coons__error_set(err, f->code, "%s", f->what());
        return coons__error_set(err, f->code, "bodies %s: %s", names, f->what());
    }
    if (const CGAL::Failure_exception *c = dynamic_cast<const CGAL::Failure_exception *>(&e)) {
        const char *text;
        int len;
        cgal_reason(c->what(), &text, &len);
        return coons__error_set(err, COONS_E_CSG,
                                "CGAL could not complete the operation on bodies %s: %.*s", names,
                                len, text);
    }
    return coons__error_set(err, COONS_E_CSG, "bodies %s: %s", names, e.what());
}

const char unknown_text[] = "unknown exception in the CGAL layer";


// A failure of the self-intersection test in words: what failed, CGAL's
// own reason (its explanation or expression, not the whole assertion
// text), and what to try.
coons_status describe_self_int(coons_error *err, const std::exception &e) noexcept
{
    const char *text = e.what();
    int len = (int)std::strlen(text);
    if (const CGAL::Failure_exception *c = dynamic_cast<const CGAL::Failure_exception *>(&e))
        cgal_reason(c->what(), &text, &len);
    return coons__error_set(err, COONS_E_CSG,
                            "the exact self-intersection test of the mesh could not complete "
                            "(CGAL: %.*s); try a coarser tolerance (-t) or write it with "
                            "--no-repair",
                            len, text);
}

coons_status self_int(const char *entry, const coons_mesh *m, size_t *pairs, bool to_float,
                      unsigned threads, coons_error *err) noexcept
{
    *pairs = 0;
    return coons::guard(entry, err, unknown_text, [&]() -> coons_status {
        size_t nv = coons_mesh_vertex_count(m);
        const double *xyz = coons_mesh_vertices(m);
        std::vector<double> f(xyz, xyz + 3 * nv);
        if (to_float) { // rounded as STL stores it, then scaled exactly
            double big = 0;
            for (size_t i = 0; i < 3 * nv; i++) big = std::max(big, std::fabs(xyz[i]));
            if (big > FLT_MAX || (big > 0 && big < std::ldexp((double)FLT_MIN, 23)))
                return coons__error_set(err, COONS_E_LIMIT,
                                        "the mesh's largest coordinate, %.17g, does not fit "
                                        "STL's 32-bit floats",
                                        big);
            for (size_t i = 0; i < 3 * nv; i++) f[i] = (double)(float)xyz[i];
        }
        const double scale = unit_scale(f.data(), nv);
        for (double &x : f) x *= scale;
        xyz = f.data();
        *pairs = count_self_intersections(xyz, nv, coons_mesh_triangles(m),
                                          coons_mesh_triangle_count(m), nullptr,
                                          std::max(1u, std::min(threads, 1024u)));
        return COONS_OK;
    }, [](coons_error *e, const std::exception &x) noexcept { return describe_self_int(e, x); });
}

} // namespace

extern "C" coons_status coons_mesh_solidify(const coons_mesh *in, const coons_csg_options *opts,
                                            coons_mesh **out, coons_csg_report *report,
                                            coons_error *err)
{
    *out = nullptr;
    std::vector<Part> parts;
    std::vector<size_t> current;
    coons_csg_report full;
    coons_csg_report *rep = nullptr;
    coons_status rc = coons::guard(
        __func__, err, unknown_text,
        [&]() -> coons_status {
            coons_status st = coons__csg_records_check(opts, report, err);
            if (st) return st;
            rep = coons__csg_report_open(report, &full);
            coons_csg_options o;
            coons__csg_options_read(opts, &o);
            return solidify(in, o, parts, current, out, rep, err);
        },
        [&](coons_error *e, const std::exception &x) noexcept {
            return describe_failure(e, x, parts, current);
        });
    coons__csg_report_close(report, rep);
    return rc;
}

extern "C" coons_status coons_mesh_count_self_intersections(const coons_mesh *m, size_t *pairs,
                                                            coons_error *err)
{
    return self_int(__func__, m, pairs, false, 1, err);
}

extern "C" coons_status coons_mesh_count_self_intersections_float(const coons_mesh *m, size_t *pairs,
                                                                  coons_error *err)
{
    return self_int(__func__, m, pairs, true, 1, err);
}

extern "C" coons_status coons_mesh_count_self_intersections_threads(const coons_mesh *m,
                                                                    int rounded, unsigned threads,
                                                                    size_t *pairs,
                                                                    coons_error *err)
{
    if (rounded != 0 && rounded != 1) {
        *pairs = 0;
        return coons__error_set(err, COONS_E_INVALID,
                                "self-intersections: rounded must be 0 or 1, not %d", rounded);
    }
    return self_int(__func__, m, pairs, rounded == 1, threads, err);
}

// Test hook (coons_test_hooks.h): the self-intersection count as the union
// runs it (local when old_tri flags input triangles), or by the reference.
extern "C" coons_status coons__csg_count_pairs(const coons_mesh *m, const unsigned char *old_tri,
                                               int reference, unsigned threads, size_t *pairs,
                                               size_t *degenerate, coons_error *err)
{
    *pairs = 0;
    if (degenerate) *degenerate = 0;
    return coons::guard(__func__, err, unknown_text, [&]() -> coons_status {
        const double *xyz = coons_mesh_vertices(m);
        const uint32_t *tri = coons_mesh_triangles(m);
        size_t nt = coons_mesh_triangle_count(m);
        InputTriangles old;
        for (size_t t = 0; old_tri && t < nt; t++)
            if (old_tri[t])
                old.insert(coons_csg::tri_key(xyz + 3 * tri[3 * t], xyz + 3 * tri[3 * t + 1],
                                              xyz + 3 * tri[3 * t + 2]));
        *pairs = count_self_intersections(xyz, coons_mesh_vertex_count(m), tri, nt, degenerate,
                                          threads, old_tri ? &old : nullptr, reference != 0);
        return COONS_OK;
    }, [](coons_error *e, const std::exception &x) noexcept { return describe_self_int(e, x); });
}

extern "C" int coons_csg_is_available(void) { return 1; }
