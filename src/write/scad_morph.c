/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The OpenSCAD animation of a model with morph bodies (seed 000 section 4,
 * Fig. 10; outputs.md "Metamorphosis"): every morph is written as the
 * vertex arrays of its keys on one lattice with one face list, and a
 * function of the time t that blends them with the path's weights in
 * OpenSCAD itself; the top-level call passes $t, so View > Animate plays
 * the metamorphosis. Other bodies are plain polyhedra, united with the
 * morphs by OpenSCAD's union(). Modules are named as scad.c names them:
 * the model NAME, each body NAME_BODY (coons__scad_part_identifier()).
 *
 * Exactness: the morph is a pointwise blend, so a frame's vertex is
 * sum_k W_k(t) K_k(u,v,w) at the vertex's lattice parameters. The keys'
 * values are those of the body grid evaluator at each vertex alone, which
 * gives bitwise the values any grid through that point gives (body.h), so
 * they are what the boundary sampler computes at time t; the weights are
 * written as the sums morph.c evaluates (morph.h), in the same order, and
 * the blend is summed key by key in key order as morph.c's grid does
 * (weights 0 add nothing). Affine wrappers of morphs are applied after
 * the blend, as body_transformed.c does. So `openscad -D '$t=T'` gives the
 * vertices of `coons2stl --time T --resolution N` (N the lattice written
 * in the file), to the printed digits.
 *
 * One lattice for all frames: uniform, N intervals along u, v and w (the
 * sampler's fixed lattice, which does not depend on the time): with
 * --resolution N that N; else the smallest N, from the largest adaptive
 * lattice count at the check times up in steps of 1/4, whose mesh (the
 * fixed face list with each frame's vertices) is within the tolerance at
 * every check time: the key times, and 4 times inside each interval
 * between keys, measured at 7 points of every triangle (edge midpoints,
 * centroid, and the points halfway between the centroid and the corners)
 * against that triangle. One face list for all frames: the sampler's at
 * the middle time 1/2; vertices merge only where they merge at every key
 * time and at 1/2 (the vertex counts agree), else the animation is
 * refused (--frames writes such a morph frame by frame).
 */
#include "writer.h"

#include "body_impl.h"
#include "coons/version.h"
#include "sampling.h"
#include "mesh_impl.h"
#include "morph.h"

#define REF_TIME 0.5
#define CHECKS_PER_INTERVAL 4
#define IDENT_CAP COONS__SCAD_IDENT_MAX

/* A node of a morph body's tree: what gives one vertex array. */
enum { N_CONST, N_AFFINE, N_MORPH };
typedef struct node {
    int kind;
    const coons_body *b;
    double *pts;    /* N_CONST: 3 nv */
    size_t inner;   /* N_AFFINE: the wrapped node */
    size_t *keys;   /* N_MORPH: nkeys nodes */
} node;

typedef struct part {
    char id[IDENT_CAP];
    int morph;
    size_t nv, nt;
    uint32_t *tri; /* 3 nt, counter-clockwise from outside */
    double *xyz;   /* plain parts: 3 nv */
    double *uvw;   /* morph parts: 3 nv */
    node *nodes;
    size_t nn, cap;
    unsigned lattice;
} part;

typedef struct anim {
    part *parts;
    size_t np;
    char model[IDENT_CAP];
    double tolerance;
} anim;

static void free_part(part *p)
{
    coons__free(p->tri);
    coons__free(p->xyz);
    coons__free(p->uvw);
    for (size_t i = 0; i < p->nn; i++) {
        coons__free(p->nodes[i].pts);
        coons__free(p->nodes[i].keys);
    }
    coons__free(p->nodes);
}

static void free_anim(anim *a)
{
    for (size_t i = 0; i < a->np; i++) free_part(&a->parts[i]);
    coons__free(a->parts);
}

static int has_morph(const coons_body *b)
{
    for (; b; b = b->inner)
        if (b->kind == &coons__morph_kind) return 1;
    return 0;
}

/* ---- the lattice and the face list ------------------------------------- */

/* Samples b on the uniform lattice of n intervals: one part with vertex
 * parameters into a new mesh. */
static coons_status sample_fixed(const coons_body *b, const coons__sample_opts *o, unsigned n,
                                 const char *name, coons_mesh **out, coons_error *err)
{
    coons__sample_opts f = *o;
    f.resolution = n;
    f.flags |= COONS_SAMPLE_UNMEASURED | COONS__SAMPLE_PARAMS;
    coons_status st = coons_mesh_new(out, err);
    if (st) return st;
    size_t used = 0;
    st = coons__body_sample_into(b, &f, name, *out, &used, err);
    if (st) {
        coons_mesh_free(*out);
        *out = NULL;
    }
    return st;
}

static coons_status sample_at(const coons_body *b, double t, const coons__sample_opts *o,
                              unsigned n, const char *name, coons_mesh **out, coons_error *err)
{
    coons_body *c = NULL;
    coons_status st = coons_body_at_time(b, t, &c, err);
    if (!st) st = sample_fixed(c, o, n, name, out, err);
    coons_body_free(c);
    return st;
}

/* The check times: keys, and CHECKS_PER_INTERVAL inside each interval. */
static size_t check_times(const coons_body *m, double *t, size_t cap)
{
    size_t n = 0, nk = m->nkeys;
    for (size_t k = 0; k < nk && n < cap; k++) {
        double a = 0, b = 0;
        coons_body_morph_key(m, k, &a);
        t[n++] = a;
        if (k + 1 == nk) break;
        coons_body_morph_key(m, k + 1, &b);
        for (int j = 1; j <= CHECKS_PER_INTERVAL && n < cap; j++)
            t[n++] = a + (b - a) * j / (CHECKS_PER_INTERVAL + 1);
    }
    return n;
}

/* Squared distance from p to triangle (a, b, c) (Ericson, "Real-Time
 * Collision Detection", 5.1.5). */
static double tri_dist2(const double p[3], const double a[3], const double b[3],
                        const double c[3])
{
    double ab[3], ac[3], ap[3], q[3];
    v3_sub(ab, b, a);
    v3_sub(ac, c, a);
    v3_sub(ap, p, a);
    double d1 = v3_dot(ab, ap), d2 = v3_dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return v3_dot(ap, ap);
    double bp[3];
    v3_sub(bp, p, b);
    double d3 = v3_dot(ab, bp), d4 = v3_dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return v3_dot(bp, bp);
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        double v = d1 / (d1 - d3);
        for (int i = 0; i < 3; i++) q[i] = a[i] + v * ab[i] - p[i];
        return v3_dot(q, q);
    }
    double cp[3];
    v3_sub(cp, p, c);
    double d5 = v3_dot(ab, cp), d6 = v3_dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return v3_dot(cp, cp);
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        double w = d2 / (d2 - d6);
        for (int i = 0; i < 3; i++) q[i] = a[i] + w * ac[i] - p[i];
        return v3_dot(q, q);
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        for (int i = 0; i < 3; i++) q[i] = b[i] + w * (c[i] - b[i]) - p[i];
        return v3_dot(q, q);
    }
    double den = 1.0 / (va + vb + vc), v = vb * den, w = vc * den;
    for (int i = 0; i < 3; i++) q[i] = a[i] + ab[i] * v + ac[i] * w - p[i];
    return v3_dot(q, q);
}

