/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Pinches split (pinch.h). A repaired fold whose two sheets touch along a
 * curve, or two solids of a union that touch along an edge or at a point,
 * come out of the repair closed but pinched: edges of four (2k) triangles,
 * vertices whose triangles form several fans. Slicers and OpenSCAD's
 * Booleans refuse such a mesh; the same solid written with the pinch
 * edges and vertices doubled (the copies a hair apart) is a 2-manifold.
 *
 * Per part: every triangle edge is a slot; slots are grouped by edge. An
 * edge of two triangles joins them. An edge of 2k > 2 triangles, k each
 * way, is split: its triangles are sorted by the angle of their third
 * vertex around the edge (axis lo -> hi), and each triangle running the
 * edge lo -> hi, whose outward normal turns towards increasing angle, is
 * joined to the one before it (running hi -> lo): between the two lies
 * solid. (A part of negative volume is oriented inward: the rule turns.)
 * Then the corners of each vertex are grouped by the joins (union-find over
 * corners: a join of two triangles along an edge joins their corners at
 * both ends); each group is one fan and gets its own copy of the vertex.
 * The copies are then moved apart, each into its own solid (separate()),
 * by far less than any tolerance: with equal coordinates every STL reader
 * and OpenSCAD's Booleans (which snap to a 2^-20 grid) would weld them and
 * see the pinch again. Nothing else moves.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "coons_internal.h"
#include "mesh_impl.h"
#include "pinch.h"
#include "union_find.h"

typedef struct slot {
    uint32_t lo, hi; /* undirected edge key (global vertex indices) */
    uint32_t c;      /* the slot's triangle edge: 3 * local triangle + k, k -> k+1 */
} slot;

typedef struct around {
    double angle;
    uint32_t c;  /* slot */
    int fwd;     /* runs lo -> hi */
} around;

static int cmp_slot(const void *x, const void *y)
{
    const slot *a = x, *b = y;
    if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
    return a->c < b->c ? -1 : (a->c > b->c);
}

static int cmp_around(const void *x, const void *y)
{
    const around *a = x, *b = y;
    if (a->angle != b->angle) return a->angle < b->angle ? -1 : 1;
    return a->c < b->c ? -1 : (a->c > b->c);
}

static int degenerate(const uint32_t *t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

/* The corner of triangle t (3 global indices) at global vertex v. */
static uint32_t corner_at(const uint32_t *tri, uint32_t t, uint32_t v)
{
    const uint32_t *p = tri + 3 * (size_t)t;
    return 3 * t + (p[0] == v ? 0u : p[1] == v ? 1u : 2u);
}

/* The largest |x| of a vector, as a power of two to divide by (exact). */
static double pow2_scale(const double v[3])
{
    double big = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
    return big > 0 && isfinite(big) ? ldexp(1.0, -ilogb(big)) : 1.0;
}

static void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The sign of the part's volume (coordinates taken relative to its first
 * vertex and scaled by a power of two, so that nothing overflows). */
static int part_inward(const coons_mesh *m, const coons__mesh_part *p)
{
    if (!p->vert_count) return 0;
    const double *o = m->xyz + 3 * p->vert_first;
    double big = 0;
    for (size_t i = 0; i < 3 * p->vert_count; i++)
        big = fmax(big, fabs(m->xyz[3 * p->vert_first + i] - o[i % 3]));
    double s = big > 0 && isfinite(big) ? ldexp(1.0, -ilogb(big)) : 1.0;
    double vol = 0;
    for (size_t t = p->tri_first; t < p->tri_first + p->tri_count; t++) {
        double q[3][3];
        for (int k = 0; k < 3; k++)
            for (int d = 0; d < 3; d++) q[k][d] = (m->xyz[3 * m->tri[3 * t + k] + d] - o[d]) * s;
        double c[3];
        cross(q[1], q[2], c);
        vol += dot(q[0], c);
    }
    return vol < 0;
}

