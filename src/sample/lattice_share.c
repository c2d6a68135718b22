/* SPDX-License-Identifier: GPL-3.0-or-later */
/* One lattice per direction class of a control lattice (seed 000 §3: "each
 * cell of the control lattice ... defines a Coons body", neighbouring cells
 * share faces). A face shared by bodies A and B ties its two parameter
 * directions in A to two directions in B, each in the same or the opposite
 * sense (coons__shared_face's sym). The directions tied this way, over all
 * shared faces, form classes (union-find with a parity bit per member: its
 * sense relative to the class root), and every member of a class gets the
 * union of the members' values, each in its own sense; so every body's
 * lattice is refined, never coarsened, and a shared face has the same
 * lattice points seen from both sides, like Gmsh's transfinite constraints
 * propagating through shared surfaces. A class tied to itself in the
 * opposite sense (a ring of cells closed with a flip) gets a lattice
 * symmetric about 1/2. Further ties of single directions (bodies that meet
 * only along a whole edge, coons__share_lattices_tied()) join classes the
 * same way. Work is linear in the bodies' lattice sizes (plus a
 * sort per class), never in the number of pairs of bodies. */
#include <stdlib.h>

#include "coons_internal.h"
#include "sampling.h"

/* Root of x with path compression; *parity gets x's sense relative to it. */
static size_t pfind(size_t *up, unsigned char *par, size_t x, int *parity)
{
    size_t r = x;
    int p = 0;
    while (up[r] != r) {
        p ^= par[r];
        r = up[r];
    }
    *parity = p;
    /* Compress: every node on the path points at r with its own parity. */
    int q = p;
    while (up[x] != r && up[x] != x) {
        size_t next = up[x];
        int pn = q ^ par[x];
        up[x] = r;
        par[x] = (unsigned char)q;
        x = next;
        q = pn;
    }
    return r;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static int same_values(const double *a, size_t na, const double *b, size_t nb)
{
    if (na != nb) return 0;
    for (size_t i = 0; i <= na; i++)
        if (a[i] != b[i]) return 0;
    return 1;
}

/* Ties directions x and y (y in the opposite sense when flip). */
static void tie(size_t *up, unsigned char *par, size_t *size, unsigned char *sym, size_t x,
                size_t y, int flip)
{
    int pa, pb;
    size_t ra = pfind(up, par, x, &pa), rb = pfind(up, par, y, &pb);
    int rel = pa ^ pb ^ flip;
    if (ra == rb) {
        if (rel) sym[ra] = 1; /* tied both ways: the lattice is symmetric */
        return;
    }
    if (size[ra] < size[rb]) { /* union by size keeps the paths short */
        size_t tmp = ra;
        ra = rb;
        rb = tmp;
    }
    up[rb] = ra;
    par[rb] = (unsigned char)rel;
    size[ra] += size[rb];
    sym[ra] |= sym[rb];
}

coons_status coons__share_lattices(size_t nb, double **t, size_t *n,
                                   const coons__shared_face *sf, size_t nsf, int *changed,
                                   coons_error *err)
{
    return coons__share_lattices_tied(nb, t, n, sf, nsf, NULL, 0, changed, err);
}

coons_status coons__share_lattices_tied(size_t nb, double **t, size_t *n,
                                        const coons__shared_face *sf, size_t nsf,
                                        const coons__lattice_tie *ties, size_t nties,
                                        int *changed, coons_error *err)
{
    if (changed) *changed = 0;
    if (nb < 2 || (!nsf && !nties)) return COONS_OK;
    size_t nd = 3 * nb;
    size_t *up = coons__malloc_array(nd, sizeof *up);
    size_t *size = coons__malloc_array(nd, sizeof *size);
    size_t *root = coons__malloc_array(nd, sizeof *root);
    size_t *first = coons__malloc_array(nd + 1, sizeof *first);
    size_t *member = coons__malloc_array(nd, sizeof *member);
    unsigned char *par = coons__calloc(nd, 1), *sym = coons__calloc(nd, 1);
    unsigned char *rpar = coons__calloc(nd, 1);
    double *all = NULL;
    coons_status st = COONS_OK;
    if (!up || !size || !root || !first || !member || !par || !sym || !rpar) {
        st = coons__error_nomem(err);
        goto done;
    }
    for (size_t x = 0; x < nd; x++) up[x] = x, size[x] = 1;
    for (size_t k = 0; k < nsf; k++) {
        int f0, a0, b0, f1, a1, b1, s = sf[k].sym;
        coons__face_axes(sf[k].face[0], &f0, &a0, &b0);
        coons__face_axes(sf[k].face[1], &f1, &a1, &b1);
        int swap = (s & COONS__SYM_SWAP) != 0;
        size_t from[2] = {3 * sf[k].body[0] + (size_t)a0, 3 * sf[k].body[0] + (size_t)b0};
        size_t to[2] = {3 * sf[k].body[1] + (size_t)(swap ? b1 : a1),
                        3 * sf[k].body[1] + (size_t)(swap ? a1 : b1)};
        int flip[2] = {(s & (swap ? COONS__SYM_FLIP_B : COONS__SYM_FLIP_A)) != 0,
                       (s & (swap ? COONS__SYM_FLIP_A : COONS__SYM_FLIP_B)) != 0};
        for (int e = 0; e < 2; e++) tie(up, par, size, sym, from[e], to[e], flip[e]);
    }
    for (size_t k = 0; k < nties; k++) tie(up, par, size, sym, ties[k].x, ties[k].y, ties[k].flip);
    /* Members grouped by root (a counting sort), each with its parity. */
    for (size_t x = 0; x <= nd; x++) first[x] = 0;
    for (size_t x = 0; x < nd; x++) {
        int p;
        root[x] = pfind(up, par, x, &p);
        rpar[x] = (unsigned char)p;
        first[root[x] + 1]++;
    }
    for (size_t x = 0; x < nd; x++) first[x + 1] += first[x];
    for (size_t x = 0; x < nd; x++) size[x] = first[x]; /* reused: fill cursor */
    for (size_t x = 0; x < nd; x++) member[size[root[x]]++] = x;
    size_t cap = 0;
    for (size_t r = 0; r < nd && !st; r++) {
        size_t m0 = first[r], m1 = first[r + 1];
        if (m1 - m0 < 2 && !(m1 > m0 && sym[r])) continue;
        size_t total = 0;
        for (size_t i = m0; i < m1; i++) total += n[member[i]] + 1;
        if (2 * total > cap) {
            coons__free(all);
            cap = 2 * total;
            all = coons__malloc_array(cap, sizeof(double));
            if (!all) {
                st = coons__error_nomem(err);
                break;
            }
        }
        size_t k = 0;
        for (size_t i = m0; i < m1; i++) {
            size_t x = member[i];
            int p = rpar[x];
            for (size_t j = 0; j <= n[x]; j++) {
                double v = t[x][j];
                all[k++] = p ? 1.0 - v : v;
                if (sym[r]) all[k++] = p ? v : 1.0 - v;
            }
        }
        qsort(all, k, sizeof(double), cmp_double);
        size_t m = 0;
        for (size_t i = 0; i < k; i++)
            if (m == 0 || all[i] - all[m - 1] > 1e-12) all[m++] = all[i];
        all[0] = 0.0;
        all[m - 1] = 1.0;
        for (size_t i = m0; i < m1; i++) {
            size_t x = member[i];
            double *v = coons__malloc_array(m, sizeof(double));
            if (!v) {
                st = coons__error_nomem(err);
                break;
            }
            int p = rpar[x];
            for (size_t j = 0; j < m; j++) v[j] = p ? 1.0 - all[m - 1 - j] : all[j];
            v[0] = 0.0;
            v[m - 1] = 1.0;
            if (changed && !same_values(v, m - 1, t[x], n[x])) *changed = 1;
            coons__free(t[x]);
            t[x] = v;
            n[x] = m - 1;
        }
    }
done:
    coons__free(all);
    coons__free(up);
    coons__free(size);
    coons__free(root);
    coons__free(first);
    coons__free(member);
    coons__free(par);
    coons__free(sym);
    coons__free(rpar);
    return st;
}
