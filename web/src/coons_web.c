/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The WebAssembly module's entry points (issue 29): a thin client of
 * <coons.h>, like coons2stl, whose outputs it reproduces byte for byte
 * with coons2stl's default options: the model loaded from memory, its
 * solid (coons_model_solidify(), the model's tolerance) written as binary
 * STL, OFF or OpenSCAD (the animation when the model has morphs, as
 * coons2stl writes it without --time), its volume mesh (hex8) as VTU, MSH
 * or INP, refused like coons2stl when a cell is inverted. Outputs go to a
 * memory stream; the page reads them with cw_out_data()/cw_out_size().
 * Without CGAL (the C core alone) a union that needs it is refused with the
 * library's message, as coons2stl refuses it.
 */
#define _POSIX_C_SOURCE 200809L /* open_memstream */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <coons.h>

#ifdef __EMSCRIPTEN__
#include <emscripten.h>
#define CW_EXPORT EMSCRIPTEN_KEEPALIVE
#else
#define CW_EXPORT
#endif

static coons_error last_error;
static char *out_data;
static size_t out_size;
/* the preview mesh: vertices (xyz doubles) and triangles (3 uint32 each) */
static coons_mesh *preview;

static void clear_output(void)
{
    free(out_data);
    out_data = NULL;
    out_size = 0;
}

CW_EXPORT const char *cw_error_message(void) { return last_error.message; }
CW_EXPORT const char *cw_error_path(void) { return last_error.path; }
CW_EXPORT int cw_error_line(void) { return last_error.line; }
CW_EXPORT int cw_error_column(void) { return last_error.column; }
CW_EXPORT const char *cw_out_data(void) { return out_data; }
CW_EXPORT size_t cw_out_size(void) { return out_size; }
CW_EXPORT void cw_out_free(void) { clear_output(); }
CW_EXPORT const char *cw_version(void) { return coons_version_string(); }

static void set_error(const char *message)
{
    memset(&last_error, 0, sizeof last_error);
    last_error.code = COONS_E_INVALID;
    snprintf(last_error.message, sizeof last_error.message, "%s", message);
}

/* The model from `size` bytes of JSON; NULL on error (cw_error_*()). */
CW_EXPORT coons_model *cw_load(const char *data, size_t size, const char *name)
{
    coons_model *m = NULL;
    memset(&last_error, 0, sizeof last_error);
    if (coons_model_load_memory(data, size, name && name[0] ? name : NULL, NULL, &m,
                                &last_error) != COONS_OK)
        return NULL;
    return m;
}

CW_EXPORT void cw_free(coons_model *m) { coons_model_free(m); }
CW_EXPORT double cw_tolerance(const coons_model *m) { return coons_model_tolerance(m); }
CW_EXPORT size_t cw_body_count(const coons_model *m) { return coons_model_body_count(m); }
CW_EXPORT size_t cw_morph_count(const coons_model *m) { return coons_model_morph_count(m); }
CW_EXPORT const char *cw_units(const coons_model *m) { return coons_model_units(m); }

CW_EXPORT int cw_set_time(coons_model *m, double t)
{
    memset(&last_error, 0, sizeof last_error);
    return coons_model_set_time(m, t, &last_error);
}

/* The solid of coons2stl -o: every body, repaired and united as the model
 * says, sampled at `tolerance` (<= 0: the model's), or, with `resolution`
 * > 0, on a fixed lattice of that many intervals along u, v, w, unmeasured
 * (a preview). */
static coons_status make_solid(const coons_model *m, double tolerance, unsigned resolution,
                               coons_mesh **out)
{
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.tolerance = tolerance > 0 ? tolerance : coons_model_tolerance(m);
    if (resolution) {
        so.resolution = resolution;
        so.flags = COONS_SAMPLE_UNMEASURED;
    }
    coons_csg_options copts = COONS_CSG_OPTIONS_INIT;
    copts.repair = 1;
    copts.threads = 1;
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    memset(&last_error, 0, sizeof last_error);
    return coons_model_solidify(m, &so, &copts, out, &rep, &last_error);
}

typedef struct sink {
    FILE *fp;
    char *buf;
    size_t size;
} sink;

static int sink_open(sink *s)
{
    clear_output();
    s->buf = NULL;
    s->size = 0;
    s->fp = open_memstream(&s->buf, &s->size);
    if (!s->fp) set_error("out of memory");
    return s->fp != NULL;
}

/* Keeps the output when rc is COONS_OK, else drops it. */
static int sink_close(sink *s, coons_status rc)
{
    if (fclose(s->fp) != 0 && rc == COONS_OK) {
        set_error("out of memory writing the output");
        rc = COONS_E_NOMEM;
    }
    if (rc != COONS_OK) {
        free(s->buf);
        return rc;
    }
    out_data = s->buf;
    out_size = s->size;
    return COONS_OK;
}

static coons_write_options write_options(const coons_model *m, const char *name)
{
    coons_write_options w = COONS_WRITE_OPTIONS_INIT;
    w.units = coons_model_units(m);
    w.name = name && name[0] ? name : NULL;
    return w;
}

/*
 * A surface format (COONS_FORMAT_STL_BINARY, _OFF, _SCAD) into the output
 * buffer; `name` is what coons2stl takes from the output file's name
 * ("dir/part.scad" -> "part"). 0 or the error's status.
 */
CW_EXPORT int cw_write_surface(const coons_model *m, int format, const char *name,
                               double tolerance)
{
    coons_write_options w = write_options(m, name);
    sink s;
    if (format == COONS_FORMAT_SCAD && coons_model_morph_count(m)) {
        coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
        so.tolerance = tolerance > 0 ? tolerance : coons_model_tolerance(m);
        if (!sink_open(&s)) return COONS_E_NOMEM;
        memset(&last_error, 0, sizeof last_error);
        coons_status rc =
            coons_model_write_scad_animation_stream(m, -1, &so, s.fp, &w, &last_error);
        return sink_close(&s, rc);
    }
    coons_mesh *mesh = NULL;
    coons_status rc = make_solid(m, tolerance, 0, &mesh);
    if (rc != COONS_OK) {
        coons_mesh_free(mesh);
        return rc;
    }
    if (!sink_open(&s)) {
        coons_mesh_free(mesh);
        return COONS_E_NOMEM;
    }
    rc = coons_mesh_write_stream(mesh, s.fp, (coons_format)format, &w, &last_error);
    coons_mesh_free(mesh);
    return sink_close(&s, rc);
}

/* Whether a part has an inverted cell: coons2stl refuses to write it
 * without --allow-inverted (the message names the body and where). */
static int refuse_inverted(const coons_volume_mesh *vm)
{
    for (size_t p = 0; p < coons_volume_mesh_part_count(vm); p++) {
        coons_volume_quality q = COONS_VOLUME_QUALITY_INIT;
        if (coons_volume_mesh_quality(vm, p, &q, NULL) != COONS_OK || !q.inverted) continue;
        memset(&last_error, 0, sizeof last_error);
        last_error.code = COONS_E_INVALID;
        snprintf(last_error.message, sizeof last_error.message,
                 "body '%s' has %zu inverted cell%s (scaled Jacobian <= 0; the worst, %.6g, at "
                 "(u, v, w) = (%.6g, %.6g, %.6g)): the body folds there",
                 coons_volume_mesh_part_name(vm, p), q.inverted, q.inverted == 1 ? "" : "s",
                 q.min_scaled_jacobian, q.worst_uvw[0], q.worst_uvw[1], q.worst_uvw[2]);
        return 1;
    }
    return 0;
}

/* A volume format (COONS_FORMAT_VTU, _MSH2, _INP) of the hex8 volume mesh
 * at the model's tolerance into the output buffer. 0 or the status. */
CW_EXPORT int cw_write_volume(const coons_model *m, int format, const char *name)
{
    coons_volume_options vo = COONS_VOLUME_OPTIONS_INIT;
    vo.element = COONS_ELEMENT_HEX8;
    vo.tolerance = coons_model_tolerance(m);
    coons_volume_mesh *vm = NULL;
    memset(&last_error, 0, sizeof last_error);
    coons_status rc = coons_model_volume_mesh(m, &vo, &vm, &last_error);
    if (rc != COONS_OK) return rc;
    if (refuse_inverted(vm)) {
        coons_volume_mesh_free(vm);
        return COONS_E_INVALID;
    }
    coons_write_options w = write_options(m, name);
    sink s;
    if (!sink_open(&s)) {
        coons_volume_mesh_free(vm);
        return COONS_E_NOMEM;
    }
    rc = coons_volume_mesh_write_stream(vm, s.fp, (coons_format)format, &w, &last_error);
    coons_volume_mesh_free(vm);
    return sink_close(&s, rc);
}

/* The mesh the page shows: the solid at `tolerance` (<= 0: the model's),
 * kept until the next call; its arrays through cw_preview_*(). A union
 * that needs CGAL, which the C core refuses (as coons2stl does), is shown
 * as its bodies' shells, unmerged: cw_preview_united() is then 0 and
 * cw_error_message() says why. */
static int preview_united;

CW_EXPORT int cw_preview(const coons_model *m, double tolerance, unsigned resolution)
{
    coons_mesh_free(preview);
    preview = NULL;
    preview_united = 1;
    coons_status rc = make_solid(m, tolerance, resolution, &preview);
    if (rc != COONS_E_UNSUPPORTED || coons_csg_is_available()) return rc;
    coons_mesh_free(preview);
    preview = NULL;
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.tolerance = tolerance > 0 ? tolerance : coons_model_tolerance(m);
    if (resolution) {
        so.resolution = resolution;
        so.flags = COONS_SAMPLE_UNMEASURED;
    }
    coons_error why = last_error;
    /* each body alone (coons_model_sample() refuses overlapping bodies too) */
    rc = coons_mesh_new(&preview, &last_error);
    for (size_t i = 0; rc == COONS_OK && i < coons_model_body_count(m); i++) {
        coons_mesh *one = NULL;
        rc = coons_body_sample(coons_model_body(m, i), &so, coons_model_body_name(m, i), &one,
                               &last_error);
        if (rc == COONS_OK)
            rc = coons_mesh_add_part(preview, coons_model_body_name(m, i), coons_mesh_vertices(one),
                                     coons_mesh_vertex_count(one), coons_mesh_triangles(one),
                                     coons_mesh_triangle_count(one), &last_error);
        coons_mesh_free(one);
    }
    if (rc != COONS_OK) return rc;
    last_error = why;
    preview_united = 0;
    return COONS_OK;
}

CW_EXPORT int cw_preview_united(void) { return preview_united; }

CW_EXPORT size_t cw_preview_vertex_count(void)
{
    return preview ? coons_mesh_vertex_count(preview) : 0;
}
CW_EXPORT size_t cw_preview_triangle_count(void)
{
    return preview ? coons_mesh_triangle_count(preview) : 0;
}
CW_EXPORT const double *cw_preview_vertices(void)
{
    return preview ? coons_mesh_vertices(preview) : NULL;
}
CW_EXPORT const uint32_t *cw_preview_triangles(void)
{
    return preview ? coons_mesh_triangles(preview) : NULL;
}

/*
 * The interior (seed 000, Fig. 2-6): the isoparametric surfaces
 * `direction` (0 u, 1 v, 2 w) = values[0..n) of every body with each body's
 * boundary (coons_model_iso_surfaces(), COONS_ISO_WITH_BOUNDARY: body k's
 * boundary is part k (n + 1), its surfaces the n parts after it), and det J
 * at every vertex (coons_body_eval_jacobian() at the vertex's parameters),
 * kept until the next call. 0 or the error's status.
 */
static coons_mesh *iso;
static double *iso_detj;

CW_EXPORT int cw_iso(const coons_model *m, int direction, const double *values, size_t n,
                     double tolerance)
{
    coons_mesh_free(iso);
    iso = NULL;
    free(iso_detj);
    iso_detj = NULL;
    coons_iso_request *req = malloc((n ? n : 1) * sizeof *req);
    if (!req) {
        set_error("out of memory");
        return COONS_E_NOMEM;
    }
    for (size_t i = 0; i < n; i++) {
        req[i].direction = direction;
        req[i].value = values[i];
    }
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.tolerance = tolerance > 0 ? tolerance : coons_model_tolerance(m);
    memset(&last_error, 0, sizeof last_error);
    coons_status rc =
        coons_model_iso_surfaces(m, req, n, &so, COONS_ISO_WITH_BOUNDARY, &iso, &last_error);
    free(req);
    if (rc != COONS_OK) return rc;
    size_t nv = coons_mesh_vertex_count(iso);
    const double *uvw = coons_mesh_vertex_parameters(iso);
    iso_detj = malloc((nv ? nv : 1) * sizeof *iso_detj);
    if (!iso_detj || !uvw) {
        set_error(iso_detj ? "the surfaces carry no parameters" : "out of memory");
        return iso_detj ? COONS_E_INVALID : COONS_E_NOMEM;
    }
    for (size_t p = 0; p < coons_mesh_part_count(iso); p++) {
        size_t tf, tc, vf, vc;
        coons_mesh_part_range(iso, p, &tf, &tc, &vf, &vc);
        const coons_body *b = coons_model_body(m, p / (n + 1));
        for (size_t v = vf; v < vf + vc; v++) {
            double x[3], jac[3][3];
            iso_detj[v] = coons_body_eval_jacobian(b, uvw[3 * v], uvw[3 * v + 1], uvw[3 * v + 2],
                                                   x, jac);
        }
    }
    return COONS_OK;
}

CW_EXPORT size_t cw_iso_vertex_count(void) { return iso ? coons_mesh_vertex_count(iso) : 0; }
CW_EXPORT size_t cw_iso_triangle_count(void) { return iso ? coons_mesh_triangle_count(iso) : 0; }
CW_EXPORT const double *cw_iso_vertices(void) { return iso ? coons_mesh_vertices(iso) : NULL; }
CW_EXPORT const uint32_t *cw_iso_triangles(void) { return iso ? coons_mesh_triangles(iso) : NULL; }
CW_EXPORT const double *cw_iso_detj(void) { return iso_detj; }
CW_EXPORT size_t cw_iso_part_count(void) { return iso ? coons_mesh_part_count(iso) : 0; }
/* The triangle range of part i: first, count. */
CW_EXPORT size_t cw_iso_part_first(size_t i)
{
    size_t tf = 0, tc = 0, vf = 0, vc = 0;
    if (iso) coons_mesh_part_range(iso, i, &tf, &tc, &vf, &vc);
    return tf;
}
CW_EXPORT size_t cw_iso_part_triangles(size_t i)
{
    size_t tf = 0, tc = 0, vf = 0, vc = 0;
    if (iso) coons_mesh_part_range(iso, i, &tf, &tc, &vf, &vc);
    return tc;
}

/*
 * The cells of a lattice: the 12 boundary edges of every body's unit cube
 * of parameters, each sampled at n + 1 points by coons_body_eval() (the
 * points of the body itself, not of a mesh), kept until the next call.
 * Body b's edge e, point s (0..n) is at ((b 12 + e)(n + 1) + s) 3 in
 * cw_cells_data(): edges 0-3 along u at (v, w) = (0,0) (1,0) (0,1) (1,1),
 * 4-7 along v at (u, w) = (0,0) (1,0) (0,1) (1,1), 8-11 along w at
 * (u, v) = (0,0) (1,0) (0,1) (1,1); the parameter of point s is s / n.
 * Returns the number of points, 0 on error (cw_error_message()).
 */
static double *cells;

CW_EXPORT size_t cw_cells(const coons_model *m, int n)
{
    free(cells);
    cells = NULL;
    size_t nb = coons_model_body_count(m);
    if (n < 1 || n > 4096) {
        set_error("the samples per edge must be 1 to 4096");
        return 0;
    }
    size_t np = nb * 12 * (size_t)(n + 1);
    cells = malloc((np ? np : 1) * 3 * sizeof *cells);
    if (!cells) {
        set_error("out of memory");
        return 0;
    }
    double *x = cells;
    for (size_t b = 0; b < nb; b++) {
        const coons_body *body = coons_model_body(m, b);
        for (int e = 0; e < 12; e++) {
            int dir = e / 4; /* the parameter along the edge */
            double a = e & 1, c = (e >> 1) & 1; /* the other two, in order */
            for (int s = 0; s <= n; s++, x += 3) {
                double t = (double)s / n, q[3];
                q[dir] = t;
                q[dir == 0 ? 1 : 0] = a;
                q[dir == 2 ? 1 : 2] = c;
                coons_body_eval(body, q[0], q[1], q[2], x);
            }
        }
    }
    memset(&last_error, 0, sizeof last_error);
    return np;
}

CW_EXPORT const double *cw_cells_data(void) { return cells; }