/* Sorts the 2k slots g[0..n) of edge lo -> hi by angle around it and joins
 * each pair that bounds a wedge of solid; 0 (nothing joined) when the
 * order does not alternate between the two directions. */
static int pair_around(const coons_mesh *m, const coons__mesh_part *p, const slot *g, size_t n,
                       around *buf, int inward, uint32_t *uf)
{
    const uint32_t *tri = m->tri + 3 * p->tri_first;
    const double *a = m->xyz + 3 * (size_t)g[0].lo, *b = m->xyz + 3 * (size_t)g[0].hi;
    double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double s = pow2_scale(d);
    for (int i = 0; i < 3; i++) d[i] *= s;
    /* e1, e2: perpendicular to d, e2 = d x e1 (right-handed about d) */
    int ax = fabs(d[0]) <= fabs(d[1]) && fabs(d[0]) <= fabs(d[2]) ? 0 : fabs(d[1]) <= fabs(d[2]) ? 1 : 2;
    double unit[3] = {0, 0, 0}, e1[3], e2[3];
    unit[ax] = 1;
    cross(d, unit, e1);
    cross(d, e1, e2);
    size_t nfwd = 0;
    for (size_t i = 0; i < n; i++) {
        uint32_t t = g[i].c / 3, k = g[i].c % 3;
        const uint32_t *v = tri + 3 * (size_t)t;
        uint32_t third = v[(k + 2) % 3];
        const double *c = m->xyz + 3 * (size_t)third;
        double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double sw = pow2_scale(w);
        for (int j = 0; j < 3; j++) w[j] *= sw;
        buf[i].angle = atan2(dot(w, e2), dot(w, e1));
        buf[i].c = g[i].c;
        buf[i].fwd = v[k] == g[i].lo;
        nfwd += (size_t)buf[i].fwd;
    }
    if (2 * nfwd != n) return 0;
    qsort(buf, n, sizeof *buf, cmp_around);
    for (size_t i = 0; i < n; i++) {
        if (buf[i].fwd == buf[(i + 1) % n].fwd) return 0; /* not alternating */
        if (i && buf[i].angle == buf[i - 1].angle) return 0; /* a tie: order unknown */
    }
    if (buf[0].angle == buf[n - 1].angle) return 0;
    /* An outward triangle running lo -> hi has the solid at decreasing
     * angle: it pairs with the one before it (inward: after it). */
    for (size_t i = 0; i < n; i++) {
        if (!buf[i].fwd) continue;
        size_t j = inward ? (i + 1) % n : (i + n - 1) % n;
        uint32_t t1 = buf[i].c / 3, t2 = buf[j].c / 3;
        coons__uf_union(uf, corner_at(tri, t1, g[0].lo), corner_at(tri, t2, g[0].lo));
        coons__uf_union(uf, corner_at(tri, t1, g[0].hi), corner_at(tri, t2, g[0].hi));
    }
    return 1;
}

/* Joins all slots of g[0..n) (an edge of two triangles, or one that cannot
 * be split): their corners at both ends stay one vertex. */
static void join_all(const uint32_t *tri, const slot *g, size_t n, uint32_t *uf)
{
    for (size_t i = 1; i < n; i++) {
        uint32_t t0 = g[0].c / 3, t = g[i].c / 3;
        coons__uf_union(uf, corner_at(tri, t0, g[0].lo), corner_at(tri, t, g[0].lo));
        coons__uf_union(uf, corner_at(tri, t0, g[0].hi), corner_at(tri, t, g[0].hi));
    }
}

/* Scratch of the slot sort: a second slot array and a count per vertex. */
typedef struct slot_sort {
    slot *tmp;
    uint32_t *cnt;
    size_t cap_v; /* entries of cnt */
} slot_sort;

/* The slots of the part's non-degenerate triangles (vertices vfirst ..
 * vfirst + vc - 1), sorted by (lo, hi, c); their count. A counting sort by
 * lo (stable: c ascending), then each run of one lo by hi (insertion sort,
 * stable; qsort for long runs): the order of qsort by cmp_slot, in linear
 * time (a qsort of every edge was most of the split's time). */
