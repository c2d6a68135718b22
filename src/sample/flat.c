/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Flat faces sampled by their boundary polygon (issue 14), and the pass
 * over a sampled body's faces that replaces the lattice triangles of its
 * flat faces and (ruled.c) of its ruled faces.
 *
 * Detection is measured, not read from the body's kind: a face is flat
 * when its lattice points and the points at thirds of every cell lie
 * within COONS__FLAT_EPS (relative to the body's extent) of the plane of its
 * vector area. On a cell where the face is polynomial of degree <= 3 in
 * each parameter (bilinear, bicubic Coons/B-spline faces; the lattice holds
 * the breakpoints), its distance to the plane is such a polynomial and
 * vanishes on the 4 x 4 samples, hence everywhere; for other faces the
 * adaptive sampler's own measurement already bounds the surface within the
 * tolerance of the cells, which lie in the plane. The face's image must
 * also be the region its boundary polygon bounds (the lattice does not fold
 * over itself): the polygon's area equals the lattice's vector area.
 *
 * Triangulation: the polygon mesher of delaunay.c (Delaunay refinement);
 * every result is checked and a face whose check fails keeps its lattice
 * triangles. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "coons_internal.h"
#include "delaunay.h"
#include "flat.h"
#include "ruled.h"
#include "union_find.h"

#define NONE UINT32_MAX
/* Normal components closer than this are the same (the frame's axis). */
#define FRAME_TIE 1e-9

/* ---- Faces of a sampled body ---------------------------------------- */

/* Is face f flat? n gets the unit normal of its (outward) triangles, o a
 * point of it. *flat = 0 on any doubt. */
static coons_status face_plane(sampler *s, int f, double n[3], double o[3], double *area2,
                               int *flat)
{
    const face_desc *F = &coons__faces[f];
    size_t na = s->n[F->a], nb = s->n[F->b];
    double N[3] = {0, 0, 0};
    *flat = 0;
    size_t t0 = s->face_tri[f], t1 = s->face_tri[f + 1];
    if (t0 == t1) return COONS_OK;
    v3_copy(o, s->pos + 3 * (size_t)s->tri[3 * t0]);
    for (size_t t = t0; t < t1; t++) {
        double a[3], b[3], c[3];
        v3_sub(a, s->pos + 3 * (size_t)s->tri[3 * t + 1], s->pos + 3 * (size_t)s->tri[3 * t]);
        v3_sub(b, s->pos + 3 * (size_t)s->tri[3 * t + 2], s->pos + 3 * (size_t)s->tri[3 * t]);
        v3_cross(c, a, b);
        v3_add(N, N, c);
    }
    double len = v3_norm(N);
    if (!(len > 1e-6)) return COONS_OK; /* a sliver or a face shrunk to a curve */
    *area2 = len;
    v3_scale(n, N, 1.0 / len);
    for (size_t ia = 0; ia <= na; ia++)
        for (size_t ib = 0; ib <= nb; ib++) {
            double q[3];
            v3_sub(q, s->pos + 3 * (size_t)coons__uf_find(s->uf, coons__sampler_id(s, f, ia, ib)), o);
            if (!(fabs(v3_dot(q, n)) <= COONS__FLAT_EPS)) return COONS_OK;
        }
    /* Thirds of every cell, a row of samples at a time. */
    size_t nbs = 3 * nb + 1;
    double *bv = coons__malloc_array(nbs, sizeof(double));
    double *row = coons__malloc_array(nbs, 3 * sizeof(double));
    if (!bv || !row) {
        coons__free(bv);
        coons__free(row);
        return coons__error_nomem(s->err);
    }
    const double *ta = s->t[F->a], *tb = s->t[F->b];
    for (size_t q = 0; q < nb; q++)
        for (int j = 0; j < 3; j++) bv[3 * q + (size_t)j] = tb[q] + (tb[q + 1] - tb[q]) * j / 3.0;
    bv[3 * nb] = tb[nb];
    coons_status st = COONS_OK;
    int ok = 1;
    for (size_t i = 0; i <= 3 * na && ok && !st; i++) {
        size_t p = i / 3;
        double av = p < na ? ta[p] + (ta[p + 1] - ta[p]) * (double)(i % 3) / 3.0 : ta[na];
        const double *qv[3];
        size_t c[3];
        qv[F->fixed] = &F->val;
        c[F->fixed] = 1;
        qv[F->a] = &av;
        c[F->a] = 1;
        qv[F->b] = bv;
        c[F->b] = nbs;
        st = coons_body_eval_grid(s->body, qv[0], c[0], qv[1], c[1], qv[2], c[2], row, s->err);
        for (size_t j = 0; j < nbs && !st && ok; j++) {
            double x[3];
            v3_scale(x, row + 3 * j, s->scale);
            v3_sub(x, x, o);
            if (!(fabs(v3_dot(x, n)) <= COONS__FLAT_EPS)) ok = 0;
        }
    }
    coons__free(bv);
    coons__free(row);
    *flat = ok && !st;
    return st;
}

/* The face's boundary ring of representative vertices, without repeats
 * of collapsed edges; *m = 0 when a vertex comes back (a pinched face). */
static coons_status face_ring(sampler *s, int f, unsigned char *seen, uint32_t **ring, size_t *m)
{
    const face_desc *F = &coons__faces[f];
    size_t na = s->n[F->a], nb = s->n[F->b], k = 0;
    *m = 0;
    uint32_t *r = coons__malloc_array(2 * (na + nb), sizeof(uint32_t));
    if (!r) return coons__error_nomem(s->err);
    for (size_t i = 0; i < 2 * (na + nb); i++) {
        size_t ia, ib;
        if (i < na) ia = i, ib = 0;
        else if (i < na + nb) ia = na, ib = i - na;
        else if (i < 2 * na + nb) ia = 2 * na + nb - i, ib = nb;
        else ia = 0, ib = 2 * (na + nb) - i;
        uint32_t v = coons__uf_find(s->uf, coons__sampler_id(s, f, ia, ib));
        if (k && r[k - 1] == v) continue;
        r[k++] = v;
    }
    while (k > 1 && r[k - 1] == r[0]) k--;
    int pinched = 0;
    for (size_t i = 0; i < k; i++) {
        if (seen[r[i]]) pinched = 1;
        seen[r[i]] = 1;
    }
    for (size_t i = 0; i < k; i++) seen[r[i]] = 0;
    *ring = r;
    *m = pinched || k < 3 ? 0 : k;
    return COONS_OK;
}


/* ---- Parameters of the Steiner points -------------------------------- */

/* The face's parameters (a, b) of the point p of its plane: the lattice
 * triangle of face f (in the plane, 2-D points xy of its lattice points)
 * holding p, found by a walk over the lattice cells from `*cell`, gives
 * them by barycentric interpolation, exact where the face is affine;
 * Newton's method on the body's map (its Jacobian) then solves
 * F(a, b) = p to rounding. *found = 0 when it does not converge. */
static void locate_params(sampler *s, int f, const double *xy, double sigma, const double p[2],
                          const double o[3], const double e1[3], const double e2[3],
                          const double n[3], size_t *cell, double ab[2], int *found)
{
    const face_desc *F = &coons__faces[f];
    size_t na = s->n[F->a], nb = s->n[F->b], cp = *cell / nb, cq = *cell % nb;
    const double *ta = s->t[F->a], *tb = s->t[F->b];
    double best = -INFINITY;
    *found = 0;
    ab[0] = ab[1] = 0.5;
    for (size_t step = 0, limit = 2 * (na + nb) + 8; step < limit; step++) {
        /* The cell's two triangles: barycentric coordinates of p. */
        for (int k = 0; k < 2; k++) {
            size_t ia[3], ib[3];
            coons__cell_tri(cp, cq, s->diag[f][cp * nb + cq], k, ia, ib);
            const double *c[3];
            for (int j = 0; j < 3; j++) c[j] = xy + 2 * (ia[j] * (nb + 1) + ib[j]);
            double ar = coons__orient2(c[0], c[1], c[2]);
            if (!(fabs(ar) > 0)) continue; /* collapsed */
            double l[3] = {coons__orient2(c[1], c[2], p) / ar, coons__orient2(c[2], c[0], p) / ar,
                           coons__orient2(c[0], c[1], p) / ar};
            double mn = fmin(l[0], fmin(l[1], l[2]));
            if (mn > best) {
                best = mn;
                ab[0] = ab[1] = 0;
                for (int j = 0; j < 3; j++) {
                    ab[0] += l[j] * ta[ia[j]];
                    ab[1] += l[j] * tb[ib[j]];
                }
                *cell = cp * nb + cq;
            }
        }
        if (best >= -1e-9) break;
        /* Out of the cell: across an edge that p lies beyond (the cell
         * runs A B C D counter-clockwise when sigma > 0). */
        const double *A = xy + 2 * (cp * (nb + 1) + cq), *B = xy + 2 * ((cp + 1) * (nb + 1) + cq);
        const double *C = B + 2, *D = A + 2;
        const double *ed[4][2] = {{A, B}, {B, C}, {C, D}, {D, A}};
        int ok[4] = {cq > 0, cp + 1 < na, cq + 1 < nb, cp > 0}, moved = 0;
        for (int j = 0; j < 4 && !moved; j++) {
            int k = (int)((step + (size_t)j) % 4);
            if (!ok[k] || !(sigma * coons__orient2(ed[k][0], ed[k][1], p) < 0)) continue;
            if (k == 0) cq--;
            else if (k == 1) cp++;
            else if (k == 2) cq++;
            else cp--;
            moved = 1;
        }
        if (!moved) break;
    }
    double P3[3];
    v3_copy(P3, o);
    v3_axpy(P3, p[0], e1);
    v3_axpy(P3, p[1], e2);
    double a = fmin(1, fmax(0, ab[0])), b = fmin(1, fmax(0, ab[1]));
    for (int it = 0; it < 40; it++) {
        double q[3], x[3], jac[3][3], d[3], xa[3], xb[3];
        q[F->fixed] = F->val;
        q[F->a] = a;
        q[F->b] = b;
        coons_body_eval_jacobian(s->body, q[0], q[1], q[2], x, jac);
        v3_scale(x, x, s->scale);
        v3_sub(d, x, P3);
        double r1 = v3_dot(d, e1), r2 = v3_dot(d, e2);
        if (hypot(r1, r2) <= 4e-14 && fabs(v3_dot(d, n)) <= COONS__FLAT_EPS) {
            ab[0] = a;
            ab[1] = b;
            *found = 1;
            return;
        }
        for (int r = 0; r < 3; r++) {
            xa[r] = jac[r][F->a] * s->scale;
            xb[r] = jac[r][F->b] * s->scale;
        }
        double j11 = v3_dot(e1, xa), j12 = v3_dot(e1, xb), j21 = v3_dot(e2, xa),
               j22 = v3_dot(e2, xb), det = j11 * j22 - j12 * j21;
        if (!(fabs(det) > 0) || !isfinite(det)) return;
        a = fmin(1, fmax(0, a - (j22 * r1 - j12 * r2) / det));
        b = fmin(1, fmax(0, b - (j11 * r2 - j21 * r1) / det));
    }
}

/* Parameters (u, v, w) of the np points pts (2-D, in the frame o, e1, e2
 * of flat face f) into uvw (3 each). *ok = 0 when the face's lattice folds
 * over itself in the plane (its triangles' areas do not all have one
 * sign) or a point's parameters are not found: the face keeps its
 * lattice. Locating a point is a walk from the cell whose centre lies in
 * its bucket of a uniform grid over the face (O(1) cells for a lattice of
 * cells of similar sizes; from the last point's cell otherwise). */
static coons_status steiner_params(sampler *s, int f, const double o[3], const double e1[3],
                                   const double e2[3], const double n[3], const double *pts,
                                   size_t np, double *uvw, int *ok)
{
    const face_desc *F = &coons__faces[f];
    size_t na = s->n[F->a], nb = s->n[F->b], nq = (na + 1) * (nb + 1), nc = na * nb;
    *ok = 0;
    size_t K = (size_t)ceil(sqrt((double)nc));
    double *xy = coons__malloc_array(nq, 2 * sizeof(double));
    uint32_t *bucket = coons__malloc_array(K * K, sizeof(uint32_t));
    if (!xy || !bucket) {
        coons__free(xy);
        coons__free(bucket);
        return coons__error_nomem(s->err);
    }
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t ia = 0; ia <= na; ia++)
        for (size_t ib = 0; ib <= nb; ib++) {
            double q[3], *c = xy + 2 * (ia * (nb + 1) + ib);
            v3_sub(q, s->pos + 3 * (size_t)coons__uf_find(s->uf, coons__sampler_id(s, f, ia, ib)),
                   o);
            c[0] = v3_dot(q, e1);
            c[1] = v3_dot(q, e2);
            for (int d = 0; d < 2; d++) lo[d] = fmin(lo[d], c[d]), hi[d] = fmax(hi[d], c[d]);
        }
    /* No fold: the areas of the lattice triangles all of one sign. */
    double sum = 0, sabs = 0;
    for (size_t p = 0; p < na; p++)
        for (size_t q = 0; q < nb; q++)
            for (int k = 0; k < 2; k++) {
                size_t ia[3], ib[3];
                coons__cell_tri(p, q, s->diag[f][p * nb + q], k, ia, ib);
                double ar = coons__orient2(xy + 2 * (ia[0] * (nb + 1) + ib[0]),
                                    xy + 2 * (ia[1] * (nb + 1) + ib[1]),
                                    xy + 2 * (ia[2] * (nb + 1) + ib[2]));
                sum += ar;
                sabs += fabs(ar);
            }
    int good = fabs(sum) > 0 && sabs <= fabs(sum) * (1 + 1e-9);
    double sigma = sum > 0 ? 1 : -1;
    double w0 = (hi[0] - lo[0]) / (double)K, w1 = (hi[1] - lo[1]) / (double)K;
    size_t K1 = K - 1;
#define BUCKET(x, y)                                                                          \
    (fmin((double)K1, fmax(0, floor(((x) - lo[0]) / w0))) +                                   \
     (double)K * fmin((double)K1, fmax(0, floor(((y) - lo[1]) / w1))))
    for (size_t i = 0; i < K * K; i++) bucket[i] = NONE;
    if (good && w0 > 0 && w1 > 0)
        for (size_t p = 0; p < na; p++)
            for (size_t q = 0; q < nb; q++) {
                const double *A = xy + 2 * (p * (nb + 1) + q), *C = xy + 2 * ((p + 1) * (nb + 1) + q + 1);
                bucket[(size_t)BUCKET(0.5 * (A[0] + C[0]), 0.5 * (A[1] + C[1]))] =
                    (uint32_t)(p * nb + q);
            }
    size_t cell = 0;
    for (size_t i = 0; i < np && good; i++) {
        const double *p = pts + 2 * i;
        if (w0 > 0 && w1 > 0) {
            uint32_t c = bucket[(size_t)BUCKET(p[0], p[1])];
            if (c != NONE) cell = c;
        }
        double ab[2];
        int found;
        locate_params(s, f, xy, sigma, p, o, e1, e2, n, &cell, ab, &found);
        if (!found) good = 0;
        double *q = uvw + 3 * i;
        q[F->fixed] = F->val;
        q[F->a] = ab[0];
        q[F->b] = ab[1];
    }
#undef BUCKET
    coons__free(xy);
    coons__free(bucket);
    *ok = good;
    return COONS_OK;
}

