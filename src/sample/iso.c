/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Isoparametric surfaces of a body: F(c, v, w), F(u, c, w), F(u, v, c)
 * for a constant c in [0,1] (seed 000, section 2.1, Fig. 2-6: the
 * "density" of the interior parametrisation, shown by the surfaces of
 * constant parameter the way Fig. 4 shows them).
 *
 * A surface is sampled on the lattice of its two free directions that the
 * boundary sampler settles on for the body (coons__body_sample_lattice(),
 * sample.c), so the surface at 0 or 1 is the boundary face point for point
 * (the same coons_body_eval_grid() call on the same values) and the
 * surfaces of one body fit the boundary mesh's density. Merging follows
 * sample.c: zero-length lattice lines and diagonals are collapsed with the
 * same "same place" tolerance (1e-9 of the surface's box diagonal plus 64
 * ulps of its largest coordinate), and two opposite sides that coincide
 * (a seam of a body closed on itself) are glued, as the sampler glues
 * coinciding opposite faces. */
#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "body_impl.h"
#include "coons_internal.h"
#include "sampling.h"
#include "mesh_impl.h"
#include "union_find.h"
#include "fmt.h"

static const char DIR_NAME[3] = {'u', 'v', 'w'};

void coons_iso_surface_name(const char *body, int direction, double value, char *out, size_t cap)
{
    if (!out || !cap) return;
    char num[COONS__FMT_MAX];
    coons__fmt_scope fs;
    if (isfinite(value) && coons__fmt_begin(&fs)) {
        coons__fmt_double(num, value);
        coons__fmt_end(&fs);
    } else {
        snprintf(num, sizeof num, "%s", isnan(value) ? "nan" : value > 0 ? "inf" : "-inf");
    }
    char d = direction >= 0 && direction < 3 ? DIR_NAME[direction] : '?';
    if (body)
        snprintf(out, cap, "%s.%c=%s", body, d, num);
    else
        snprintf(out, cap, "%c=%s", d, num);
}

static coons_status check_request(int direction, double value, coons_error *err)
{
    if (direction < 0 || direction > 2)
        return coons__error_set(err, COONS_E_INVALID,
                                "isoparametric direction %d is not 0 (u), 1 (v) or 2 (w)",
                                direction);
    if (!(value >= 0.0 && value <= 1.0))
        return coons__error_set(err, COONS_E_DOMAIN,
                                "isoparametric surface %c=%g: the value must lie in [0,1]",
                                DIR_NAME[direction], value);
    return COONS_OK;
}

/* One surface on a given lattice. */
typedef struct iso_job {
    const coons_body *body;
    int d, a, b;           /* fixed direction; free directions, F_a x F_b the normal */
    double value;
    const double *ta, *tb; /* lattice values of a and b */
    size_t na, nb;         /* intervals */
    const char *name;
    coons_error *err;
    double *pos, *uvw;     /* raw lattice points, (na+1)(nb+1) */
    uint32_t *uf, *tri, *map;
    double merge_tol;
} iso_job;

static inline uint32_t raw(const iso_job *j, size_t ia, size_t ib)
{
    return (uint32_t)(ia * (j->nb + 1) + ib);
}

static void merge_close(iso_job *j, uint32_t x, uint32_t y)
{
    uint32_t rx = coons__uf_find(j->uf, x), ry = coons__uf_find(j->uf, y);
    if (rx == ry || v3_dist(j->pos + 3 * (size_t)rx, j->pos + 3 * (size_t)ry) > j->merge_tol)
        return;
    coons__uf_link(j->uf, rx, ry);
}

static const double *rep(iso_job *j, uint32_t id)
{
    return j->pos + 3 * (size_t)coons__uf_find(j->uf, id);
}

