/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Free-form deformation of a triangle mesh by a body (seed 000 sections 1
 * and 5: Coons bodies "can be easily utilized in FFD applications", after
 * Sederberg and Parry): a point p goes to B((p - lo) / (hi - lo)).
 *
 * Refinement by edge bisection with conforming templates: an edge is
 * marked when the image of its parametric midpoint lies farther than the
 * tolerance from the chord of its end images, and a triangle marks its
 * three edges when the image of its parametric centroid (or of the points
 * halfway between the centroid and its corners) lies farther than the
 * tolerance from the triangle of its corner images. "Farther than the
 * tolerance" is judged against 0.9 times it, as the sampler does: the margin
 * covers maxima between the samples. A triangle measured within it and left
 * whole is not measured again; the largest distance over the triangles of
 * the result is the measured deviation (coons_deform_report). Every marked edge gets
 * one midpoint, shared by both its triangles, and each triangle is split
 * by the template of its marked edges (1: two triangles, 2: three, 3:
 * four), keeping its winding; this repeats until nothing is marked. The
 * split depends on the edge alone, so a closed 2-manifold input stays
 * closed and 2-manifold, and with unchanged winding outward; through a
 * left-handed body (det J < 0) the winding is reversed at the end.
 *
 * Progress (coons_deform_options.progress, stage "deform"): round r (from
 * 0, at most 64) spans the fractions 1 - 2^-r to 1 - 2^-(r+1), its first
 * half the triangles measured, its second half the triangles split, so the
 * fraction never goes back; 1 at the end.
 */
#include <string.h>

#include "body_impl.h"
#include "mesh_impl.h"

typedef struct work {
    double *q, *x; /* parameters and images, 3 per vertex */
    size_t nv, cap_v;
    uint32_t *tri;
    size_t nt, cap_t;
    /* per triangle: its measured deviation, or -1 when not yet measured */
    float *dev;
    /* edge -> midpoint vertex (open addressing; key 0 is empty) */
    uint64_t *key;
    uint32_t *mid;  /* UINT32_MAX: measured and not split */
    float *edev;    /* the edge's measured squared deviation */
    size_t cap_e;
    const coons_body *b;
    double tol, limit; /* limit = 0.9 * tol */
    coons_error *err;
    /* the progress report: round r spans [base, base + span) */
    coons_progress_fn progress;
    void *userdata;
    double base, span, shown;
} work;

/* Reports the share `done` of the current round (0 to 1), every
 * PROGRESS_EVERY triangles; never backwards. */
#define PROGRESS_EVERY 4096
static void report_round(work *w, double done)
{
    if (!w->progress) return;
    double f = w->base + w->span * done;
    if (f < w->shown) return;
    w->shown = f;
    w->progress(w->userdata, "deform", f);
}

static uint64_t edge_key(uint32_t a, uint32_t b)
{
    uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
    return ((uint64_t)lo << 32 | hi) + 1;
}

static size_t slot(const work *w, uint64_t k)
{
    uint64_t h = k * 0x9e3779b97f4a7c15ull;
    size_t i = (size_t)(h >> 20) & (w->cap_e - 1);
    while (w->key[i] && w->key[i] != k) i = (i + 1) & (w->cap_e - 1);
    return i;
}

static coons_status reset_edges(work *w, size_t n)
{
    size_t cap = 16;
    while (cap < 4 * n) cap *= 2;
    coons__free(w->key);
    coons__free(w->mid);
    coons__free(w->edev);
    w->key = coons__calloc(cap, sizeof *w->key);
    w->mid = coons__malloc_array(cap, sizeof *w->mid);
    w->edev = coons__malloc_array(cap, sizeof *w->edev);
    w->cap_e = cap;
    return w->key && w->mid && w->edev ? COONS_OK : coons__error_nomem(w->err);
}