static size_t part_slots(const uint32_t *tri, size_t tc, size_t vfirst, size_t vc, slot *sl,
                         const slot_sort *ss)
{
    size_t ns = 0;
    int fits = vc + 1 <= ss->cap_v, ranged = fits;
    slot *out = fits ? ss->tmp : sl;
    for (size_t t = 0; t < tc; t++) {
        const uint32_t *v = tri + 3 * t;
        if (degenerate(v)) continue;
        for (uint32_t k = 0; k < 3; k++) {
            uint32_t x = v[k], y = v[(k + 1) % 3];
            slot *q = out + ns++;
            q->lo = x < y ? x : y;
            q->hi = x < y ? y : x;
            q->c = 3 * (uint32_t)t + k;
            if (q->lo < vfirst || q->hi >= vfirst + vc) ranged = 0;
        }
    }
    if (!ranged) {
        if (fits && ns) memcpy(sl, ss->tmp, ns * sizeof *sl);
        qsort(sl, ns, sizeof *sl, cmp_slot);
        return ns;
    }
    uint32_t *cnt = ss->cnt;
    memset(cnt, 0, (vc + 1) * sizeof *cnt);
    for (size_t i = 0; i < ns; i++) cnt[ss->tmp[i].lo - vfirst + 1]++;
    for (size_t v = 0; v < vc; v++) cnt[v + 1] += cnt[v];
    for (size_t i = 0; i < ns; i++) sl[cnt[ss->tmp[i].lo - vfirst]++] = ss->tmp[i];
    for (size_t i = 0; i < ns;) {
        size_t j = i;
        while (j < ns && sl[j].lo == sl[i].lo) j++;
        if (j - i > 32) {
            qsort(sl + i, j - i, sizeof *sl, cmp_slot);
        } else {
            for (size_t a = i + 1; a < j; a++)
                for (size_t b = a; b > i && sl[b - 1].hi > sl[b].hi; b--) {
                    slot x = sl[b];
                    sl[b] = sl[b - 1];
                    sl[b - 1] = x;
                }
        }
        i = j;
    }
    return ns;
}

/* Edges of more than two slots among sl[0..ns). */
static size_t count_nonmanifold(const slot *sl, size_t ns)
{
    size_t bad = 0;
    for (size_t i = 0; i < ns;) {
        size_t j = i;
        while (j < ns && sl[j].lo == sl[i].lo && sl[j].hi == sl[i].hi) j++;
        bad += j - i > 2;
        i = j;
    }
    return bad;
}

typedef struct plan {
    uint32_t *newtri;  /* 3 * nt: local vertex index in the new part */
    uint32_t *src;     /* extra vertices: the global index each copies */
    size_t nsrc, cap_src;
    size_t *extra;     /* per part: extra vertices */
    size_t before;     /* edges of more than two triangles before */
    size_t split_vertices;
    unsigned char *split; /* per vertex of the mesh: written more than once */
} plan;

static int push_src(plan *pl, uint32_t v)
{
    if (pl->nsrc == pl->cap_src) {
        size_t nc = pl->cap_src ? 2 * pl->cap_src : 64;
        uint32_t *q = coons__realloc(pl->src, nc * sizeof *q);
        if (!q) return 0;
        pl->src = q;
        pl->cap_src = nc;
    }
    pl->src[pl->nsrc++] = v;
    return 1;
}

/* Plans part pi into pl (scratch: sl, uf, root of 3 * tc; buf of 3 * tc;
 * seen of vc). 0 on allocation failure. */
