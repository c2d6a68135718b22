/* SPDX-License-Identifier: GPL-3.0-or-later */
/* What a trilinear hexahedron of a lattice becomes where its body
 * collapses (coons/volume.h: "A collapsed cell ... repeats a node", and
 * coons_volume_mesh_cell_shape()).
 *
 * The mesher merges lattice nodes that evaluate to the same point, so a
 * cell at a collapsed edge of the body (a wedge-shaped tip) has two of its
 * parallel edges reduced to a point each, and a cell at a face collapsed
 * to a point (a cone's apex, the nail's tip) has a whole face reduced to
 * one node. Formats that have wedges and pyramids (Gmsh, VTK, CalculiX)
 * get those instead of a hexahedron with a zero-volume corner, whose
 * Jacobian vanishes there and which Gmsh's minJ and CalculiX report as
 * invalid. The classification is purely combinatorial: it works in the
 * cell's reference corners (r, s, t) in {0,1}^3, which the mesher keeps
 * right-handed (a left-handed body's cells are mirrored), so the
 * orientation of the result follows from the reference frame alone. */
#include "cell_shape.h"

#include "volume_impl.h"

#include <string.h>

/* Reference corner of each Gmsh corner: bit 0 r, bit 1 s, bit 2 t. */
static const unsigned char BITS[8] = {0, 1, 3, 2, 4, 5, 7, 6};

static int corner_of(unsigned bits)
{
    for (int i = 0; i < 8; i++)
        if (BITS[i] == bits) return i;
    return -1;
}

static int coord(int corner, int axis) { return (BITS[corner] >> axis) & 1; }

/* Reference corner with the given coordinates along axes a, b, c. */
static int at(int a, int va, int b, int vb, int c, int vc)
{
    return corner_of((unsigned)(va << a | vb << b | vc << c));
}

/* Sign of ((p1 - p0) x (p2 - p0)) . e_axis in reference coordinates, where
 * each p is the mean of two reference corners (a merged pair, or a corner
 * given twice). */
static int turn(int p[3][2], int axis)
{
    double q[3][3];
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++) q[i][k] = 0.5 * (coord(p[i][0], k) + coord(p[i][1], k));
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) e1[k] = q[1][k] - q[0][k], e2[k] = q[2][k] - q[0][k];
    int x = (axis + 1) % 3, y = (axis + 2) % 3;
    double n = e1[x] * e2[y] - e1[y] * e2[x];
    return n > 0 ? 1 : n < 0 ? -1 : 0;
}

static int distinct(const uint32_t *v, int n)
{
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            if (v[i] == v[j]) return 0;
    return 1;
}

/* Edges of the hexahedron as corner pairs, with their direction axis. */
static const unsigned char EDGE[12][3] = {{0, 1, 0}, {3, 2, 0}, {4, 5, 0}, {7, 6, 0},
                                          {0, 3, 1}, {1, 2, 1}, {4, 7, 1}, {5, 6, 1},
                                          {0, 4, 2}, {1, 5, 2}, {2, 6, 2}, {3, 7, 2}};

static coons__cell_shape wedge(const uint32_t h[8], const int e[2], uint32_t out[8])
{
    int b = EDGE[e[0]][2];
    if (EDGE[e[1]][2] != b) return COONS__SHAPE_DEGENERATE;
    int o1 = (b + 1) % 3, o2 = (b + 2) % 3;
    int c0 = EDGE[e[0]][0], c1 = EDGE[e[1]][0];
    /* The two edges share the coordinate of axis a (the face they lie in
     * collapses to a line) and differ in axis c. */
    int a, c;
    if (coord(c0, o1) == coord(c1, o1) && coord(c0, o2) != coord(c1, o2))
        a = o1, c = o2;
    else if (coord(c0, o2) == coord(c1, o2) && coord(c0, o1) != coord(c1, o1))
        a = o2, c = o1;
    else
        return COONS__SHAPE_DEGENERATE;
    int sigma = coord(c0, a);
    /* Triangle at c = 0: the merged pair M, then P, Q at a = 1 - sigma. */
    int tri[3][2] = {{at(a, sigma, b, 0, c, 0), at(a, sigma, b, 1, c, 0)},
                     {at(a, 1 - sigma, b, 0, c, 0), at(a, 1 - sigma, b, 0, c, 0)},
                     {at(a, 1 - sigma, b, 1, c, 0), at(a, 1 - sigma, b, 1, c, 0)}};
    if (turn(tri, c) < 0) {
        int t0 = tri[1][0];
        tri[1][0] = tri[1][1] = tri[2][0];
        tri[2][0] = tri[2][1] = t0;
    }
    for (int i = 0; i < 3; i++) {
        int lo = tri[i][0];
        int hi = at(a, coord(lo, a), b, coord(lo, b), c, 1);
        out[i] = h[lo];
        out[3 + i] = h[hi];
    }
    return distinct(out, 6) ? COONS__SHAPE_WEDGE : COONS__SHAPE_DEGENERATE;
}