/* A new vertex at parameters q; x: its image if known, else NULL. */
static coons_status add_vertex(work *w, const double q[3], const double *x, uint32_t *id)
{
    if (w->nv == UINT32_MAX) return coons__error_set(w->err, COONS_E_LIMIT, "deform: too many vertices");
    if (w->nv == w->cap_v) {
        size_t cap = w->cap_v ? 2 * w->cap_v : 64;
        double *q2 = coons__realloc(w->q, cap * 3 * sizeof *q2);
        if (!q2) return coons__error_nomem(w->err);
        w->q = q2;
        double *x2 = coons__realloc(w->x, cap * 3 * sizeof *x2);
        if (!x2) return coons__error_nomem(w->err);
        w->x = x2;
        w->cap_v = cap;
    }
    memcpy(w->q + 3 * w->nv, q, 3 * sizeof *q);
    if (x)
        memcpy(w->x + 3 * w->nv, x, 3 * sizeof *x);
    else
        coons_body_eval(w->b, q[0], q[1], q[2], w->x + 3 * w->nv);
    *id = (uint32_t)w->nv++;
    return COONS_OK;
}

/* Squared distance from the image x of the edge's parametric midpoint q to
 * its chord. */
static double edge_dev2(const work *w, uint32_t a, uint32_t b, double q[3], double x[3])
{
    for (int d = 0; d < 3; d++) q[d] = 0.5 * (w->q[3 * a + d] + w->q[3 * b + d]);
    coons_body_eval(w->b, q[0], q[1], q[2], x);
    return coons__seg_dist2(x, w->x + 3 * a, w->x + 3 * b);
}

/* Largest squared distance from the images of the 4 inner points to the
 * triangle, stopping early once it exceeds the limit. */
static double face_dev2(const work *w, const uint32_t v[3])
{
    static const double BARY[4][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3},
                                      {2.0 / 3, 1.0 / 6, 1.0 / 6},
                                      {1.0 / 6, 2.0 / 3, 1.0 / 6},
                                      {1.0 / 6, 1.0 / 6, 2.0 / 3}};
    double worst = 0;
    for (int s = 0; s < 4 && worst <= w->limit * w->limit; s++) {
        double q[3], x[3];
        for (int d = 0; d < 3; d++)
            q[d] = BARY[s][0] * w->q[3 * v[0] + d] + BARY[s][1] * w->q[3 * v[1] + d] +
                   BARY[s][2] * w->q[3 * v[2] + d];
        coons_body_eval(w->b, q[0], q[1], q[2], x);
        worst = fmax(worst,
                     coons__tri_dist2(x, w->x + 3 * v[0], w->x + 3 * v[1], w->x + 3 * v[2]));
    }
    return worst;
}

/* Marks an edge for splitting (creating its midpoint once). */
static coons_status mark(work *w, uint32_t a, uint32_t b)
{
    uint64_t k = edge_key(a, b);
    size_t i = slot(w, k);
    if (w->key[i] && w->mid[i] != UINT32_MAX) return COONS_OK;
    double q[3];
    for (int d = 0; d < 3; d++) q[d] = 0.5 * (w->q[3 * a + d] + w->q[3 * b + d]);
    uint32_t id;
    coons_status st = add_vertex(w, q, NULL, &id);
    if (st) return st;
    if (!w->key[i]) w->edev[i] = 0.0f;
    w->key[i] = k;
    w->mid[i] = id;
    return COONS_OK;
}

/* The edge's squared deviation, measured once per round (its two triangles
 * share it); an edge beyond the limit is marked, its midpoint's image
 * kept. */
static coons_status measure_edge(work *w, uint32_t a, uint32_t b, double lim2, double *d2)
{
    uint64_t k = edge_key(a, b);
    size_t i = slot(w, k);
    if (w->key[i]) {
        *d2 = w->edev[i];
        return COONS_OK;
    }
    double q[3], x[3];
    *d2 = edge_dev2(w, a, b, q, x);
    uint32_t id = UINT32_MAX;
    if (*d2 > lim2) {
        coons_status st = add_vertex(w, q, x, &id);
        if (st) return st;
    }
    w->key[i] = k;
    w->mid[i] = id;
    w->edev[i] = (float)*d2;
    return COONS_OK;
}