/* Largest distance of the exact boundary of b from the fixed face list
 * with b's vertices, at 7 points per triangle. */
static double deviation(const coons_body *b, const part *p)
{
    static const double BARY[7][3] = {{0.5, 0.5, 0},         {0, 0.5, 0.5},
                                      {0.5, 0, 0.5},         {1.0 / 3, 1.0 / 3, 1.0 / 3},
                                      {2.0 / 3, 1.0 / 6, 1.0 / 6}, {1.0 / 6, 2.0 / 3, 1.0 / 6},
                                      {1.0 / 6, 1.0 / 6, 2.0 / 3}};
    double worst = 0;
    for (size_t t = 0; t < p->nt; t++) {
        const uint32_t *v = p->tri + 3 * t;
        double P[3][3];
        for (int k = 0; k < 3; k++) {
            const double *q = p->uvw + 3 * (size_t)v[k];
            coons_body_eval(b, q[0], q[1], q[2], P[k]);
        }
        for (int s = 0; s < 7; s++) {
            double q[3], x[3];
            for (int d = 0; d < 3; d++)
                q[d] = BARY[s][0] * p->uvw[3 * v[0] + d] + BARY[s][1] * p->uvw[3 * v[1] + d] +
                       BARY[s][2] * p->uvw[3 * v[2] + d];
            coons_body_eval(b, q[0], q[1], q[2], x);
            double d2 = tri_dist2(x, P[0], P[1], P[2]);
            if (d2 > worst) worst = d2;
        }
    }
    return sqrt(worst);
}