/* Evaluates the lattice points and their parameters. */
static coons_status eval_points(iso_job *j, size_t np)
{
    const double *q[3];
    size_t c[3];
    q[j->d] = &j->value;
    c[j->d] = 1;
    q[j->a] = j->ta;
    c[j->a] = j->na + 1;
    q[j->b] = j->tb;
    c[j->b] = j->nb + 1;
    double *grid = coons__malloc_array(np, 3 * sizeof(double));
    if (!grid) return coons__error_nomem(j->err);
    coons_status st = coons_body_eval_grid(j->body, q[0], c[0], q[1], c[1], q[2], c[2], grid,
                                           j->err);
    if (!st && !coons__all_finite(grid, 3 * np))
        st = coons__error_set(j->err, COONS_E_INVALID,
                              "body '%s' evaluates to a non-finite point on surface %c=%g",
                              j->name, DIR_NAME[j->d], j->value);
    if (st) {
        coons__free(grid);
        return st;
    }
    for (size_t ia = 0; ia <= j->na; ia++)
        for (size_t ib = 0; ib <= j->nb; ib++) {
            size_t idx[3];
            idx[j->d] = 0;
            idx[j->a] = ia;
            idx[j->b] = ib;
            size_t g = (idx[0] * c[1] + idx[1]) * c[2] + idx[2];
            uint32_t r = raw(j, ia, ib);
            v3_copy(j->pos + 3 * (size_t)r, grid + 3 * g);
            double *p = j->uvw + 3 * (size_t)r;
            p[j->d] = j->value;
            p[j->a] = j->ta[ia];
            p[j->b] = j->tb[ib];
        }
    coons__free(grid);
    return COONS_OK;
}

/* Glues coinciding opposite sides, collapses zero-length lattice lines and
 * diagonals, and emits two triangles per cell, degenerate ones dropped;
 * returns the triangle count (representative raw ids in j->tri). */
static size_t mesh_cells(iso_job *j, size_t np)
{
    double lo[3], hi[3];
    bbox_empty(lo, hi);
    for (size_t i = 0; i < np; i++) bbox_add(lo, hi, j->pos + 3 * i);
    j->merge_tol = coons__same_place_tol(lo, hi);
    for (uint32_t i = 0; i < (uint32_t)np; i++) j->uf[i] = i;
    size_t na = j->na, nb = j->nb, k;
    for (k = 0; k <= nb; k++)
        if (v3_dist(j->pos + 3 * (size_t)raw(j, 0, k), j->pos + 3 * (size_t)raw(j, na, k)) >
            j->merge_tol)
            break;
    if (k > nb)
        for (k = 0; k <= nb; k++) coons__uf_union(j->uf, raw(j, 0, k), raw(j, na, k));
    for (k = 0; k <= na; k++)
        if (v3_dist(j->pos + 3 * (size_t)raw(j, k, 0), j->pos + 3 * (size_t)raw(j, k, nb)) >
            j->merge_tol)
            break;
    if (k > na)
        for (k = 0; k <= na; k++) coons__uf_union(j->uf, raw(j, k, 0), raw(j, k, nb));
    for (size_t ia = 0; ia <= na; ia++)
        for (size_t ib = 0; ib <= nb; ib++) {
            if (ia < na) merge_close(j, raw(j, ia, ib), raw(j, ia + 1, ib));
            if (ib < nb) merge_close(j, raw(j, ia, ib), raw(j, ia, ib + 1));
        }
    /* Diagonals are chosen (and collapsed) before any triangle is made, as
     * in sample.c, so a collapse in one cell is seen by its neighbours. */
    unsigned char *diag = (unsigned char *)j->map; /* na * nb <= np bytes of scratch */
    for (size_t p = 0; p < na; p++)
        for (size_t q = 0; q < nb; q++) {
            uint32_t i00 = raw(j, p, q), i10 = raw(j, p + 1, q);
            uint32_t i01 = raw(j, p, q + 1), i11 = raw(j, p + 1, q + 1);
            double d1 = v3_dist(rep(j, i00), rep(j, i11)), d2 = v3_dist(rep(j, i10), rep(j, i01));
            unsigned char dg = d2 < d1;
            diag[p * nb + q] = dg;
            if (dg)
                merge_close(j, i10, i01);
            else
                merge_close(j, i00, i11);
        }
    size_t nt = 0;
    for (size_t p = 0; p < na; p++)
        for (size_t q = 0; q < nb; q++) {
            uint32_t A = coons__uf_find(j->uf, raw(j, p, q));
            uint32_t B = coons__uf_find(j->uf, raw(j, p + 1, q));
            uint32_t C = coons__uf_find(j->uf, raw(j, p + 1, q + 1));
            uint32_t D = coons__uf_find(j->uf, raw(j, p, q + 1));
            uint32_t t[2][3] = {{A, B, C}, {A, C, D}};
            if (diag[p * nb + q]) {
                t[0][2] = D;
                t[1][0] = B;
            }
            for (int s = 0; s < 2; s++) {
                if (t[s][0] == t[s][1] || t[s][1] == t[s][2] || t[s][2] == t[s][0]) continue;
                memcpy(j->tri + 3 * nt++, t[s], sizeof t[s]);
            }
        }
    return nt;
}