static int plan_part(const coons_mesh *m, size_t pi, plan *pl, slot *sl, uint32_t *uf,
                     uint32_t *root, around *buf, unsigned char *seen, const slot_sort *ss)
{
    const coons__mesh_part *p = &m->parts[pi];
    const uint32_t *tri = m->tri + 3 * p->tri_first;
    size_t tc = p->tri_count, vc = p->vert_count;
    for (size_t c = 0; c < 3 * tc; c++) uf[c] = (uint32_t)c, root[c] = UINT32_MAX;
    memset(seen, 0, vc);
    size_t ns = part_slots(tri, tc, p->vert_first, vc, sl, ss);
    int inward = -1;
    for (size_t i = 0; i < ns;) {
        size_t j = i;
        while (j < ns && sl[j].lo == sl[i].lo && sl[j].hi == sl[i].hi) j++;
        size_t n = j - i;
        if (n > 2) {
            pl->before++;
            if (inward < 0) inward = part_inward(m, p);
            if (n % 2 || !pair_around(m, p, sl + i, n, buf, inward, uf))
                join_all(tri, sl + i, n, uf);
        } else if (n == 2) {
            join_all(tri, sl + i, n, uf);
        }
        i = j;
    }
    /* One vertex per fan: the first fan of a vertex keeps its index. seen:
     * 1 the index is taken, 2 the vertex was also copied. */
    size_t extra = 0;
    for (size_t t = 0; t < tc; t++) {
        const uint32_t *v = tri + 3 * t;
        int deg = degenerate(v);
        for (uint32_t k = 0; k < 3; k++) {
            uint32_t c = 3 * (uint32_t)t + k, local = v[k] - (uint32_t)p->vert_first;
            if (deg) { /* a degenerate triangle keeps its indices */
                pl->newtri[3 * (p->tri_first + t) + k] = local;
                seen[local] |= 1;
                continue;
            }
            uint32_t r = coons__uf_find(uf, c);
            if (root[r] == UINT32_MAX) {
                if (!(seen[local] & 1)) {
                    root[r] = local;
                    seen[local] |= 1;
                } else {
                    root[r] = (uint32_t)(vc + extra++);
                    if (!push_src(pl, v[k])) return 0;
                    if (!(seen[local] & 2)) pl->split_vertices++;
                    seen[local] |= 2;
                    pl->split[v[k]] = 1;
                }
            }
            pl->newtri[3 * (p->tri_first + t) + k] = root[r];
        }
    }
    pl->extra[pi] = extra;
    return 1;
}

/* The copies of a split vertex moved apart, each into its own fan's solid
 * (against the sum of its triangles' outward normals) by a small fraction
 * of the fan's shortest edge, at least a few float32 units of the
 * coordinate and at least 2^-19 model units where that stays below
 * PINCH_SHIFT_MAX of the edge: readers that weld vertices by position
 * (every STL reader, OpenSCAD's Booleans, which snap to a grid of 2^-20
 * units, so copies must differ by more than that in some coordinate) would
 * otherwise make the pinch again. acc: 4 doubles per vertex. */
#define PINCH_SHIFT 1e-3 /* of the fan's shortest edge */
#define PINCH_SHIFT_MAX 1e-1
#define PINCH_FLOAT_ULPS 16.0
#define PINCH_OPENSCAD_GRID 0x1p-19