/* Takes the part's face list and vertex parameters from mesh part 0. */
static coons_status take_faces(part *p, const coons_mesh *mesh, coons_error *err)
{
    p->nv = coons_mesh_vertex_count(mesh);
    p->nt = coons_mesh_triangle_count(mesh);
    p->tri = coons__malloc_array(p->nt, 3 * sizeof *p->tri);
    p->uvw = coons__malloc_array(p->nv, 3 * sizeof *p->uvw);
    if (!p->tri || !p->uvw) return coons__error_nomem(err);
    memcpy(p->tri, coons_mesh_triangles(mesh), p->nt * 3 * sizeof *p->tri);
    memcpy(p->uvw, coons_mesh_vertex_parameters(mesh), p->nv * 3 * sizeof *p->uvw);
    return COONS_OK;
}

static coons_status faces_on_lattice(const coons_body *b, const coons_body *m,
                                     const coons__sample_opts *o, const char *name,
                                     const double *times, size_t nt, part *p, coons_error *err);

/* The lattice and face list of morph body b. */
static coons_status morph_faces(const coons_body *b, const coons__sample_opts *o,
                                const char *name, part *p, coons_error *err)
{
    const coons_body *m = b;
    while (m->kind != &coons__morph_kind) m = m->inner;
    size_t cap = m->nkeys * (CHECKS_PER_INTERVAL + 1);
    double *times = coons__malloc_array(cap, sizeof *times);
    if (!times) return coons__error_nomem(err);
    size_t nt = check_times(m, times, cap);
    coons_status st = faces_on_lattice(b, m, o, name, times, nt, p, err);
    coons__free(times);
    return st;
}

static coons_status faces_on_lattice(const coons_body *b, const coons_body *m,
                                     const coons__sample_opts *o, const char *name,
                                     const double *times, size_t nt, part *p, coons_error *err)
{
    coons_status st = COONS_OK;
    unsigned n = o->resolution;
    if (!n) { /* the largest adaptive lattice count at the check times */
        coons__sample_opts a = *o;
        a.resolution = 0;
        for (size_t i = 0; i < nt && !st; i++) {
            coons_body *c = NULL;
            double *t3[3] = {NULL, NULL, NULL};
            size_t n3[3];
            st = coons_body_at_time(b, times[i], &c, err);
            if (!st) st = coons__body_sample_lattice(c, &a, name, t3, n3, NULL, err);
            for (int d = 0; d < 3; d++) {
                if (!st && n3[d] > n) n = (unsigned)n3[d];
                coons__free(t3[d]);
            }
            coons_body_free(c);
        }
        if (st) return st;
    }
    for (;;) {
        coons_mesh *ref = NULL;
        st = sample_at(b, REF_TIME, o, n, name, &ref, err);
        if (!st) {
            free_part(p);
            p->tri = NULL, p->uvw = NULL, p->nodes = NULL, p->nn = p->cap = 0;
            st = take_faces(p, ref, err);
        }
        coons_mesh_free(ref);
        if (st) return st;
        p->lattice = n;
        if (2 * p->nt > o->max_triangles)
            return coons__error_set(err, COONS_E_LIMIT,
                                    "body '%s': the animation's lattice of %u intervals needs "
                                    "more than %zu triangles (the limit)",
                                    name, n, o->max_triangles);
        /* vertices merge the same way at every key time */
        for (size_t k = 0; k < m->nkeys && !st; k++) {
            double at = 0;
            coons_body_morph_key(m, k, &at);
            coons_mesh *km = NULL;
            st = sample_at(b, at, o, n, name, &km, err);
            if (!st && coons_mesh_vertex_count(km) != p->nv)
                st = coons__error_set(err, COONS_E_UNSUPPORTED,
                                      "body '%s': its lattice collapses differently at key time "
                                      "%g (%zu vertices, %zu at time %g), so no one face list "
                                      "serves every frame; write frames with --frames instead",
                                      name, at, coons_mesh_vertex_count(km), p->nv, REF_TIME);
            coons_mesh_free(km);
        }
        if (st) return st;
        if (o->resolution) return COONS_OK;
        double worst = 0;
        for (size_t i = 0; i < nt && !st; i++) {
            coons_body *c = NULL;
            st = coons_body_at_time(b, times[i], &c, err);
            if (!st) worst = fmax(worst, deviation(c, p));
            coons_body_free(c);
        }
        if (st) return st;
        if (worst <= o->tolerance) return COONS_OK;
        n += n / 4 > 0 ? n / 4 : 1;
    }
}