/* Compacts the used vertices (in order of first use) and appends the part. */
static coons_status emit(iso_job *j, size_t np, size_t nt, coons_mesh *into)
{
    double *xyz = coons__malloc_array(np, 3 * sizeof(double));
    double *uvw = coons__malloc_array(np, 3 * sizeof(double));
    coons_status st = COONS_OK;
    if (!xyz || !uvw) {
        st = coons__error_nomem(j->err);
        goto done;
    }
    memset(j->map, 0xff, np * sizeof(uint32_t));
    uint32_t nv = 0;
    for (size_t i = 0; i < 3 * nt; i++) {
        uint32_t v = j->tri[i];
        if (j->map[v] == UINT32_MAX) {
            v3_copy(xyz + 3 * (size_t)nv, j->pos + 3 * (size_t)v);
            v3_copy(uvw + 3 * (size_t)nv, j->uvw + 3 * (size_t)v);
            j->map[v] = nv++;
        }
        j->tri[i] = j->map[v];
    }
    st = coons__mesh_add_part_uvw(into, j->name, xyz, uvw, nv, j->tri, nt, j->err);
done:
    coons__free(xyz);
    coons__free(uvw);
    return st;
}

/* The surface `direction` = value of body b on lattice t/n, appended to
 * `into` as part `name`; *triangles gets its triangle count. */
static coons_status iso_on_lattice(const coons_body *b, int direction, double value,
                                   double *const t[3], const size_t n[3], size_t budget,
                                   const char *name, coons_mesh *into, size_t *triangles,
                                   coons_error *err)
{
    iso_job j;
    memset(&j, 0, sizeof j);
    j.body = b;
    j.d = direction;
    j.a = (direction + 1) % 3;
    j.b = (direction + 2) % 3;
    j.value = value;
    j.ta = t[j.a];
    j.tb = t[j.b];
    j.na = n[j.a];
    j.nb = n[j.b];
    j.name = name;
    j.err = err;
    size_t cells = j.na * j.nb, np = (j.na + 1) * (j.nb + 1);
    if (2 * cells > budget)
        return coons__error_set(err, COONS_E_LIMIT,
                                "surface '%s' needs %zu triangles, more than the %zu left of "
                                "the limit; raise max_triangles (coons2stl --max-triangles N) "
                                "or loosen the tolerance",
                                name, 2 * cells, budget);
    if (np > UINT32_MAX)
        return coons__error_set(err, COONS_E_LIMIT, "surface '%s': more than %u vertices", name,
                                (unsigned)UINT32_MAX);
    j.pos = coons__malloc_array(np, 3 * sizeof(double));
    j.uvw = coons__malloc_array(np, 3 * sizeof(double));
    j.uf = coons__malloc_array(np, sizeof(uint32_t));
    j.map = coons__malloc_array(np, sizeof(uint32_t));
    j.tri = coons__malloc_array(cells ? cells : 1, 6 * sizeof(uint32_t));
    coons_status st = COONS_OK;
    if (!j.pos || !j.uvw || !j.uf || !j.map || !j.tri)
        st = coons__error_nomem(err);
    if (!st) st = eval_points(&j, np);
    if (!st) {
        size_t nt = mesh_cells(&j, np);
        st = emit(&j, np, nt, into);
        if (!st && triangles) *triangles = nt;
    }
    coons__free(j.pos);
    coons__free(j.uvw);
    coons__free(j.uf);
    coons__free(j.map);
    coons__free(j.tri);
    return st;
}