coons_status coons__flat_faces(sampler *s)
{
    /* Morph bodies keep the lattice: all their frames share one mesh
     * topology (the OpenSCAD animation, scad_morph.c). */
    coons__free(s->flat_uvw);
    s->flat_uvw = NULL;
    s->flat_v0 = s->nv;
    s->flat_faces = s->ruled_faces = 0;
    if (s->o->flags & COONS__SAMPLE_LATTICE_FACES || !s->nt ||
        coons_body_kind(s->body) == COONS_BODY_MORPH)
        return COONS_OK;
    uint32_t *ftri[6] = {NULL};
    size_t fnt[6] = {0}, ns = 0, scap = 0;
    int flat[6] = {0};
    double *spos = NULL, *suvw = NULL;
    coons_status st = COONS_OK;
    unsigned char *seen = coons__calloc(s->nv, 1);
    if (!seen) return coons__error_nomem(s->err);
    for (int f = 0; f < 6 && !st; f++) {
        if (s->glued & 1 << coons__faces[f].fixed || s->skip & 1u << f) continue;
        double n[3], o[3], area2 = 0;
        int is_flat;
        if ((st = face_plane(s, f, n, o, &area2, &is_flat)) || !is_flat) continue;
        uint32_t *ring = NULL;
        size_t m;
        if ((st = face_ring(s, f, seen, &ring, &m)) || !m) {
            coons__free(ring);
            continue;
        }
        /* A frame (e1, e2, n), e1 from the axis least along n (exact for
         * faces normal to an axis). Components within FRAME_TIE of each
         * other (n is a unit vector) are a tie, broken by the lower axis:
         * rounding, which differs at each scale of the model, must not
         * turn the frame (the mesher's order follows it). */
        int ax = 0;
        for (int d = 1; d < 3; d++)
            if (fabs(n[d]) < fabs(n[ax]) - FRAME_TIE) ax = d;
        double u[3] = {0, 0, 0}, e1[3], e2[3];
        u[ax] = 1;
        v3_cross(e1, n, u);
        v3_scale(e1, e1, 1.0 / v3_norm(e1));
        v3_cross(e2, n, e1);
        double *xy = coons__malloc_array(m, 2 * sizeof(double));
        if (!xy) {
            coons__free(ring);
            st = coons__error_nomem(s->err);
            break;
        }
        double a2 = 0;
        for (size_t i = 0; i < m; i++) {
            double q[3];
            v3_sub(q, s->pos + 3 * (size_t)ring[i], o);
            xy[2 * i] = v3_dot(q, e1);
            xy[2 * i + 1] = v3_dot(q, e2);
        }
        for (size_t i = 0; i < m; i++) {
            const double *a = xy + 2 * i, *b = xy + 2 * ((i + 1) % m);
            a2 += a[0] * b[1] - a[1] * b[0];
        }
        if (a2 < 0) { /* the ring runs clockwise seen from outside */
            for (size_t i = 0, j = m - 1; i < j; i++, j--) {
                uint32_t x = ring[i];
                ring[i] = ring[j];
                ring[j] = x;
                for (size_t c = 0; c < 2; c++) {
                    double y = xy[2 * i + c];
                    xy[2 * i + c] = xy[2 * j + c];
                    xy[2 * j + c] = y;
                }
            }
        }
        /* The lattice covers the polygon once (no fold): equal areas. */
        double *pts = NULL;
        uint32_t *tri = NULL;
        size_t np = 0, nt = 0;
        int ok = 0;
        if (fabs(fabs(a2) - area2) <= 1e3 * COONS__FLAT_EPS * area2)
            st = coons__polygon_mesh(xy, m, COONS__FLAT_MIN_ANGLE, &pts, &np, &tri, &nt, &ok,
                                     s->err);
        coons__free(xy);
        if (!st && ok && ns + np + s->nv > UINT32_MAX) ok = 0;
        /* Only where it saves triangles: a coarse face whose lattice cells
         * are long keeps them rather than gain Steiner points. */
        if (!st && ok && nt >= s->face_tri[f + 1] - s->face_tri[f]) ok = 0;
        if (!st && ok && np) {
            size_t need = 3 * (ns + np);
            if (need > scap) {
                size_t c = scap ? scap : 48;
                while (c < need) c *= 2;
                double *q = coons__realloc(spos, c * sizeof(double));
                if (q) spos = q;
                double *r = q ? coons__realloc(suvw, c * sizeof(double)) : NULL;
                if (r) suvw = r;
                if (!q || !r) st = coons__error_nomem(s->err);
                else scap = c;
            }
        }
        /* The Steiner points' parameters: with them, the isoparametric
         * output (which keeps every vertex's (u,v,w)) meshes flat faces
         * as the boundary does; a face whose points have none keeps its
         * lattice, whether parameters are asked for or not. */
        if (!st && ok && np)
            st = steiner_params(s, f, o, e1, e2, n, pts, np, suvw + 3 * ns, &ok);
        if (!st && ok) {
            for (size_t i = 0; i < np; i++) {
                double *q = spos + 3 * (ns + i);
                v3_copy(q, o);
                v3_axpy(q, pts[2 * i], e1);
                v3_axpy(q, pts[2 * i + 1], e2);
            }
            for (size_t i = 0; i < 3 * nt; i++)
                tri[i] = tri[i] < m ? ring[tri[i]] : (uint32_t)(s->nv + ns + (tri[i] - m));
            ns += np;
            ftri[f] = tri;
            fnt[f] = nt;
            flat[f] = 1;
            tri = NULL;
        }
        coons__free(pts);
        coons__free(tri);
        coons__free(ring);
    }
    coons__free(seen);
    /* Faces ruled between two straight lines (not flat): strips (ruled.c). */
    unsigned ruled_bits = 0;
    double ruled_dev = 0;
    if (!st) st = coons__ruled_faces(s, flat, ftri, fnt, &ruled_bits, &ruled_dev);
    /* The new mesh: lattice triangles of the other faces, in face order. */
    size_t total = 0;
    int any = 0;
    for (int f = 0; f < 6; f++) {
        total += flat[f] ? fnt[f] : s->face_tri[f + 1] - s->face_tri[f];
        any |= flat[f];
    }
    uint32_t *tri = NULL;
    if (!st && any) {
        tri = coons__malloc_array(total, 3 * sizeof(uint32_t));
        double *pos = coons__realloc(s->pos, (s->nv + ns) * 3 * sizeof(double));
        if (pos) s->pos = pos;
        uint32_t *uf = coons__realloc(s->uf, (s->nv + ns) * sizeof(uint32_t));
        if (uf) s->uf = uf;
        unsigned char *ev = coons__realloc(s->evaluated, s->nv + ns);
        if (ev) s->evaluated = ev;
        if (!tri || !pos || !uf || !ev) st = coons__error_nomem(s->err);
    }
    if (!st && any) {
        size_t k = 0, face_tri[7];
        for (int f = 0; f < 6; f++) {
            face_tri[f] = k;
            if (flat[f]) {
                if (fnt[f]) memcpy(tri + 3 * k, ftri[f], 3 * fnt[f] * sizeof(uint32_t));
                k += fnt[f];
            } else {
                size_t c = s->face_tri[f + 1] - s->face_tri[f];
                if (c) memcpy(tri + 3 * k, s->tri + 3 * s->face_tri[f], 3 * c * sizeof(uint32_t));
                k += c;
            }
        }
        face_tri[6] = k;
        memcpy(s->face_tri, face_tri, sizeof face_tri);
        if (ns) memcpy(s->pos + 3 * s->nv, spos, 3 * ns * sizeof(double));
        s->flat_uvw = suvw; /* 3 ns: raw vertices s->nv .. s->nv + ns - 1 */
        suvw = NULL;
        for (size_t i = 0; i < ns; i++) {
            s->uf[s->nv + i] = (uint32_t)(s->nv + i);
            s->evaluated[s->nv + i] = 1;
        }
        s->nv += ns;
        coons__free(s->tri);
        s->tri = tri;
        s->nt = k;
        s->flat_faces = 0;
        for (int f = 0; f < 6; f++) s->flat_faces |= (unsigned)flat[f] << f;
        s->flat_faces &= ~ruled_bits;
        s->ruled_faces = ruled_bits;
        if (s->measured) s->dev = fmax(s->dev, ruled_dev);
        tri = NULL;
    }
    coons__free(tri);
    coons__free(spos);
    coons__free(suvw);
    for (int f = 0; f < 6; f++) coons__free(ftri[f]);
    return st;
}