/* ---- the vertex arrays --------------------------------------------------- */

static coons_status add_node(part *p, node nd, size_t *index, coons_error *err)
{
    if (p->nn == p->cap) {
        size_t cap = p->cap ? 2 * p->cap : 8;
        node *q = coons__realloc(p->nodes, cap * sizeof *q);
        if (!q) {
            coons__free(nd.pts);
            coons__free(nd.keys);
            return coons__error_nomem(err);
        }
        p->nodes = q;
        p->cap = cap;
    }
    p->nodes[p->nn] = nd;
    *index = p->nn++;
    return COONS_OK;
}

/* The node of b (and its subtree); *index receives it. */
static coons_status build_node(part *p, const coons_body *b, size_t *index, coons_error *err)
{
    node nd = {N_CONST, b, NULL, 0, NULL};
    coons_status st = COONS_OK;
    if (!has_morph(b)) {
        if (!(nd.pts = coons__malloc_array(p->nv, 3 * sizeof *nd.pts)))
            return coons__error_nomem(err);
        for (size_t v = 0; v < p->nv && !st; v++) {
            const double *q = p->uvw + 3 * v;
            st = coons_body_eval_grid(b, q, 1, q + 1, 1, q + 2, 1, nd.pts + 3 * v, err);
        }
        if (st) {
            coons__free(nd.pts);
            return st;
        }
        return add_node(p, nd, index, err);
    }
    if (b->kind != &coons__morph_kind) { /* an affine wrapper */
        nd.kind = N_AFFINE;
        if ((st = build_node(p, b->inner, &nd.inner, err))) return st;
        return add_node(p, nd, index, err);
    }
    nd.kind = N_MORPH;
    size_t *keys = coons__malloc_array(b->nkeys, sizeof *keys);
    if (!keys) return coons__error_nomem(err);
    for (size_t k = 0; k < b->nkeys && !st; k++) st = build_node(p, b->keys[k], &keys[k], err);
    if (st) {
        coons__free(keys);
        return st;
    }
    nd.keys = keys;
    return add_node(p, nd, index, err);
}

/* ---- writing ------------------------------------------------------------- */

static void put_num(coons__sink *s, double v)
{
    char b[COONS__FMT_MAX];
    coons__fmt_double(b, v);
    coons__sink_puts(s, b);
}

static void put_fmt(coons__sink *s, const char *fmt, size_t a, size_t b)
{
    char line[160];
    snprintf(line, sizeof line, fmt, a, b);
    coons__sink_puts(s, line);
}

static void put_points(coons__sink *s, const double *xyz, size_t nv)
{
    for (size_t v = 0; v < nv && coons__sink_ok(s); v++) {
        char *p = coons__sink_room(s, 3 * COONS__FMT_MAX + 8), *p0 = p;
        if (!p) return;
        *p++ = '[';
        for (int k = 0; k < 3; k++) {
            p += coons__fmt_double(p, xyz[3 * v + (size_t)k]);
            *p++ = k < 2 ? ',' : ']';
        }
        if (v + 1 < nv) *p++ = ',';
        *p++ = '\n';
        s->len += (size_t)(p - p0);
    }
}

/* polyhedron() wants faces clockwise seen from outside: (a, c, b). */
static void put_faces(coons__sink *s, const uint32_t *tri, size_t nt)
{
    for (size_t t = 0; t < nt && coons__sink_ok(s); t++) {
        char *p = coons__sink_room(s, 48), *p0 = p;
        if (!p) return;
        static const int order[3] = {0, 2, 1};
        *p++ = '[';
        for (int k = 0; k < 3; k++) {
            p += coons__fmt_u64(p, tri[3 * t + (size_t)order[k]]);
            *p++ = k < 2 ? ',' : ']';
        }
        if (t + 1 < nt) *p++ = ',';
        *p++ = '\n';
        s->len += (size_t)(p - p0);
    }
}

static void put_node_name(coons__sink *s, const part *p, size_t i)
{
    coons__sink_puts(s, p->id);
    put_fmt(s, "_n%zu", i, 0);
}