static uint32_t midpoint(const work *w, uint32_t a, uint32_t b)
{
    size_t i = slot(w, edge_key(a, b));
    return w->key[i] ? w->mid[i] : UINT32_MAX;
}

static void put(uint32_t *t, size_t *n, uint32_t a, uint32_t b, uint32_t c)
{
    t[3 * *n] = a, t[3 * *n + 1] = b, t[3 * *n + 2] = c;
    ++*n;
}

/* One round: mark, then split. *changed: whether anything was split. */
static coons_status round_once(work *w, size_t max_triangles, int *changed)
{
    coons_status st = reset_edges(w, w->nt * 3 / 2 + 16);
    double lim2 = w->limit * w->limit;
    /* measuring is the first half of the round's share, splitting the second */
    double per = w->nt ? 0.5 / (double)w->nt : 0;
    for (size_t t = 0; t < w->nt && !st; t++) {
        if (t % PROGRESS_EVERY == 0) report_round(w, per * (double)t);
        if (w->dev[t] >= 0) continue; /* measured and left whole before */
        const uint32_t *v = w->tri + 3 * t;
        double worst = face_dev2(w, v);
        int all = worst > lim2;
        for (int e = 0; e < 3 && !st; e++) {
            double d2 = 0;
            if (all)
                st = mark(w, v[e], v[(e + 1) % 3]);
            else
                st = measure_edge(w, v[e], v[(e + 1) % 3], lim2, &d2);
            worst = fmax(worst, d2);
        }
        /* a triangle that needs splitting is measured again as its parts */
        w->dev[t] = worst > lim2 ? -1.0f : (float)sqrt(worst);
    }
    if (st) return st;
    size_t cap = 4 * w->nt, n = 0;
    uint32_t *out = coons__malloc_array(cap ? cap : 1, 3 * sizeof *out);
    float *dev = coons__malloc_array(cap ? cap : 1, sizeof *dev);
    if (!out || !dev) {
        coons__free(out);
        coons__free(dev);
        return coons__error_nomem(w->err);
    }
    *changed = 0;
    for (size_t t = 0; t < w->nt; t++) {
        if (t % PROGRESS_EVERY == 0) report_round(w, 0.5 + per * (double)t);
        const uint32_t *v = w->tri + 3 * t;
        uint32_t m[3];
        int k = 0, first = -1;
        for (int e = 0; e < 3; e++) {
            m[e] = midpoint(w, v[e], v[(e + 1) % 3]); /* m[e] on edge v[e] v[e+1] */
            if (m[e] != UINT32_MAX) k++;
        }
        size_t n0 = n;
        if (k == 0) {
            dev[n] = w->dev[t];
            put(out, &n, v[0], v[1], v[2]);
            continue;
        }
        *changed = 1;
        if (k == 3) {
            put(out, &n, v[0], m[0], m[2]);
            put(out, &n, m[0], v[1], m[1]);
            put(out, &n, m[2], m[1], v[2]);
            put(out, &n, m[0], m[1], m[2]);
            for (size_t i = n0; i < n; i++) dev[i] = -1.0f;
            continue;
        }
        /* rotate so that edge 0 (a b) is split and, with two, edge 1 too */
        for (int r = 0; r < 3; r++)
            if (m[r] != UINT32_MAX && (k == 1 || m[(r + 1) % 3] != UINT32_MAX)) first = r;
        uint32_t a = v[first], b = v[(first + 1) % 3], c = v[(first + 2) % 3];
        uint32_t mab = m[first], mbc = m[(first + 1) % 3];
        if (k == 1) {
            put(out, &n, a, mab, c);
            put(out, &n, mab, b, c);
        } else {
            put(out, &n, mab, b, mbc);
            put(out, &n, a, mab, mbc);
            put(out, &n, a, mbc, c);
        }
        for (size_t i = n0; i < n; i++) dev[i] = -1.0f;
    }
    coons__free(w->tri);
    coons__free(w->dev);
    w->tri = out;
    w->dev = dev;
    w->nt = n;
    w->cap_t = cap;
    if (n > max_triangles)
        return coons__error_set(w->err, COONS_E_LIMIT,
                                "deform: reaching the tolerance %g needs more than %zu triangles "
                                "(the limit)",
                                w->tol, max_triangles);
    return COONS_OK;
}

