/* SPDX-License-Identifier: GPL-3.0-or-later */
/* OpenMesh glue: a coons_mesh as an OpenMesh halfedge triangle mesh (double
 * coordinates), for the checks of coons_mesh_check() and for reading STL/OFF
 * files with OpenMesh's readers.
 *
 * Debian's OpenMesh 9.0 logs to omlog/omerr (e.g. "add_face: complex edge")
 * and stores float points by default; the library must stay silent and keep
 * doubles, hence Vec3d traits and the streams disabled before any call.
 * add_face() reports a refused face only by an invalid handle: every handle
 * is checked and counted. Every extern "C" entry runs through the guard
 * of cxx_guard.hpp: no exception crosses into C. */

/* gcc 12 warns falsely (-Wmaybe-uninitialized) inside OpenMesh's headers at
 * -O2; silenced for this file only. */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include "cxx_guard.hpp"

extern "C" {
#include "coons_internal.h"
#include "mesh_glue.h"
}

namespace {

struct Traits : public OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
    typedef OpenMesh::Vec3d Normal;
};
typedef OpenMesh::TriMesh_ArrayKernelT<Traits> OMesh;

void silence()
{
    /* Process-wide switches of OpenMesh's own streams (they are OpenMesh's
     * global state, not ours); idempotent. */
    omlog().disable();
    omout().disable();
    omerr().disable();
}

/* Builds om from the arrays of m; returns the number of refused faces. */
size_t build(const coons_mesh *m, OMesh &om)
{
    size_t nv = coons_mesh_vertex_count(m), nt = coons_mesh_triangle_count(m);
    const double *x = coons_mesh_vertices(m);
    const uint32_t *t = coons_mesh_triangles(m);
    om.reserve(nv, 3 * nt / 2 + 3, nt);
    std::vector<OMesh::VertexHandle> vh(nv);
    for (size_t i = 0; i < nv; i++) vh[i] = om.add_vertex(OMesh::Point(x[3 * i], x[3 * i + 1], x[3 * i + 2]));
    size_t rejected = 0;
    for (size_t f = 0; f < nt; f++) {
        uint32_t a = t[3 * f], b = t[3 * f + 1], c = t[3 * f + 2];
        if (a == b || b == c || c == a) { /* OpenMesh cannot hold these at all */
            rejected++;
            continue;
        }
        OMesh::FaceHandle fh = om.add_face(vh[a], vh[b], vh[c]);
        if (!fh.is_valid()) rejected++;
    }
    return rejected;
}

/* What the guard says of an exception of this layer (cxx_guard.hpp). */
const coons::guard_text om_text = {COONS_E_INTERNAL, "OpenMesh: ", "OpenMesh: unknown exception"};

/* om's points and triangles as a new one-part mesh named `name`. */
coons_status mesh_of(const OMesh &om, const char *name, coons_mesh **out, coons_error *err)
{
    std::vector<double> xyz;
    xyz.reserve(3 * om.n_vertices());
    for (OMesh::VertexHandle v : om.vertices()) {
        const OMesh::Point &p = om.point(v);
        xyz.push_back(p[0]);
        xyz.push_back(p[1]);
        xyz.push_back(p[2]);
    }
    std::vector<uint32_t> tri;
    tri.reserve(3 * om.n_faces());
    for (OMesh::FaceHandle fh : om.faces()) {
        size_t k = 0;
        for (OMesh::VertexHandle v : om.fv_range(fh)) {
            tri.push_back(static_cast<uint32_t>(v.idx()));
            k++;
        }
        if (k != 3)
            return coons__error_set(err, COONS_E_INTERNAL,
                                    "OpenMesh returned a face with %zu vertices", k);
    }
    coons_mesh *m;
    coons_status st = coons_mesh_new(&m, err);
    if (st) return st;
    st = coons_mesh_add_part(m, name, xyz.data(), om.n_vertices(), tri.data(), tri.size() / 3, err);
    if (st) {
        coons_mesh_free(m);
        return st;
    }
    *out = m;
    return COONS_OK;
}

} // namespace

extern "C" coons_status coons_mesh_check(const coons_mesh *m, coons_mesh_report *report,
                                         coons_error *err)
{
    return coons::guard(__func__, err, om_text, [&]() -> coons_status {
        coons_status st = coons__mesh_check_c(m, report, err);
        if (st) return st;
        silence();
        OMesh om;
        report->openmesh_rejected = build(m, om);
        size_t boundary = 0;
        for (OMesh::HalfedgeHandle h : om.halfedges())
            if (om.is_boundary(h)) boundary++;
        report->openmesh_boundary = boundary;
        report->openmesh = 1;
        return COONS_OK;
    });
}

extern "C" coons_status coons__mesh_read(const char *path, coons_mesh **out, coons_error *err)
{
    *out = NULL;
    return coons::guard(__func__, err, om_text, [&]() -> coons_status {
        silence();
        FILE *f = fopen(path, "rb");
        if (!f) return coons__error_set(err, COONS_E_IO, "cannot open '%s'", path);
        fclose(f);
        OMesh om;
        OpenMesh::IO::Options opt;
        if (!OpenMesh::IO::read_mesh(om, std::string(path), opt))
            return coons__error_set(err, COONS_E_IO,
                                    "OpenMesh cannot read '%s' (its readers take STL, OFF, "
                                    "OBJ, PLY and OM files, chosen by extension)",
                                    path);
        if (om.n_faces() == 0)
            return coons__error_set(err, COONS_E_IO, "OpenMesh read no face from '%s'", path);
        const char *base = std::strrchr(path, '/');
        return mesh_of(om, base ? base + 1 : path, out, err);
    });
}