/* The weights function of a morph node: the interval of t, s in it, the
 * Hermite basis H (morph.c's `basis`) and per interval the shares A of
 * every key (morph.h), summed as A0 H0 + A1 H1 + A2 H2 + A3 H3; then the
 * points, the blend of the keys' arrays in key order. */
static void put_morph_node(coons__sink *s, const part *p, size_t i)
{
    const node *nd = &p->nodes[i];
    const coons_body *m = nd->b;
    size_t n = m->nkeys;
    int cubic = m->path == COONS_MORPH_SMOOTH && n > 2;
    /* weights */
    coons__sink_puts(s, "function ");
    put_node_name(s, p, i);
    coons__sink_puts(s, "_w(t0) = let(\n  t = t0 < 0 ? 0 : (t0 > 1 ? 1 : t0),\n  T = [");
    for (size_t k = 0; k < n; k++) {
        double at = 0;
        coons_body_morph_key(m, k, &at);
        if (k) coons__sink_puts(s, ", ");
        put_num(s, at);
    }
    coons__sink_puts(s, "],\n  i = ");
    if (n == 2)
        coons__sink_puts(s, "0");
    else {
        coons__sink_puts(s, "len([for (k = [1 : ");
        put_fmt(s, "%zu", n - 2, 0);
        coons__sink_puts(s, "]) if (t >= T[k]) 1])");
    }
    coons__sink_puts(s, ",\n  s0 = (t - T[i]) / (T[i + 1] - T[i]),\n  s = s0 > 1 ? 1 : s0,\n");
    if (cubic)
        coons__sink_puts(s, "  s2 = s * s, s3 = s2 * s,\n"
                            "  H = [2 * s3 - 3 * s2 + 1, s3 - 2 * s2 + s, -2 * s3 + 3 * s2, "
                            "s3 - s2],\n");
    else
        coons__sink_puts(s, "  H = [1 - s, 0, s, 0],\n");
    coons__sink_puts(s, "  A = [\n");
    for (size_t iv = 0; iv + 1 < n && coons__sink_ok(s); iv++) {
        double A[4][4];
        size_t first = 0, cnt = coons__morph_terms(n, m->at, m->path, iv, A, &first);
        coons__sink_puts(s, "    [");
        for (size_t k = 0; k < n; k++) {
            coons__sink_puts(s, k ? ", [" : "[");
            for (int q = 0; q < 4; q++) {
                if (q) coons__sink_puts(s, ", ");
                put_num(s, k >= first && k < first + cnt ? A[k - first][q] : 0.0);
            }
            coons__sink_puts(s, "]");
        }
        coons__sink_puts(s, iv + 2 < n ? "],\n" : "]\n");
    }
    coons__sink_puts(s, "  ][i])\n  [for (a = A) a[0] * H[0] + a[1] * H[1] + a[2] * H[2] + "
                        "a[3] * H[3]];\n");
    /* points */
    coons__sink_puts(s, "function ");
    put_node_name(s, p, i);
    coons__sink_puts(s, "(t) = let(W = ");
    put_node_name(s, p, i);
    coons__sink_puts(s, "_w(t)");
    for (size_t k = 0; k < n; k++) {
        put_fmt(s, ", K%zu = ", k, 0);
        put_node_name(s, p, nd->keys[k]);
        coons__sink_puts(s, p->nodes[nd->keys[k]].kind == N_CONST ? "()" : "(t)");
    }
    put_fmt(s, ")\n  [for (v = [0 : %zu]) ", p->nv - 1, 0);
    for (size_t k = 0; k < n; k++) put_fmt(s, k ? " + W[%zu] * K%zu[v]" : "W[%zu] * K%zu[v]", k, k);
    coons__sink_puts(s, "];\n");
}

static void put_affine_node(coons__sink *s, const part *p, size_t i)
{
    const node *nd = &p->nodes[i];
    const double *x = nd->b->xf;
    coons__sink_puts(s, "function ");
    put_node_name(s, p, i);
    coons__sink_puts(s, "(t) = [for (q = ");
    put_node_name(s, p, nd->inner);
    coons__sink_puts(s, "(t)) [");
    for (int r = 0; r < 3; r++) {
        if (r) coons__sink_puts(s, ", ");
        for (int c = 0; c < 3; c++) {
            if (c) coons__sink_puts(s, " + ");
            put_num(s, x[4 * r + c]);
            put_fmt(s, " * q[%zu]", (size_t)c, 0);
        }
        coons__sink_puts(s, " + ");
        put_num(s, x[4 * r + 3]);
    }
    coons__sink_puts(s, "]];\n");
}

