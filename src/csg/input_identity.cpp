// SPDX-License-Identifier: GPL-3.0-or-later
//
// What a Boolean result keeps unchanged from its input shells, recognised by
// coordinates (cgal_common.hpp), free of CGAL: the vertices that are
// bitwise input vertices (fresh_vertices: welding moves only the others)
// and the triangles that are input triangles (tri_key, input_triangles:
// the local final check skips pairs of them).
#include <algorithm>

#include "cgal_common.hpp"

namespace coons_csg {

std::vector<char> fresh_vertices(const Soup &s, const double *xyz, const std::vector<Part> &parts,
                                 const std::vector<size_t> &ids)
{
    std::vector<const double *> in;
    for (size_t id : ids)
        for (size_t v = 0; v < parts[id].vert_count; v++)
            in.push_back(xyz + 3 * (parts[id].vert_first + v));
    std::sort(in.begin(), in.end(), point_less);
    size_t nv = s.xyz.size() / 3, j = 0;
    std::vector<char> fresh(nv, 1);
    for (size_t v = 0; v < nv; v++) {
        const double *p = &s.xyz[3 * v];
        while (j < in.size() && point_less(in[j], p)) j++;
        if (j < in.size() && !point_less(p, in[j])) fresh[v] = 0;
    }
    return fresh;
}

TriKey tri_key(const double *a, const double *b, const double *c)
{
    const double *q[3] = {a, b, c};
    int first = 0;
    for (int i = 1; i < 3; i++)
        if (std::memcmp(q[i], q[first], 3 * sizeof(double)) < 0) first = i;
    TriKey k;
    for (int i = 0; i < 3; i++) std::memcpy(k.v + 3 * i, q[(first + i) % 3], 3 * sizeof(double));
    return k;
}

void input_triangles(const double *xyz, const uint32_t *tri, const std::vector<Part> &parts,
                     const std::vector<size_t> &ids, InputTriangles &out)
{
    size_t n = 0;
    for (size_t id : ids) n += parts[id].tri_count;
    out.reserve(n);
    for (size_t id : ids) {
        const Part &p = parts[id];
        for (size_t t = p.tri_first; t < p.tri_first + p.tri_count; t++) {
            const uint32_t *q = tri + 3 * t;
            out.insert(tri_key(xyz + 3 * q[0], xyz + 3 * q[1], xyz + 3 * q[2]));
        }
    }
}

} // namespace coons_csg