static void separate(coons_mesh *m, const unsigned char *split, const uint32_t *orig, double *acc)
{
    for (size_t x = 0; x < m->nv; x++) {
        acc[4 * x] = acc[4 * x + 1] = acc[4 * x + 2] = 0;
        acc[4 * x + 3] = HUGE_VAL;
    }
    for (size_t i = 0; i < m->nparts; i++) {
        const coons__mesh_part *p = &m->parts[i];
        double sign = part_inward(m, p) ? -1.0 : 1.0;
        for (size_t t = p->tri_first; t < p->tri_first + p->tri_count; t++) {
            const uint32_t *v = m->tri + 3 * t;
            if (degenerate(v)) continue;
            for (int k = 0; k < 3; k++) {
                uint32_t x = v[k];
                if (!split[orig[x]]) continue;
                const double *a = m->xyz + 3 * (size_t)x, *b = m->xyz + 3 * (size_t)v[(k + 1) % 3],
                             *c = m->xyz + 3 * (size_t)v[(k + 2) % 3];
                double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
                double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
                double l1 = sqrt(dot(e1, e1)), l2 = sqrt(dot(e2, e2));
                double s1 = pow2_scale(e1), s2 = pow2_scale(e2), n[3];
                for (int d = 0; d < 3; d++) e1[d] *= s1, e2[d] *= s2;
                cross(e1, e2, n); /* outward, scaled: only its direction counts */
                double len = sqrt(dot(n, n));
                if (!(len > 0)) continue;
                for (int d = 0; d < 3; d++) acc[4 * x + d] += sign * n[d] / len;
                acc[4 * x + 3] = fmin(acc[4 * x + 3], fmin(l1, l2));
            }
        }
    }
    for (size_t x = 0; x < m->nv; x++) {
        if (!split[orig[x]]) continue;
        double *n = acc + 4 * x, len = sqrt(dot(n, n));
        if (!(len > 0) || !isfinite(acc[4 * x + 3])) continue;
        double *q = m->xyz + 3 * x;
        double big = fmax(fabs(q[0]), fmax(fabs(q[1]), fabs(q[2])));
        double h = acc[4 * x + 3];
        double step = fmax(PINCH_SHIFT * h, PINCH_FLOAT_ULPS * ldexp(big, -23));
        step = fmax(step, PINCH_OPENSCAD_GRID);
        step = fmin(step, PINCH_SHIFT_MAX * h);
        for (int d = 0; d < 3; d++) q[d] -= step * n[d] / len;
    }
}