coons_status coons_body_deform_mesh(const coons_body *b, const coons_mesh *in, const double *lo,
                                    const double *hi, double tolerance, size_t max_triangles,
                                    coons_mesh **out, coons_error *err)
{
    return coons_body_deform_mesh_report(b, in, lo, hi, tolerance, max_triangles, out, NULL, err);
}

void coons_deform_options_init(coons_deform_options *o)
{
    const coons_deform_options d = COONS_DEFORM_OPTIONS_INIT;
    if (o) *o = d;
}

coons_status coons_body_deform_mesh_report(const coons_body *b, const coons_mesh *in,
                                           const double *lo, const double *hi, double tolerance,
                                           size_t max_triangles, coons_mesh **out,
                                           coons_deform_report *report, coons_error *err)
{
    coons_deform_options o = COONS_DEFORM_OPTIONS_INIT;
    o.tolerance = tolerance;
    o.max_triangles = max_triangles;
    o.lo = lo;
    o.hi = hi;
    return coons_body_deform(b, in, &o, out, report, err);
}

coons_status coons_body_deform(const coons_body *b, const coons_mesh *in,
                               const coons_deform_options *opts, coons_mesh **out,
                               coons_deform_report *report, coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "deform: out is NULL");
    *out = NULL;
    if (report && COONS__RECORD_CHECK(err, "deform report", report->version, COONS_DEFORM_REPORT))
        return COONS_E_INVALID;
    if (!opts) return coons__error_set(err, COONS_E_INVALID, "deform: options is NULL");
    /* version 1 has no `threads` */
    if (coons__record_version_check("deform options", opts->version, 1,
                                    COONS_DEFORM_OPTIONS_VERSION, "COONS_DEFORM_OPTIONS_INIT", err))
        return COONS_E_INVALID;
    unsigned threads = coons__record_threads(opts->version >= 2 ? opts->threads : 1);
    (void)threads;
    if (!b || !in) return coons__error_set(err, COONS_E_INVALID, "deform: NULL body or mesh");
    const double *lo = opts->lo, *hi = opts->hi;
    double tolerance = opts->tolerance;
    size_t max_triangles = opts->max_triangles;
    if (!(tolerance > 0) || !isfinite(tolerance))
        return coons__error_set(err, COONS_E_INVALID, "deform: the tolerance must be > 0");
    if (!max_triangles) max_triangles = COONS_MESH_MAX_TRIANGLES;
    size_t nv = coons_mesh_vertex_count(in), nt = coons_mesh_triangle_count(in);
    const double *xyz = coons_mesh_vertices(in);
    double L[3], H[3];
    if (lo && hi) {
        v3_copy(L, lo);
        v3_copy(H, hi);
    } else {
        bbox_empty(L, H);
        for (size_t i = 0; i < nv; i++) bbox_add(L, H, xyz + 3 * i);
    }
    for (int d = 0; d < 3; d++)
        if (!(H[d] > L[d]) || !isfinite(H[d] - L[d]))
            return coons__error_set(err, COONS_E_INVALID,
                                    "deform: the frame is flat or not finite along %c "
                                    "(%.17g to %.17g)",
                                    "xyz"[d], L[d], H[d]);
    /* a point may lie outside by rounding of the frame: 1e-12 of the extent */
    size_t outside = 0, first = 0;
    for (size_t i = 0; i < nv; i++)
        for (int d = 0; d < 3; d++) {
            double s = (xyz[3 * i + d] - L[d]) / (H[d] - L[d]);
            if (s < -1e-12 || s > 1 + 1e-12 || !isfinite(s)) {
                if (!outside++) first = i;
                break;
            }
        }
    if (outside)
        return coons__error_set(err, COONS_E_DOMAIN,
                                "deform: %zu of the %zu points lie outside the frame (%.9g, %.9g, "
                                "%.9g) - (%.9g, %.9g, %.9g), the first is point %zu at (%.9g, %.9g, "
                                "%.9g)",
                                outside, nv, L[0], L[1], L[2], H[0], H[1], H[2], first,
                                xyz[3 * first], xyz[3 * first + 1], xyz[3 * first + 2]);
    work w;
    memset(&w, 0, sizeof w);
    w.b = b;
    w.tol = tolerance;
    w.limit = 0.9 * tolerance;
    w.err = err;
    w.progress = opts->progress;
    w.userdata = opts->userdata;
    w.span = 0.5;
    report_round(&w, 0);
    coons_status st = COONS_OK;
    for (size_t i = 0; i < nv && !st; i++) {
        double q[3];
        uint32_t id;
        for (int d = 0; d < 3; d++) q[d] = clamp01((xyz[3 * i + d] - L[d]) / (H[d] - L[d]));
        st = add_vertex(&w, q, NULL, &id);
    }
    if (!st && (!(w.tri = coons__malloc_array(nt ? nt : 1, 3 * sizeof *w.tri)) ||
                !(w.dev = coons__malloc_array(nt ? nt : 1, sizeof *w.dev))))
        st = coons__error_nomem(err);
    if (!st) {
        memcpy(w.tri, coons_mesh_triangles(in), nt * 3 * sizeof *w.tri);
        for (size_t t = 0; t < nt; t++) w.dev[t] = -1.0f;
        w.nt = nt;
    }
    unsigned rounds = 0;
    for (int changed = 1; !st && changed && rounds < 64;) {
        st = round_once(&w, max_triangles, &changed);
        rounds += !st && changed;
        /* round r (from 0) spans [1 - 2^-r, 1 - 2^-(r+1)) */
        w.base += w.span;
        w.span *= 0.5;
    }
    /* after 64 rounds that all split something, the last parts are measured */
    for (size_t t = 0; t < w.nt && !st; t++)
        if (w.dev[t] < 0) {
            double worst = face_dev2(&w, w.tri + 3 * t), q[3], x[3];
            for (int e = 0; e < 3; e++)
                worst = fmax(worst, edge_dev2(&w, w.tri[3 * t + e], w.tri[3 * t + (e + 1) % 3],
                                              q, x));
            w.dev[t] = (float)sqrt(worst);
        }
    double o[3], J[3][3];
    int reversed = !st && coons_body_eval_jacobian(b, 0.5, 0.5, 0.5, o, J) < 0;
    if (!st) {
        /* a left-handed body turns the winding inside out */
        if (reversed)
            for (size_t t = 0; t < w.nt; t++) {
                uint32_t x = w.tri[3 * t + 1];
                w.tri[3 * t + 1] = w.tri[3 * t + 2];
                w.tri[3 * t + 2] = x;
            }
        st = coons_mesh_new(out, err);
        if (!st) st = coons_mesh_add_part(*out, "deformed", w.x, w.nv, w.tri, w.nt, err);
        if (st) {
            coons_mesh_free(*out);
            *out = NULL;
        }
    }
    if (!st && w.progress) w.progress(w.userdata, "deform", 1.0);
    if (!st && report) {
        v3_copy(report->lo, L);
        v3_copy(report->hi, H);
        double worst = 0;
        for (size_t t = 0; t < w.nt; t++) worst = fmax(worst, (double)w.dev[t]);
        /* the float rounding of the stored distances, upwards */
        report->deviation = worst * (1 + 1e-7);
        report->triangles_in = nt;
        report->triangles_out = w.nt;
        report->vertices_in = nv;
        report->vertices_out = w.nv;
        report->rounds = rounds;
        report->reversed = reversed;
    }
    coons__free(w.dev);
    coons__free(w.q);
    coons__free(w.x);
    coons__free(w.tri);
    coons__free(w.key);
    coons__free(w.mid);
    coons__free(w.edev);
    return st;
}