coons_status coons_body_iso_surface(const coons_body *b, int direction, double value,
                                    const coons_sample_options *opts, const char *name,
                                    coons_mesh *into, coons_error *err)
{
    if (!b || !into) return coons__error_set(err, COONS_E_INVALID, "no body or mesh given");
    coons_status st = check_request(direction, value, err);
    if (st) return st;
    coons__sample_opts o;
    if ((st = coons__sample_opts_resolve(opts, &o, err))) return st;
    if (!(o.tolerance > 0)) {
        double lo[3], hi[3];
        coons_body_control_bbox(b, lo, hi);
        double dg = bbox_diag(lo, hi);
        o.tolerance = dg > 0 ? 1e-3 * dg : 1e-3;
    }
    char buf[COONS_ISO_NAME_MAX];
    if (!name) {
        coons_iso_surface_name(NULL, direction, value, buf, sizeof buf);
        name = buf;
    }
    double *t[3];
    size_t n[3];
    if ((st = coons__body_sample_lattice(b, &o, name, t, n, NULL, err))) return st;
    st = iso_on_lattice(b, direction, value, t, n, o.max_triangles, name, into, NULL, err);
    for (int d = 0; d < 3; d++) coons__free(t[d]);
    return st;
}

/* One body's boundary (with parameters) and surfaces. */
static coons_status model_body(const coons_body *b, const char *bname,
                               const coons_iso_request *req, size_t nreq,
                               const coons__sample_opts *o, unsigned flags, size_t *budget,
                               coons_mesh *m, coons_error *err)
{
    coons__sample_opts oi = *o;
    oi.max_triangles = *budget;
    coons_status st;
    if (flags & COONS_ISO_WITH_BOUNDARY) {
        size_t used = 0;
        oi.flags |= COONS__SAMPLE_PARAMS;
        if ((st = coons__body_sample_into(b, &oi, bname, m, &used, err))) return st;
        *budget -= used;
        oi.flags = o->flags;
        oi.max_triangles = *budget;
    }
    if (!nreq) return COONS_OK;
    double *t[3];
    size_t n[3];
    if ((st = coons__body_sample_lattice(b, &oi, bname, t, n, NULL, err))) return st;
    for (size_t r = 0; r < nreq && !st; r++) {
        char name[COONS_ISO_NAME_MAX];
        coons_iso_surface_name(bname, req[r].direction, req[r].value, name, sizeof name);
        size_t used = 0;
        st = iso_on_lattice(b, req[r].direction, req[r].value, t, n, *budget, name, m, &used, err);
        *budget -= used;
    }
    for (int d = 0; d < 3; d++) coons__free(t[d]);
    return st;
}

coons_status coons_model_iso_surfaces(const coons_model *model, const coons_iso_request *req,
                                      size_t nreq, const coons_sample_options *opts,
                                      unsigned int flags, coons_mesh **out, coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "no output mesh pointer given");
    *out = NULL;
    if (!model) return coons__error_set(err, COONS_E_INVALID, "no model given");
    if (!req && nreq)
        return coons__error_set(err, COONS_E_INVALID, "no isoparametric surfaces given");
    if (flags & ~COONS_ISO_WITH_BOUNDARY)
        return coons__error_set(err, COONS_E_INVALID, "unknown isoparametric surface flags 0x%x",
                                flags & ~COONS_ISO_WITH_BOUNDARY);
    coons_status st;
    for (size_t r = 0; r < nreq; r++)
        if ((st = check_request(req[r].direction, req[r].value, err))) return st;
    coons__sample_opts o;
    if ((st = coons__sample_opts_resolve(opts, &o, err))) return st;
    if (!(o.tolerance > 0)) o.tolerance = coons_model_tolerance(model);
    coons_mesh *m;
    if ((st = coons_mesh_new(&m, err))) return st;
    size_t budget = o.max_triangles;
    for (size_t i = 0; i < coons_model_body_count(model) && !st; i++)
        st = model_body(coons_model_body(model, i), coons_model_body_name(model, i), req, nreq, &o,
                        flags, &budget, m, err);
    if (st) {
        coons_mesh_free(m);
        return st;
    }
    *out = m;
    return COONS_OK;
}