static void put_part(coons__sink *s, const part *p, size_t index)
{
    char head[256];
    snprintf(head, sizeof head, "\n// body %zu, module %.160s: %s(%zu vertices, %zu triangles)\n",
             index, p->id, p->morph ? "a morph " : "", p->nv, p->nt);
    coons__sink_puts(s, head);
    if (!p->morph) {
        coons__sink_puts(s, "module ");
        coons__sink_puts(s, p->id);
        coons__sink_puts(s, "() {\n  polyhedron(points = [\n");
        put_points(s, p->xyz, p->nv);
        coons__sink_puts(s, "  ], faces = [\n");
        put_faces(s, p->tri, p->nt);
        coons__sink_puts(s, "  ], convexity = 10);\n}\n");
        return;
    }
    snprintf(head, sizeof head,
             "// one lattice of %u intervals along u, v and w and one face list for every\n"
             "// frame: coons2stl --time T --resolution %u gives these vertices at t = T.\n",
             p->lattice, p->lattice);
    coons__sink_puts(s, head);
    for (size_t i = 0; i < p->nn && coons__sink_ok(s); i++) {
        const node *nd = &p->nodes[i];
        if (nd->kind == N_CONST) {
            coons__sink_puts(s, "function ");
            put_node_name(s, p, i);
            coons__sink_puts(s, "() = [\n");
            put_points(s, nd->pts, p->nv);
            coons__sink_puts(s, "];\n");
        } else if (nd->kind == N_AFFINE) {
            put_affine_node(s, p, i);
        } else {
            put_morph_node(s, p, i);
        }
    }
    coons__sink_puts(s, "function ");
    coons__sink_puts(s, p->id);
    coons__sink_puts(s, "_faces() = [\n");
    put_faces(s, p->tri, p->nt);
    coons__sink_puts(s, "];\nmodule ");
    coons__sink_puts(s, p->id);
    coons__sink_puts(s, "(t = $t) {\n  polyhedron(points = ");
    put_node_name(s, p, p->nn - 1);
    coons__sink_puts(s, "(t), faces = ");
    coons__sink_puts(s, p->id);
    coons__sink_puts(s, "_faces(), convexity = 10);\n}\n");
}

static coons_status write_anim(const coons_mesh *unused, const coons__wopts *o, coons__sink *s)
{
    /* The job's mesh pointer carries the animation (see write_scad_anim). */
    const anim *a = (const anim *)(const void *)unused;
    coons__scad_header(s, o);
    coons__sink_puts(s, "// A metamorphosis: ");
    coons__sink_puts(s, a->model);
    coons__sink_puts(s, "(t) draws the model at time t in [0, 1]; the call at the end passes\n"
                        "// $t, so View > Animate plays it. Each morph blends its keys' vertex "
                        "arrays\n// with its path's weights; faces are clockwise seen from "
                        "outside.\n");
    for (size_t i = 0; i < a->np && coons__sink_ok(s); i++) put_part(s, &a->parts[i], i);
    coons__sink_puts(s, "\nmodule ");
    coons__sink_puts(s, a->model);
    coons__sink_puts(s, "(t = $t) {\n  union() {\n");
    for (size_t i = 0; i < a->np; i++) {
        coons__sink_puts(s, "    ");
        coons__sink_puts(s, a->parts[i].id);
        coons__sink_puts(s, a->parts[i].morph ? "(t);\n" : "();\n");
    }
    coons__sink_puts(s, "  }\n}\n\n");
    coons__sink_puts(s, a->model);
    coons__sink_puts(s, "($t);\n");
    return s->status;
}

/* Unique identifiers, as scad.c names parts: MODEL_BODY, then _2, _3 ... */
static void unique_id(anim *a, size_t i, const char *name)
{
    char base[IDENT_CAP - 24];
    coons__scad_part_identifier(base, sizeof base, a->model, name);
    snprintf(a->parts[i].id, IDENT_CAP, "%s", base);
    for (unsigned long k = 2;; k++) {
        int clash = strcmp(a->parts[i].id, a->model) == 0;
        for (size_t j = 0; j < i && !clash; j++) clash = strcmp(a->parts[j].id, a->parts[i].id) == 0;
        if (!clash) break;
        snprintf(a->parts[i].id, IDENT_CAP, "%s_%lu", base, k);
    }
}

