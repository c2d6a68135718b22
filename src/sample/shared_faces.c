/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Faces shared by two bodies (coons-model(5), "Bodies that share faces";
 * seed 000 section 3: neighbouring cells of a control lattice share faces):
 * a face of one body and a face of another that are the same map up to one
 * of the 8 symmetries of the unit square, pointwise within the consistency
 * tolerance, whatever produced them.
 *
 * Candidates are found by the face's centre point F(1/2, 1/2), which every
 * symmetry of the square keeps: centres go into a hash grid of cell size
 * 2 tol, and only faces whose centres lie within tol of each other are
 * compared, on a 5 x 5 grid of parameters (corners, edge midpoints, the
 * centre and the quarter points) in each of the 8 orientations. */
#include <string.h>

#include "coons_internal.h"
#include "sampling.h"

#define G 5 /* samples per face direction */

/* The two parameter directions of body face f (u0 u1 v0 v1 w0 w1): the
 * other two axes in increasing order, as the sampler's faces. */
void coons__face_axes(int f, int *fixed, int *a, int *b)
{
    int ax = f / 2;
    *fixed = ax;
    *a = ax == 0 ? 1 : 0;
    *b = ax == 2 ? 1 : 2;
}

/* The face's G x G samples, by the body's grid evaluation (one basis
 * per direction, not one evaluation per point). */
static coons_status face_grid(const coons_body *b, int f, double out[G][G][3], coons_error *err)
{
    int ax, da, db;
    coons__face_axes(f, &ax, &da, &db);
    double g[G], fixed = (double)(f % 2);
    for (int i = 0; i < G; i++) g[i] = (double)i / (G - 1);
    const double *q[3];
    size_t c[3];
    q[ax] = &fixed;
    c[ax] = 1;
    q[da] = g;
    c[da] = G;
    q[db] = g;
    c[db] = G;
    /* u slowest: with the fixed axis of count 1, the order is (a, b). */
    return coons_body_eval_grid(b, q[0], c[0], q[1], c[1], q[2], c[2], &out[0][0][0], err);
}

/* Index (i', j') on the second face of sample (i, j) of the first under
 * symmetry `sym` (COONS__SYM_*). */
static void sym_index(int sym, int i, int j, int *io, int *jo)
{
    int a = (sym & COONS__SYM_SWAP) ? j : i, b = (sym & COONS__SYM_SWAP) ? i : j;
    if (sym & COONS__SYM_FLIP_A) a = G - 1 - a;
    if (sym & COONS__SYM_FLIP_B) b = G - 1 - b;
    *io = a;
    *jo = b;
}

static int close3(const double *p, const double *q, double tol)
{
    return fabs(p[0] - q[0]) <= tol && fabs(p[1] - q[1]) <= tol && fabs(p[2] - q[2]) <= tol;
}

typedef struct fslot {
    int64_t key[3];
    uint32_t head; /* first face in the chain, UINT32_MAX: empty */
} fslot;

static size_t fhash(const fslot *t, size_t cap, const int64_t k[3])
{
    uint64_t x = (uint64_t)k[0] * 0x9E3779B97F4A7C15ull ^ (uint64_t)k[1] * 0xC2B2AE3D27D4EB4Full ^
                 (uint64_t)k[2] * 0x165667B19E3779F9ull;
    x ^= x >> 31;
    size_t s = (size_t)x & (cap - 1);
    while (t[s].head != UINT32_MAX &&
           (t[s].key[0] != k[0] || t[s].key[1] != k[1] || t[s].key[2] != k[2]))
        s = (s + 1) & (cap - 1);
    return s;
}

coons_status coons__find_shared_faces(const coons_body *const *bodies, size_t nb, double tol,
                                      coons__shared_face **out, size_t *count,
                                      coons_error *err)
{
    *out = NULL;
    *count = 0;
    if (nb < 2) return COONS_OK;
    if (nb > (UINT32_MAX - 1) / 6)
        return coons__error_set(err, COONS_E_LIMIT, "too many bodies (%zu)", nb);
    size_t nf = 6 * nb;
    double(*grid)[G][G][3] = coons__malloc_array(nf, sizeof *grid);
    uint32_t *next = coons__malloc_array(nf, sizeof(uint32_t));
    unsigned char *used = coons__calloc(nf, 1);
    size_t cap = 16;
    while (cap < 2 * nf) cap *= 2;
    fslot *tab = coons__malloc_array(cap, sizeof *tab);
    coons__shared_face *res = coons__malloc_array(nf / 2 + 1, sizeof *res);
    coons_status st = COONS_OK;
    if (!grid || !next || !used || !tab || !res) {
        st = coons__error_nomem(err);
        goto done;
    }
    for (size_t s = 0; s < cap; s++) tab[s].head = UINT32_MAX;
    double lo[3] = {INFINITY, INFINITY, INFINITY};
    for (size_t i = 0; i < nf; i++) {
        if ((st = face_grid(bodies[i / 6], (int)(i % 6), grid[i], err))) goto done;
        const double *c = grid[i][G / 2][G / 2];
        for (int d = 0; d < 3; d++) lo[d] = c[d] < lo[d] ? c[d] : lo[d];
    }
    double inv = 1.0 / (2 * (tol > 0 ? tol : 1e-300));
    size_t n = 0;
    for (size_t i = 0; i < nf; i++) {
        const double *c = grid[i][G / 2][G / 2];
        int64_t k[3];
        for (int d = 0; d < 3; d++) k[d] = (int64_t)floor((c[d] - lo[d]) * inv);
        for (int dx = -1; dx <= 1 && !used[i]; dx++)
            for (int dy = -1; dy <= 1 && !used[i]; dy++)
                for (int dz = -1; dz <= 1 && !used[i]; dz++) {
                    int64_t q[3] = {k[0] + dx, k[1] + dy, k[2] + dz};
                    size_t s = fhash(tab, cap, q);
                    for (uint32_t o = tab[s].head; o != UINT32_MAX && !used[i]; o = next[o]) {
                        if (used[o] || o / 6 == i / 6) continue;
                        for (int sym = 0; sym < 8; sym++) {
                            int same = 1;
                            for (int a = 0; a < G && same; a++)
                                for (int b = 0; b < G && same; b++) {
                                    int ao, bo;
                                    sym_index(sym, a, b, &ao, &bo);
                                    same = close3(grid[o][a][b], grid[i][ao][bo], tol);
                                }
                            if (!same) continue;
                            res[n].body[0] = o / 6;
                            res[n].face[0] = (int)(o % 6);
                            res[n].body[1] = i / 6;
                            res[n].face[1] = (int)(i % 6);
                            res[n].sym = sym;
                            n++;
                            used[o] = used[i] = 1;
                            break;
                        }
                    }
                }
        size_t s = fhash(tab, cap, k);
        if (tab[s].head == UINT32_MAX) memcpy(tab[s].key, k, sizeof k);
        next[i] = tab[s].head;
        tab[s].head = (uint32_t)i;
    }
    *out = res;
    *count = n;
    res = NULL;
done:
    coons__free(grid);
    coons__free(next);
    coons__free(used);
    coons__free(tab);
    coons__free(res);
    return st;
}
