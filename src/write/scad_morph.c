/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The OpenSCAD animation of a model with morph bodies (seed 000 section 4,
 * Fig. 10; outputs.md "Metamorphosis"): every morph is written as the
 * vertex arrays of its keys on the one lattice and face list of its whole
 * path (src/mesh/morph_lattice.c plans them and evaluates the keys), and a
 * function of the time t that blends them with the path's weights in
 * OpenSCAD itself; the top-level call passes $t, so View > Animate plays
 * the metamorphosis. Other bodies are plain polyhedra, united with the
 * morphs by OpenSCAD's union(). Modules are named as scad.c names them:
 * the model NAME, each body NAME_BODY (coons__scad_part_identifier()).
 *
 * Exactness: the morph is a pointwise blend, so a frame's vertex is
 * sum_k W_k(t) K_k(u,v,w) at the vertex's lattice parameters. The keys'
 * values are those of the body grid evaluator at each vertex alone
 * (morph_lattice.c), as a frame's vertices are; the weights are written
 * as the sums morph.c evaluates (morph.h), in the same order, and the
 * blend is summed key by key in key order as morph.c's grid does (weights
 * 0 add nothing). Affine wrappers of morphs are applied after the blend,
 * as body_transformed.c does. So `openscad -D '$t=T'` gives the vertices
 * of `coons2stl --time T` (same lattice, same face list), to the printed
 * digits.
 */
#include "writer.h"

#include "body_impl.h"
#include "coons/version.h"
#include "mesh_impl.h"
#include "morph_lattice.h"
#include "sampling.h"
#include "morph.h"

#define IDENT_CAP COONS__SCAD_IDENT_MAX

typedef struct part {
    char id[IDENT_CAP];
    int morph;
    size_t nv, nt;
    uint32_t *tri; /* plain parts: 3 nt, counter-clockwise from outside */
    double *xyz;   /* plain parts: 3 nv */
    coons__morph_lattice lat; /* morph parts: lattice, faces, the tree */
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
    coons__morph_lattice_free(&p->lat);
}

static void free_anim(anim *a)
{
    for (size_t i = 0; i < a->np; i++) free_part(&a->parts[i]);
    coons__free(a->parts);
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
    const coons__morph_node *nd = &p->lat.nodes[i];
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
        coons__sink_puts(s, p->lat.nodes[nd->keys[k]].kind == COONS__MORPH_CONST ? "()" : "(t)");
    }
    put_fmt(s, ")\n  [for (v = [0 : %zu]) ", p->nv - 1, 0);
    for (size_t k = 0; k < n; k++) put_fmt(s, k ? " + W[%zu] * K%zu[v]" : "W[%zu] * K%zu[v]", k, k);
    coons__sink_puts(s, "];\n");
}

static void put_affine_node(coons__sink *s, const part *p, size_t i)
{
    const coons__morph_node *nd = &p->lat.nodes[i];
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
             "// frame: coons2stl --time T with the same -t and --resolution gives these\n"
             "// vertices and faces at t = T.\n",
             p->lat.n);
    coons__sink_puts(s, head);
    for (size_t i = 0; i < p->lat.nn && coons__sink_ok(s); i++) {
        const coons__morph_node *nd = &p->lat.nodes[i];
        if (nd->kind == COONS__MORPH_CONST) {
            coons__sink_puts(s, "function ");
            put_node_name(s, p, i);
            coons__sink_puts(s, "() = [\n");
            put_points(s, nd->pts, p->nv);
            coons__sink_puts(s, "];\n");
        } else if (nd->kind == COONS__MORPH_AFFINE) {
            put_affine_node(s, p, i);
        } else {
            put_morph_node(s, p, i);
        }
    }
    coons__sink_puts(s, "function ");
    coons__sink_puts(s, p->id);
    coons__sink_puts(s, "_faces() = [\n");
    put_faces(s, p->lat.tri, p->nt);
    coons__sink_puts(s, "];\nmodule ");
    coons__sink_puts(s, p->id);
    coons__sink_puts(s, "(t = $t) {\n  polyhedron(points = ");
    put_node_name(s, p, p->lat.nn - 1);
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
        p->morph = coons__body_has_morph(b);
        if (p->morph) {
            st = coons__morph_lattice_plan(b, &o, name, &p->lat, err);
            if (!st) st = coons__morph_lattice_tree(&p->lat, b, err);
            p->nv = p->lat.nv;
            p->nt = p->lat.nt;
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