coons_status coons__mesh_split_pinches(coons_mesh *m, size_t *edges_split, size_t *vertices_split,
                                       size_t *nonmanifold_left, coons_error *err)
{
    size_t maxt = 0, maxv = 0;
    for (size_t i = 0; i < m->nparts; i++) {
        if (m->parts[i].tri_count > maxt) maxt = m->parts[i].tri_count;
        if (m->parts[i].vert_count > maxv) maxv = m->parts[i].vert_count;
    }
    if (maxt > UINT32_MAX / 3)
        return coons__error_set(err, COONS_E_LIMIT,
                                "a part of %zu triangles is too large to check for pinches", maxt);
    plan pl;
    memset(&pl, 0, sizeof pl);
    slot *sl = coons__malloc_array(3 * maxt + 1, sizeof *sl);
    uint32_t *uf = coons__malloc_array(3 * maxt + 1, sizeof *uf);
    uint32_t *root = coons__malloc_array(3 * maxt + 1, sizeof *root);
    around *buf = coons__malloc_array(3 * maxt + 1, sizeof *buf);
    slot_sort ss = {coons__malloc_array(3 * maxt + 1, sizeof(slot)),
                    coons__malloc_array(maxv + 2, sizeof(uint32_t)), maxv + 2};
    unsigned char *seen = coons__malloc(maxv + 1);
    pl.newtri = coons__malloc_array(3 * m->nt + 1, sizeof *pl.newtri);
    pl.extra = coons__calloc(m->nparts + 1, sizeof *pl.extra);
    pl.split = coons__calloc(m->nv + 1, 1);
    double *xyz = NULL, *uvw = NULL, *acc = NULL;
    uint32_t *orig = NULL;
    coons_status st = COONS_OK;
    if (!sl || !uf || !root || !buf || !seen || !pl.newtri || !pl.extra || !pl.split || !ss.tmp ||
        !ss.cnt)
        goto nomem;
    for (size_t i = 0; i < m->nparts; i++)
        if (!plan_part(m, i, &pl, sl, uf, root, buf, seen, &ss)) goto nomem;
    size_t left = 0;
    if (pl.nsrc) {
        if (pl.nsrc > (size_t)UINT32_MAX - m->nv) {
            st = coons__error_set(err, COONS_E_LIMIT,
                                  "splitting the pinches would make more than %u vertices",
                                  (unsigned)UINT32_MAX);
            goto done;
        }
        size_t nv = m->nv + pl.nsrc;
        xyz = coons__malloc_array(3 * nv, sizeof *xyz);
        if (!xyz) goto nomem;
        if (m->uvw && !(uvw = coons__malloc_array(3 * nv, sizeof *uvw))) goto nomem;
        acc = coons__malloc_array(4 * nv, sizeof *acc);
        orig = coons__malloc_array(nv, sizeof *orig);
        if (!acc || !orig) goto nomem;
        /* Nothing fails from here on: the mesh is rewritten. */
        size_t cursor = 0, s = 0;
        for (size_t i = 0; i < m->nparts; i++) {
            coons__mesh_part *p = &m->parts[i];
            size_t first = cursor;
            if (p->vert_count)
                memcpy(xyz + 3 * cursor, m->xyz + 3 * p->vert_first, 3 * p->vert_count * sizeof *xyz);
            for (size_t k = 0; k < p->vert_count; k++)
                orig[cursor + k] = (uint32_t)(p->vert_first + k);
            if (uvw)
                memcpy(uvw + 3 * cursor, m->uvw + 3 * p->vert_first,
                       3 * p->vert_count * sizeof *uvw);
            cursor += p->vert_count;
            for (size_t e = 0; e < pl.extra[i]; e++, s++, cursor++) {
                orig[cursor] = pl.src[s];
                memcpy(xyz + 3 * cursor, m->xyz + 3 * (size_t)pl.src[s], 3 * sizeof *xyz);
                if (uvw) memcpy(uvw + 3 * cursor, m->uvw + 3 * (size_t)pl.src[s], 3 * sizeof *uvw);
            }
            for (size_t k = 3 * p->tri_first; k < 3 * (p->tri_first + p->tri_count); k++)
                m->tri[k] = pl.newtri[k] + (uint32_t)first;
            p->vert_first = first;
            p->vert_count = cursor - first;
        }
        coons__free(m->xyz);
        m->xyz = xyz;
        m->cap_v = 3 * nv;
        xyz = NULL;
        if (uvw) {
            coons__free(m->uvw);
            m->uvw = uvw;
            m->cap_uvw = 3 * nv;
            uvw = NULL;
        }
        m->nv = nv;
        separate(m, pl.split, orig, acc);
        for (size_t i = 0; i < m->nparts; i++) {
            const coons__mesh_part *p = &m->parts[i];
            left += count_nonmanifold(
                sl, part_slots(m->tri + 3 * p->tri_first, p->tri_count, p->vert_first,
                               p->vert_count, sl, &ss));
        }
    } else {
        left = pl.before; /* nothing changed */
    }
    *edges_split += pl.before - left;
    *vertices_split += pl.split_vertices;
    if (nonmanifold_left) *nonmanifold_left = left;
    goto done;
nomem:
    st = coons__error_nomem(err);
done:
    coons__free(sl);
    coons__free(uf);
    coons__free(root);
    coons__free(buf);
    coons__free(ss.tmp);
    coons__free(ss.cnt);
    coons__free(seen);
    coons__free(pl.newtri);
    coons__free(pl.src);
    coons__free(pl.extra);
    coons__free(pl.split);
    coons__free(acc);
    coons__free(orig);
    coons__free(xyz);
    coons__free(uvw);
    return st;
}

/* ---- the pinches welded back, for the crossing counts ----------------- */

typedef struct point_id {
    double x[3];
    uint32_t id;
} point_id;

static int cmp_point(const void *x, const void *y)
{
    const point_id *p = x, *q = y;
    for (int d = 0; d < 3; d++)
        if (p->x[d] != q->x[d]) return p->x[d] < q->x[d] ? -1 : 1;
    return p->id < q->id ? -1 : (p->id > q->id);
}