static coons__cell_shape pyramid(const uint32_t h[8], uint32_t out[8])
{
    for (int a = 0; a < 3; a++)
        for (int sigma = 0; sigma < 2; sigma++) {
            int b = (a + 1) % 3, c = (a + 2) % 3;
            uint32_t apex = h[at(a, sigma, b, 0, c, 0)];
            if (h[at(a, sigma, b, 1, c, 0)] != apex || h[at(a, sigma, b, 0, c, 1)] != apex ||
                h[at(a, sigma, b, 1, c, 1)] != apex)
                continue;
            /* Base at a = 1 - sigma, cyclic in (b, c); its normal by the
             * right-hand rule must point to the apex, along (2 sigma - 1) e_a. */
            int base[4] = {at(a, 1 - sigma, b, 0, c, 0), at(a, 1 - sigma, b, 1, c, 0),
                           at(a, 1 - sigma, b, 1, c, 1), at(a, 1 - sigma, b, 0, c, 1)};
            int p[3][2] = {{base[0], base[0]}, {base[1], base[1]}, {base[2], base[2]}};
            int want = sigma ? 1 : -1;
            for (int i = 0; i < 4; i++) {
                int k = turn(p, a) == want ? i : (4 - i) % 4;
                out[i] = h[base[k]];
            }
            out[4] = apex;
            return distinct(out, 5) ? COONS__SHAPE_PYRAMID : COONS__SHAPE_DEGENERATE;
        }
    return COONS__SHAPE_DEGENERATE;
}

coons__cell_shape coons__hex8_shape(const uint32_t h[8], uint32_t out[8])
{
    int e[12], n = 0;
    for (int i = 0; i < 12; i++)
        if (h[EDGE[i][0]] == h[EDGE[i][1]]) e[n++] = i;
    coons__cell_shape shape = COONS__SHAPE_DEGENERATE;
    if (n == 0 && distinct(h, 8))
        shape = COONS__SHAPE_HEX;
    else if (n == 2)
        shape = wedge(h, e, out);
    else if (n == 4)
        shape = pyramid(h, out);
    if (shape == COONS__SHAPE_HEX || shape == COONS__SHAPE_DEGENERATE) memcpy(out, h, 8 * sizeof *h);
    return shape;
}

coons__cell_shape coons__cell_shape_of(const uint32_t *h, size_t npc, uint32_t out[27])
{
    if (npc == 8) return coons__hex8_shape(h, out);
    memcpy(out, h, npc * sizeof *h);
    return distinct(h, 8) ? COONS__SHAPE_HEX : COONS__SHAPE_DEGENERATE;
}

coons_status coons_volume_mesh_cell_shape(const coons_volume_mesh *vm, size_t i,
                                          coons_cell_shape *shape, uint32_t *nodes,
                                          size_t *count, coons_error *err)
{
    if (!vm || !shape || !nodes || !count)
        return coons__error_set(err, COONS_E_INVALID, "no mesh or no output given");
    if (i >= vm->nc)
        return coons__error_set(err, COONS_E_INVALID, "no cell %zu (the mesh has %zu)", i, vm->nc);
    uint32_t out[COONS_VOLUME_CELL_NODES_MAX];
    coons__cell_shape sh = coons__cell_shape_of(vm->cell + vm->npc * i, vm->npc, out);
    size_t n = sh == COONS__SHAPE_WEDGE ? 6 : sh == COONS__SHAPE_PYRAMID ? 5 : vm->npc;
    memcpy(nodes, out, n * sizeof *out);
    *shape = sh == COONS__SHAPE_WEDGE     ? COONS_CELL_WEDGE
             : sh == COONS__SHAPE_PYRAMID ? COONS_CELL_PYRAMID
                                          : COONS_CELL_HEXAHEDRON;
    *count = n;
    return COONS_OK;
}