static coons_status build(const coons_model *m, long body, const coons_sample_options *so,
                          const char *model_name, anim *a, coons_error *err)
{
    coons__sample_opts o;
    coons_status st = coons__sample_opts_resolve(so, &o, err);
    if (st) return st;
    if (!(o.tolerance > 0)) o.tolerance = coons_model_tolerance(m);
    a->tolerance = o.tolerance;
    size_t nb = coons_model_body_count(m), first = body >= 0 ? (size_t)body : 0;
    size_t last = body >= 0 ? (size_t)body + 1 : nb;
    if (body >= 0 && (size_t)body >= nb)
        return coons__error_set(err, COONS_E_INVALID, "no body %ld", body);
    coons__scad_identifier(a->model, sizeof a->model, model_name);
    if (!(a->parts = coons__calloc(last - first, sizeof *a->parts))) return coons__error_nomem(err);
    for (size_t i = first; i < last && !st; i++) {
        part *p = &a->parts[a->np++];
        const coons_body *b = coons_model_body(m, i);
        const char *name = coons_model_body_name(m, i);
        unique_id(a, a->np - 1, name);
        p->morph = has_morph(b);
        if (p->morph) {
            st = morph_faces(b, &o, name, p, err);
            size_t root = 0;
            if (!st) st = build_node(p, b, &root, err);
            o.max_triangles -= o.max_triangles > p->nt ? p->nt : o.max_triangles;
        } else {
            coons_mesh *mesh = NULL;
            size_t used = 0;
            st = coons_mesh_new(&mesh, err);
            if (!st) st = coons__body_sample_into(b, &o, name, mesh, &used, err);
            if (!st) {
                p->nv = coons_mesh_vertex_count(mesh);
                p->nt = coons_mesh_triangle_count(mesh);
                p->tri = coons__malloc_array(p->nt, 3 * sizeof *p->tri);
                p->xyz = coons__malloc_array(p->nv, 3 * sizeof *p->xyz);
                if (!p->tri || !p->xyz)
                    st = coons__error_nomem(err);
                else {
                    memcpy(p->tri, coons_mesh_triangles(mesh), 3 * p->nt * sizeof *p->tri);
                    memcpy(p->xyz, coons_mesh_vertices(mesh), 3 * p->nv * sizeof *p->xyz);
                }
            }
            coons_mesh_free(mesh);
            o.max_triangles -= used < o.max_triangles ? used : o.max_triangles;
        }
    }
    return st;
}

static coons_status write_scad_anim(const coons_model *m, long body,
                                    const coons_sample_options *so, const char *path, FILE *fp,
                                    const coons_write_options *wo, coons_error *err)
{
    if (!m) return coons__error_set(err, COONS_E_INVALID, "scad animation: model is NULL");
    coons__write_job job;
    coons_status st = coons__write_prepare(&job, 1, COONS_FORMAT_SCAD, COONS_MESH_KIND_SURFACE,
                                           wo, err);
    if (st) return st;
    anim a;
    memset(&a, 0, sizeof a);
    st = build(m, body, so, job.o.name, &a, err);
    if (!st) {
        /* The machinery of atomic.c writes one row's writer over one mesh:
         * a row whose writer is write_anim, handed the animation as its
         * mesh pointer (write_anim casts it back). */
        coons__format_row row = *job.row;
        row.write_surface = write_anim;
        job.row = &row;
        job.surface = (const coons_mesh *)(const void *)&a;
        job.volume = NULL;
        st = path ? coons__write_path(&job, path, wo, err) : coons__write_stream(&job, fp, wo, err);
    }
    free_anim(&a);
    return st;
}

coons_status coons_model_write_scad_animation(const coons_model *m, long body,
                                              const coons_sample_options *so, const char *path,
                                              const coons_write_options *wo, coons_error *err)
{
    if (!path || !path[0]) return coons__error_set(err, COONS_E_INVALID, "no output path given");
    return write_scad_anim(m, body, so, path, NULL, wo, err);
}

coons_status coons_model_write_scad_animation_stream(const coons_model *m, long body,
                                                     const coons_sample_options *so, FILE *fp,
                                                     const coons_write_options *wo,
                                                     coons_error *err)
{
    if (!fp) return coons__error_set(err, COONS_E_INVALID, "no output stream given");
    return write_scad_anim(m, body, so, NULL, fp, wo, err);
}