coons_status coons__mesh_welded(const coons_mesh *m, coons_mesh **out, coons_error *err)
{
    *out = NULL;
    coons_mesh *w = NULL;
    coons_status st = coons_mesh_new(&w, err);
    if (st) return st;
    size_t maxv = 1, maxt = 1;
    for (size_t i = 0; i < m->nparts; i++) {
        if (m->parts[i].vert_count > maxv) maxv = m->parts[i].vert_count;
        if (m->parts[i].tri_count > maxt) maxt = m->parts[i].tri_count;
    }
    point_id *order = coons__malloc_array(maxv, sizeof *order);
    uint32_t *rep = coons__malloc_array(maxv, sizeof *rep);
    double *xyz = coons__malloc_array(3 * maxv, sizeof *xyz);
    uint32_t *tri = coons__malloc_array(3 * maxt, sizeof *tri);
    if (!order || !rep || !xyz || !tri) {
        st = coons__error_nomem(err);
        goto done;
    }
    for (size_t i = 0; i < m->nparts && !st; i++) {
        const coons__mesh_part *p = &m->parts[i];
        const double *v = m->xyz + 3 * p->vert_first;
        for (size_t k = 0; k < p->vert_count; k++) {
            memcpy(order[k].x, v + 3 * k, sizeof order[k].x);
            order[k].id = (uint32_t)k;
        }
        qsort(order, p->vert_count, sizeof *order, cmp_point);
        size_t n = 0;
        for (size_t k = 0; k < p->vert_count; k++) {
            const double *a = order[k].x;
            if (n == 0 || a[0] != xyz[3 * (n - 1)] || a[1] != xyz[3 * (n - 1) + 1] ||
                a[2] != xyz[3 * (n - 1) + 2]) {
                memcpy(xyz + 3 * n, a, 3 * sizeof *xyz);
                n++;
            }
            rep[order[k].id] = (uint32_t)(n - 1);
        }
        for (size_t k = 0; k < 3 * p->tri_count; k++)
            tri[k] = rep[m->tri[3 * p->tri_first + k] - p->vert_first];
        st = coons_mesh_add_part(w, p->name, xyz, n, tri, p->tri_count, err);
    }
done:
    coons__free(order);
    coons__free(rep);
    coons__free(xyz);
    coons__free(tri);
    if (st) {
        coons_mesh_free(w);
        return st;
    }
    *out = w;
    return COONS_OK;
}

coons_status coons__mesh_clone(const coons_mesh *m, coons_mesh **out, coons_error *err)
{
    *out = NULL;
    coons_mesh *c = NULL;
    coons_status st = coons_mesh_new(&c, err);
    if (st) return st;
    c->xyz = coons__malloc_array(3 * m->nv + 1, sizeof *c->xyz);
    c->tri = coons__malloc_array(3 * m->nt + 1, sizeof *c->tri);
    c->parts = coons__calloc(m->nparts + 1, sizeof *c->parts);
    c->uvw = m->uvw ? coons__malloc_array(3 * m->nv + 1, sizeof *c->uvw) : NULL;
    if (!c->xyz || !c->tri || !c->parts || (m->uvw && !c->uvw)) goto nomem;
    c->cap_v = 3 * m->nv + 1;
    c->cap_t = 3 * m->nt + 1;
    c->cap_p = m->nparts + 1;
    c->cap_uvw = c->uvw ? 3 * m->nv + 1 : 0;
    if (m->nv) memcpy(c->xyz, m->xyz, 3 * m->nv * sizeof *c->xyz);
    if (m->nt) memcpy(c->tri, m->tri, 3 * m->nt * sizeof *c->tri);
    if (c->uvw && m->nv) memcpy(c->uvw, m->uvw, 3 * m->nv * sizeof *c->uvw);
    c->nv = m->nv;
    c->nt = m->nt;
    for (size_t i = 0; i < m->nparts; i++) {
        size_t len = strlen(m->parts[i].name);
        char *name = coons__malloc(len + 1);
        if (!name) goto nomem;
        memcpy(name, m->parts[i].name, len + 1);
        c->parts[i] = m->parts[i];
        c->parts[i].name = name;
        c->nparts = i + 1;
    }
    *out = c;
    return COONS_OK;
nomem:
    coons_mesh_free(c);
    return coons__error_nomem(err);
}
