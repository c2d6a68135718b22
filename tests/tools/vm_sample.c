/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Writes a small volume mesh of known geometry, for the tests that read
 * volume-mesh files with other programs (Gmsh, meshio, VTK, CalculiX):
 *
 *     vm_sample OUT ELEMENT MAP [FORMAT]
 *
 * ELEMENT is hex8, hex20 or hex27; FORMAT a coons_format_from_name() name
 * (default: from OUT's extension). The mesh is a 2 x 2 x 2 lattice of
 * cells over (r, s, t) in [0,1]^3, nodes at the lattice points and, for
 * hex20/hex27, at the parameter midpoints, placed by MAP:
 *
 *   quad      x = r + 0.2 s^2,  y = s + 0.1 r t,  z = t + 0.15 r^2
 *             (quadratic: a hex27 cell interpolates it exactly, a hex20
 *             cell too along its edges, so a reader that orders the edge
 *             and face nodes wrongly evaluates other points);
 *   apex      x = r, y = r s, z = t: the face r = 0 collapses to the line
 *             x = y = 0, so the cells at r = 0 repeat corner nodes (wedges);
 *   pyramid   x = r (s - 1/2), y = r (t - 1/2), z = r: the face r = 0
 *             collapses to a point (pyramids).
 *
 * Coincident nodes are one node. Node fields u, v, w (the parameters
 * r, s, t), cell fields body (Int32) and scaled_jacobian; two parts
 * "lo" (cells with r < 1/2) and "hi"; cell sets per part; for each part
 * the node set and face set "PART.u0" .. "PART.w1" of its cells' faces on
 * the six sides of the unit cube. Exit status 0 on success, 1 with a
 * message otherwise. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <coons.h>

#define N 2 /* cells per direction */

static void map(const char *which, const double p[3], double x[3])
{
    double r = p[0], s = p[1], t = p[2];
    if (!strcmp(which, "apex")) {
        x[0] = r, x[1] = r * s, x[2] = t;
    } else if (!strcmp(which, "pyramid")) {
        x[0] = r * (s - 0.5), x[1] = r * (t - 0.5), x[2] = r;
    } else {
        x[0] = r + 0.2 * s * s, x[1] = s + 0.1 * r * t, x[2] = t + 0.15 * r * r;
    }
}

int main(int argc, char **argv)
{
    if (argc < 4 || argc > 5) {
        fprintf(stderr, "usage: vm_sample OUT hex8|hex20|hex27 quad|apex|pyramid [FORMAT]\n");
        return 1;
    }
    coons_element el = !strcmp(argv[2], "hex27")   ? COONS_ELEMENT_HEX27
                       : !strcmp(argv[2], "hex20") ? COONS_ELEMENT_HEX20
                                                   : COONS_ELEMENT_HEX8;
    /* Gmsh node reference positions (doubled), as in coons/volume.h. */
    static const int ref[27][3] = {
        {0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 2}, {2, 2, 2},
        {0, 2, 2}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 1, 0}, {2, 0, 1}, {1, 2, 0},
        {2, 2, 1}, {0, 2, 1}, {1, 0, 2}, {0, 1, 2}, {2, 1, 2}, {1, 2, 2}, {1, 1, 0},
        {1, 0, 1}, {0, 1, 1}, {2, 1, 1}, {1, 2, 1}, {1, 1, 2}, {1, 1, 1}};
    int npc = (int)el;
    enum { M = 2 * N + 1 }; /* half-step lattice points per direction */
    double xyz[M * M * M][3], uvw[M * M * M][3];
    int id[M * M * M];
    size_t nn = 0;
    for (int k = 0; k < M; k++)
        for (int j = 0; j < M; j++)
            for (int i = 0; i < M; i++) {
                double p[3] = {i / (2.0 * N), j / (2.0 * N), k / (2.0 * N)}, x[3];
                map(argv[3], p, x);
                int found = -1;
                for (size_t q = 0; q < nn && found < 0; q++)
                    if (xyz[q][0] == x[0] && xyz[q][1] == x[1] && xyz[q][2] == x[2])
                        found = (int)q;
                if (found < 0) {
                    memcpy(xyz[nn], x, sizeof x);
                    memcpy(uvw[nn], p, sizeof p);
                    found = (int)nn++;
                }
                id[i + M * (j + M * k)] = found;
            }
    /* Only nodes some cell uses are kept (hex8 skips the midpoints). */
    uint32_t cells[N * N * N][27];
    int used[M * M * M] = {0};
    int ncell = 0;
    int part_of[N * N * N], ijk[N * N * N][3];
    for (int part = 0; part < 2; part++)
        for (int k = 0; k < N; k++)
            for (int j = 0; j < N; j++)
                for (int i = 0; i < N; i++) {
                    if ((i < N / 2) != (part == 0)) continue;
                    for (int n = 0; n < npc; n++) {
                        int a = 2 * i + ref[n][0], b = 2 * j + ref[n][1], c = 2 * k + ref[n][2];
                        int q = id[a + M * (b + M * c)];
                        cells[ncell][n] = (uint32_t)q;
                        used[q] = 1;
                    }
                    ijk[ncell][0] = i, ijk[ncell][1] = j, ijk[ncell][2] = k;
                    part_of[ncell++] = part;
                }
    int newid[M * M * M];
    size_t kept = 0;
    double kx[M * M * M][3], ku[3][M * M * M];
    for (size_t q = 0; q < nn; q++) {
        newid[q] = -1;
        if (!used[q]) continue;
        memcpy(kx[kept], xyz[q], sizeof xyz[q]);
        for (int d = 0; d < 3; d++) ku[d][kept] = uvw[q][d];
        newid[q] = (int)kept++;
    }
    for (int c = 0; c < ncell; c++)
        for (int n = 0; n < npc; n++) cells[c][n] = (uint32_t)newid[cells[c][n]];

    coons_error e = COONS_ERROR_INIT;
    coons_volume_mesh *vm = NULL;
    coons_status st = coons_volume_mesh_new(el, &vm, &e);
    if (!st) st = coons_volume_mesh_add_nodes(vm, &kx[0][0], kept, NULL, &e);
    const char *pname[2] = {"lo", "hi"};
    for (int part = 0; part < 2 && !st; part++) {
        uint32_t rows[N * N * N * 27];
        size_t n = 0, first = 0;
        for (int c = 0; c < ncell; c++)
            if (part_of[c] == part) memcpy(rows + npc * n++, cells[c], (size_t)npc * 4);
        st = coons_volume_mesh_add_part(vm, pname[part], NULL, &e);
        if (!st) st = coons_volume_mesh_add_cells(vm, rows, n, (size_t)part, &first, &e);
    }
    static const char *fname[3] = {"u", "v", "w"};
    for (int d = 0; d < 3 && !st; d++)
        st = coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, fname[d], COONS_FIELD_FLOAT64,
                                         ku[d], &e);
    int32_t body[N * N * N];
    double sj[N * N * N];
    for (int c = 0; c < ncell && !st; c++) {
        body[c] = part_of[c];
        sj[c] = coons_volume_mesh_cell_scaled_jacobian(vm, (size_t)c, NULL);
        if (isnan(sj[c])) sj[c] = 0;
    }
    if (!st) st = coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "body", COONS_FIELD_INT32,
                                              body, &e);
    if (!st)
        st = coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "scaled_jacobian",
                                         COONS_FIELD_FLOAT64, sj, &e);
    /* Sets: per part, its cells, and its cells' faces on the cube's sides
     * (local face f lies on side f when the cell's lattice position touches
     * it; at a collapsed side the face is there, with repeated nodes). */
    for (int part = 0; part < 2 && !st; part++) {
        uint32_t items[N * N * N];
        size_t n = 0;
        for (int c = 0; c < ncell; c++)
            if (part_of[c] == part) items[n++] = (uint32_t)c;
        st = coons_volume_mesh_add_cell_set(vm, pname[part], items, n, &e);
        static const char *side[6] = {"u0", "u1", "v0", "v1", "w0", "w1"};
        for (int f = 0; f < 6 && !st; f++) {
            int axis = f / 2, hi = f % 2;
            uint32_t pairs[2 * N * N * N], nodes[N * N * N * 27];
            size_t np = 0, nnode = 0;
            for (int c = 0; c < ncell; c++) {
                if (part_of[c] != part) continue;
                int on = ijk[c][axis] == (hi ? N - 1 : 0);
                if (!on) continue;
                pairs[2 * np] = (uint32_t)c;
                pairs[2 * np + 1] = (uint32_t)f;
                np++;
                for (int q = 0; q < npc; q++) {
                    uint32_t v = cells[c][q];
                    int dup = 0;
                    for (size_t z = 0; z < nnode; z++) dup |= nodes[z] == v;
                    if (2 * hi == ref[q][axis] && !dup) nodes[nnode++] = v;
                }
            }
            char name[32];
            snprintf(name, sizeof name, "%s.%s", pname[part], side[f]);
            st = coons_volume_mesh_add_face_set(vm, name, pairs, np, &e);
            if (!st) st = coons_volume_mesh_add_node_set(vm, name, nodes, nnode, &e);
        }
    }
    coons_format fmt = COONS_FORMAT_AUTO;
    if (!st && argc == 5) st = coons_format_from_name(argv[4], &fmt, &e);
    if (!st) st = coons_volume_mesh_write(vm, argv[1], fmt, NULL, &e);
    coons_volume_mesh_free(vm);
    if (st) {
        fprintf(stderr, "vm_sample: %s\n", e.message);
        return 1;
    }
    return 0;
}
