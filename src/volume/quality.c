/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Cell quality of volume meshes: Knupp's scaled Jacobian of the linear
 * hexahedron of each cell's corners (P. M. Knupp, "Achieving finite
 * element mesh quality via optimization of the Jacobian matrix norm and
 * associated quantities", Int. J. Numer. Meth. Engng 48 (2000); the
 * Verdict library's hex scaled Jacobian), and the per-part report
 * (coons/volume.h). */
#include <string.h>

#include "body_impl.h"
#include "volume_impl.h"

/* From each corner (Gmsh order), its neighbours along +r, +s, +t of the
 * reference cell, so det[e1,e2,e3] > 0 for a valid cell: at corner 0 the
 * edges to 1, 3, 4; at the others the same right-handed triple turned. */
/*     corner  0: 1 3 4   1: 2 0 5   2: 3 1 6   3: 0 2 7
 *             4: 7 5 0   5: 4 6 1   6: 5 7 2   7: 6 4 3 */

/* The 12 edges of the hexahedron (Gmsh corners), and for each corner its
 * three edges to the neighbours above, with the sign of the edge's direction
 * seen from the corner. */
static const unsigned char EDGES[12][2] = {{0, 1}, {3, 2}, {4, 5}, {7, 6}, {0, 3}, {1, 2},
                                           {4, 7}, {5, 6}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
static const signed char CORNER_EDGE[8][3][2] = {
    {{0, 1}, {4, 1}, {8, 1}},
    {{5, 1}, {0, -1}, {9, 1}},
    {{1, -1}, {5, -1}, {10, 1}},
    {{4, -1}, {1, 1}, {11, 1}},
    {{6, 1}, {2, 1}, {8, -1}},
    {{2, -1}, {7, 1}, {9, -1}},
    {{7, -1}, {3, -1}, {10, -1}},
    {{3, 1}, {6, -1}, {11, -1}}};

static double cell_sj(const coons_volume_mesh *vm, size_t c, int *collapsed)
{
    const uint32_t *h = vm->cell + vm->npc * c;
    int rep = 0, any = 0;
    for (int i = 0; i < 8; i++)
        for (int j = i + 1; j < 8; j++) rep |= h[i] == h[j];
    /* Unit edge vectors (0 where an edge has no length). */
    double e[12][3];
    unsigned char zero[12];
    for (int k = 0; k < 12; k++) {
        const double *a = vm->xyz + 3 * (size_t)h[EDGES[k][0]];
        const double *b = vm->xyz + 3 * (size_t)h[EDGES[k][1]];
        double l = 0;
        for (int d = 0; d < 3; d++) e[k][d] = b[d] - a[d], l += e[k][d] * e[k][d];
        zero[k] = !(l > 0) || h[EDGES[k][0]] == h[EDGES[k][1]];
        double inv = zero[k] ? 0.0 : 1.0 / sqrt(l);
        for (int d = 0; d < 3; d++) e[k][d] *= inv;
    }
    double best = INFINITY;
    for (int i = 0; i < 8; i++) {
        int e0 = CORNER_EDGE[i][0][0], e1 = CORNER_EDGE[i][1][0], e2 = CORNER_EDGE[i][2][0];
        if (zero[e0] || zero[e1] || zero[e2]) continue;
        const double *x = e[e0], *y = e[e1], *z = e[e2];
        double det = x[0] * (y[1] * z[2] - y[2] * z[1]) - x[1] * (y[0] * z[2] - y[2] * z[0]) +
                     x[2] * (y[0] * z[1] - y[1] * z[0]);
        det *= CORNER_EDGE[i][0][1] * CORNER_EDGE[i][1][1] * CORNER_EDGE[i][2][1];
        if (det < best) best = det;
        any = 1;
    }
    if (collapsed) *collapsed = rep;
    return any ? best : 0.0;
}

double coons_volume_mesh_cell_scaled_jacobian(const coons_volume_mesh *vm, size_t cell,
                                              int *collapsed)
{
    if (collapsed) *collapsed = 0;
    if (!vm || cell >= vm->nc) return NAN;
    return cell_sj(vm, cell, collapsed);
}

/* Cells at a time of the batch below: each step is a loop over them that
 * the compiler turns into vector instructions. */
#define SJ_LANES 32

/* cell_sj() of `n` <= SJ_LANES cells from `first`, whose 12 edges join
 * distinct nodes, lane by lane: the same operations in the same order on
 * each cell (IEEE sqrt and division are exact-rounded in vector form as in
 * scalar form, and C11 forbids contracting them into FMAs), so the same
 * bits. An edge of no length (distinct nodes at one point) leaves its
 * cell to cell_sj(), which skips the corners at that edge; it returns 0
 * for it. */
/* The corner of unit edges x, y, z (each lanes of x, y and z components):
 * best = min(best, sign det[x, y, z]) lane by lane. */
static inline void sj_corner(double (*x)[SJ_LANES], double (*y)[SJ_LANES],
                             double (*z)[SJ_LANES], double sign, double *best)
{
    const double *x0 = x[0], *x1 = x[1], *x2 = x[2], *y0 = y[0], *y1 = y[1], *y2 = y[2],
                 *z0 = z[0], *z1 = z[1], *z2 = z[2];
    for (size_t l = 0; l < SJ_LANES; l++) {
        double det = x0[l] * (y1[l] * z2[l] - y2[l] * z1[l]) -
                     x1[l] * (y0[l] * z2[l] - y2[l] * z0[l]) +
                     x2[l] * (y0[l] * z1[l] - y1[l] * z0[l]);
        det *= sign;
        best[l] = det < best[l] ? det : best[l];
    }
}

COONS__SIMD_CLONES
static int sj_lanes(const coons_volume_mesh *vm, size_t first, size_t n, double *out)
{
    double p[8][3][SJ_LANES], e[12][3][SJ_LANES], best[SJ_LANES];
    int flat = 0;
    for (size_t l = 0; l < SJ_LANES; l++) {
        /* Lanes past n repeat the last cell: their values are not used. */
        const uint32_t *h = vm->cell + vm->npc * (first + (l < n ? l : n - 1));
        for (int i = 0; i < 8; i++)
            for (int d = 0; d < 3; d++) p[i][d][l] = vm->xyz[3 * (size_t)h[i] + (size_t)d];
    }
    for (int k = 0; k < 12; k++) {
        double(*a)[SJ_LANES] = p[EDGES[k][0]], (*b)[SJ_LANES] = p[EDGES[k][1]];
        double len[SJ_LANES];
        for (size_t l = 0; l < SJ_LANES; l++) {
            double x = b[0][l] - a[0][l], y = b[1][l] - a[1][l], z = b[2][l] - a[2][l];
            double q = 0;
            q += x * x;
            q += y * y;
            q += z * z;
            len[l] = q;
            e[k][0][l] = x;
            e[k][1][l] = y;
            e[k][2][l] = z;
        }
        for (size_t l = 0; l < SJ_LANES; l++) flat |= !(len[l] > 0);
        if (flat) return 0;
        for (size_t l = 0; l < SJ_LANES; l++) {
            /* len > 0: sqrt needs no errno (-fno-math-errno lets it be a
             * vector instruction) */
            double inv = 1.0 / sqrt(len[l]);
            e[k][0][l] *= inv;
            e[k][1][l] *= inv;
            e[k][2][l] *= inv;
        }
    }
    for (size_t l = 0; l < SJ_LANES; l++) best[l] = INFINITY;
    for (int i = 0; i < 8; i++)
        sj_corner(e[CORNER_EDGE[i][0][0]], e[CORNER_EDGE[i][1][0]], e[CORNER_EDGE[i][2][0]],
                  CORNER_EDGE[i][0][1] * CORNER_EDGE[i][1][1] * CORNER_EDGE[i][2][1], best);
    for (size_t l = 0; l < n; l++) out[l] = best[l];
    return 1;
}

/* Whether the 12 edges of a hex8 (or the corner hexahedron of a hex20 or
 * hex27) join distinct nodes. */
static int edges_distinct(const uint32_t *h)
{
    int same = 0;
    for (int k = 0; k < 12; k++) same |= h[EDGES[k][0]] == h[EDGES[k][1]];
    return !same;
}

void coons__volume_mesh_scaled_jacobians(const coons_volume_mesh *vm, size_t lo, size_t hi,
                                         double *out)
{
    size_t c = lo;
    while (c < hi) {
        /* A run of cells whose edges join distinct nodes goes by lanes. */
        size_t n = 0;
        while (n < SJ_LANES && c + n < hi && edges_distinct(vm->cell + vm->npc * (c + n))) n++;
        if (n && sj_lanes(vm, c, n, out + (c - lo))) {
            c += n;
            continue;
        }
        size_t end = c + (n ? n : 1);
        for (; c < end; c++) out[c - lo] = cell_sj(vm, c, NULL);
    }
}

void coons_volume_quality_init(coons_volume_quality *q)
{
    const coons_volume_quality d = COONS_VOLUME_QUALITY_INIT;
    if (q) *q = d;
}

/* The node field called `name`, or NULL. */
static const double *node_field(const coons_volume_mesh *vm, const char *name)
{
    const coons__vfield *f = vm->fields[COONS_FIELD_NODE].items;
    for (size_t i = 0; i < vm->fields[COONS_FIELD_NODE].count; i++)
        if (!strcmp(f[i].name, name) && f[i].type == COONS_FIELD_FLOAT64) return f[i].values;
    return NULL;
}

coons_status coons_volume_mesh_quality(const coons_volume_mesh *vm, size_t part,
                                       coons_volume_quality *q, coons_error *err)
{
    if (!vm || !q) return coons__error_set(err, COONS_E_INVALID, "no mesh or report given");
    if (COONS__RECORD_CHECK(err, "volume quality report", q->version, COONS_VOLUME_QUALITY))
        return COONS_E_INVALID;
    if (part >= vm->parts.count)
        return coons__error_set(err, COONS_E_INVALID, "no part %zu (the mesh has %zu)", part,
                                vm->parts.count);
    coons_volume_quality r = COONS_VOLUME_QUALITY_INIT;
    r.element = vm->element;
    r.min_scaled_jacobian = r.mean_scaled_jacobian = NAN;
    for (int d = 0; d < 3; d++) r.worst_uvw[d] = NAN;
    unsigned char *seen = vm->nn ? coons__calloc(vm->nn, 1) : NULL;
    if (vm->nn && !seen) return coons__error_nomem(err);
    double sum = 0, worst = INFINITY;
    double block[256]; /* the scaled Jacobians of cells [c0, c0 + 256), by lanes */
    size_t c0 = 0, c1 = 0;
    for (size_t c = 0; c < vm->nc; c++) {
        if (vm->part[c] != part) continue;
        if (c >= c1) {
            c0 = c;
            c1 = vm->nc - c < 256 ? vm->nc : c + 256;
            coons__volume_mesh_scaled_jacobians(vm, c0, c1, block);
        }
        double sj = block[c - c0];
        const uint32_t *h = vm->cell + vm->npc * c;
        int col = 0; /* a repeated corner, as cell_sj() says */
        for (int i = 0; i < 8; i++)
            for (int j = i + 1; j < 8; j++) col |= h[i] == h[j];
        r.cells++;
        sum += sj;
        if (sj < worst) worst = sj, r.worst_cell = c;
        if (col)
            r.collapsed++;
        else if (sj <= 0)
            r.inverted++;
        if (sj < 0.2) r.below_0_2++;
        for (size_t k = 0; k < vm->npc; k++) {
            uint32_t v = vm->cell[vm->npc * c + k];
            if (!seen[v]) seen[v] = 1, r.nodes++;
        }
    }
    coons__free(seen);
    if (r.cells) {
        r.min_scaled_jacobian = worst;
        r.mean_scaled_jacobian = sum / (double)r.cells;
        static const char *names[3] = {"u", "v", "w"};
        for (int d = 0; d < 3; d++) {
            const double *f = node_field(vm, names[d]);
            if (!f) continue;
            double m = 0;
            for (int k = 0; k < 8; k++) m += f[vm->cell[vm->npc * r.worst_cell + (size_t)k]];
            r.worst_uvw[d] = m / 8;
        }
    }
    *q = r;
    return COONS_OK;
}
