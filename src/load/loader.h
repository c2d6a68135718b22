/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The model loader: the model format, version 1 (man/man5/coons-model.5),
 * read into objects built with the public constructors only. What its
 * files share. Internal.
 *
 *   json.c          strict JSON: the validating scan and the tokens
 *   ld_errors.c     error positions, the JSON pointer of the value being
 *                   read, objects (members, need, expect, type)
 *   values.c        numbers, degrees, points and vectors, nets, knots,
 *                   blends, the data of tensor-product surfaces and volumes
 *   read_curve.c    the table of curve readers, one read_curve_*.c each
 *   read_patch.c    the table of patch readers, one read_patch_*.c each
 *   read_body.c     the table of body readers, one read_body*.c each
 *   read_ref.c      "define" and references {"ref": NAME, modifiers}, which
 *                   coons__ld_curve/_patch/_body hand over to it
 *   read_model.c    the top level and the two passes
 *   load.c          the entry points coons_model_load_file/_memory
 *
 * Two passes over the tokens. The consistency tolerance (1e-9 of the
 * diagonal of the box of ALL control points of the model, "Consistency")
 * is known only after the whole document has been read, so pass 1 checks
 * every value and accumulates that box, and pass 2 reads the same values
 * again and builds curves, patches and bodies with that tolerance. The
 * agreement checks (src/core/agree.h) are made by the readers before the
 * constructors repeat them, so that an error can point at the first of the
 * two disagreeing values.
 *
 * Adding a curve, patch or body type: one read_<kind>_<type>.c with its
 * reader, and one row in the table of read_<kind>.c; its name comes from
 * coons_<kind>_type_name().
 */
#ifndef COONS_LOADER_H
#define COONS_LOADER_H

#include "json.h"
#include "model_impl.h"

typedef struct coons__ld_name {
    char *name; /* NULL when the body has no "name" */
    size_t tok;
} coons__ld_name;

/* A definition of "define" (read_ref.c). */
typedef struct coons__ld_def {
    char *name;  /* the key, decoded */
    size_t tok;  /* the value */
    int kind;    /* COONS__LD_KIND_*, or -1 not known yet */
    int state;   /* 0 not reached, 1 being read (a cycle if reached again), 2 read */
    void *built; /* pass 2: the definition built once (its kind's object) */
} coons__ld_def;

enum { COONS__LD_KIND_NONE, COONS__LD_KIND_CURVE, COONS__LD_KIND_PATCH, COONS__LD_KIND_BODY };

/* A reference being followed: the definition and the reference's path. */
typedef struct coons__ld_via {
    size_t def;
    char *path;
} coons__ld_via;

/* The state of one load. */
typedef struct coons__ld {
    const coons__json *j;
    const char *buf;
    size_t len;
    const char *file;
    coons_error *err;
    char path[4096]; /* JSON pointer of the value being read */
    size_t plen;
    int build;   /* pass 2 */
    int bbox_on; /* points count towards the control box */
    double lo[3], hi[3];
    double ctol;
    size_t max_points;
    /* top level, read in pass 1 */
    size_t bodies_tok;
    double tolerance; /* 0: default */
    int op;
    size_t units_tok;
    coons__ld_name *names; /* one per body */
    /* definitions and references (read_ref.c) */
    size_t define_tok;
    coons__ld_def *defs; /* sorted by name */
    size_t ndefs;
    coons__ld_via *via;  /* the references being followed, outermost first */
    size_t depth;
    double xf[12];       /* pass 1: the composed transform of the references followed */
    int xf_on;
    size_t expanded, max_values; /* JSON values read through references, and the limit */
} coons__ld;

/* ---- errors and positions (ld_errors.c) -------------------------------------- */

/* Replaces control characters by '?' (names and keys quoted in messages). */
void coons__ld_sanitize(char *s);
/* Truncating copy into dst[cap]. */
void coons__ld_copy_trunc(char *dst, size_t cap, const char *src);
/* Fills L->err: code, file, line and column of offset, the current path, and
 * the message "file:line:column: path: msg". Returns code. */
coons_status coons__ld_fail_at(coons__ld *L, size_t offset, coons_status code, const char *msg);
/* The same at the start of token tok, with a formatted message. */
coons_status coons__ld_fail(coons__ld *L, size_t tok, coons_status code, const char *fmt, ...)
    COONS__PRINTF(4, 5);
/* coons__ld_fail() with "/key/part" on the path (an agreement error at
 * one part of an object of parts). */
coons_status coons__ld_fail_in(coons__ld *L, const char *key, const char *part, size_t tok,
                              coons_status code, const char *fmt, ...) COONS__PRINTF(6, 7);
/* rc of a constructor: OK, or "cannot build <what>: <its message>". */
coons_status coons__ld_built(coons__ld *L, size_t tok, coons_status rc, const char *what,
                             const coons_error *e);

/* ---- the path (ld_errors.c): push returns the length to pop back to -------- */

size_t coons__ld_push_key(coons__ld *L, const char *k);
size_t coons__ld_push_index(coons__ld *L, size_t i);
void coons__ld_pop(coons__ld *L, size_t old);

/* ---- words for messages (ld_errors.c) -------------------------------------- */

/* "an object", "a number", ... */
const char *coons__ld_kind(const coons__ld *L, size_t tok);
/* names (NULL-terminated) joined with ", ". */
void coons__ld_join(const char *const *names, char *out, size_t cap);
/* Sanitised, truncated text of a string value. */
void coons__ld_text_of(const coons__ld *L, size_t tok, char *out, size_t cap);
/* "(x, y, z)" */
void coons__ld_fmt3(char *b, size_t cap, const double p[3]);
/* Fills out[] with name(0), name(1), ... up to the first NULL and ends it
 * with NULL; returns the count. cap counts the NULL. */
size_t coons__ld_names(const char *(*name)(int), const char **out, size_t cap);

/* ---- objects (ld_errors.c) ------------------------------------------------- */

/* Value token of the first member `key` of object obj, or 0. */
size_t coons__ld_member(const coons__ld *L, size_t obj, const char *key);
/* Object obj has only the keys in names (NULL-terminated), each at most
 * once; val[i] = value token of names[i] or 0. blend_hint: the message for
 * a "blend" key where it is not allowed, or NULL. */
coons_status coons__ld_members(coons__ld *L, size_t obj, const char *what,
                               const char *const *names, size_t *val, const char *blend_hint);
/* val 0: "missing key". */
coons_status coons__ld_need(coons__ld *L, size_t obj, size_t val, const char *key,
                            const char *what);
coons_status coons__ld_expect(coons__ld *L, size_t tok, coons__json_type type, const char *desc);
/* The "type" of object obj, one of types[] (NULL-terminated): *out = its index. */
coons_status coons__ld_type_of_obj(coons__ld *L, size_t obj, const char *what,
                                   const char *const *types, int *out);

/* An object being read by a reader of the tables. */
typedef struct coons__ld_obj {
    size_t tok;     /* the object */
    size_t index;   /* bodies: the index in "bodies" */
    char what[48];  /* "a line curve", "a coons patch", "a body0" */
    char hint[128]; /* the message for a "blend" where none is allowed */
    char need[192]; /* "<what> takes <keys>", for a missing key */
} coons__ld_obj;

/* The "type" of object obj (kind: "a curve", ...) among types[], and the
 * record o of the object, its what "a <type><suffix>". */
coons_status coons__ld_typed(coons__ld *L, size_t obj, const char *kind,
                             const char *const *types, const char *suffix, int *type,
                             coons__ld_obj *o);
/* members() of o with the reader's keys, and o->need from them. */
coons_status coons__ld_keys(coons__ld *L, coons__ld_obj *o, const char *const *keys,
                            size_t *val);

/* ---- values (values.c) --------------------------------------------------- */

coons_status coons__ld_number(coons__ld *L, size_t tok, double *v);
/* An integer in [1, COONS_SPLINE_MAX_DEGREE]. */
coons_status coons__ld_degree(coons__ld *L, size_t tok, int *p);

enum { COONS__LD_POINT, COONS__LD_VECTOR, COONS__LD_WEIGHT };

/* [x, y, z] or [x, y]; a COONS__LD_POINT in pass 1 extends the box. */
coons_status coons__ld_vec(coons__ld *L, size_t tok, int leaf, double out[3]);

typedef struct coons__ld_netspec {
    int dims;            /* 1 (curve), 2 (surface), 3 (volume) */
    int leaf;            /* COONS__LD_* */
    const size_t *fixed; /* required shape (weights), or NULL */
    size_t min;          /* at least this many along each direction */
    int exact;           /* exactly min (dims 1) */
    size_t maxdir;       /* at most this many along each direction (Bezier degree), or 0 */
    const char *what;    /* "a line", "a bezier-surface", ... */
    const char *noun;    /* "points", "tangents", "weights" */
} coons__ld_netspec;

/* "s", "t" of a surface, "u", "v", "w" of a volume. */
const char *coons__ld_axis_name(int dims, int d);
/* A rectangular net of ns->dims nested arrays; *out is allocated (3 doubles
 * per point, 1 per weight) after the shape has been checked. */
coons_status coons__ld_net(coons__ld *L, size_t tok, const coons__ld_netspec *ns,
                           size_t shape[3], double **out);
/* coons__ld_net() of the value val of key `key`, with the key on the path. */
coons_status coons__ld_net_key(coons__ld *L, size_t val, const char *key,
                               const coons__ld_netspec *ns, size_t shape[3], double **out);
/* ncp + p + 1 knots of degree p; *out allocated. */
coons_status coons__ld_knots(coons__ld *L, size_t tok, int p, size_t ncp, double **out);
/* "linear" / "cubic" under the key "blend"; tok 0: linear. */
/* The string at `key` (pushed on the path) is keyword a (*out = 0) or b
 * (*out = 1); anything else is an error that names both. */
coons_status coons__ld_keyword(coons__ld *L, size_t tok, const char *key, const char *a,
                              const char *b, int *out);
coons_status coons__ld_blend(coons__ld *L, size_t tok, coons_blend *out);

/* Tensor-product data of surfaces (dims 2) and volumes (3): the values of
 * "points", "degree", "knots", "weights" (0 where absent). */
typedef struct coons__ld_tensor {
    int deg[3];
    size_t n[3];
    double *pts, *kn[3], *w; /* owned, coons__ld_tensor_free() */
} coons__ld_tensor;

coons_status coons__ld_tensor_read(coons__ld *L, const coons__ld_obj *o, int dims,
                                   int is_bspline, const size_t val[4], coons__ld_tensor *t);
void coons__ld_tensor_free(coons__ld_tensor *t);

/* ---- the readers --------------------------------------------------------- */

/* out NULL in pass 1. */
typedef coons_status (*coons__ld_curve_fn)(coons__ld *L, coons__ld_obj *o, coons_curve **out);
typedef coons_status (*coons__ld_patch_fn)(coons__ld *L, coons__ld_obj *o, coons_patch **out);
typedef coons_status (*coons__ld_body_fn)(coons__ld *L, coons__ld_obj *o, coons_body **out);

/* One row per type; the type's name is coons_<kind>_type_name(type). */
typedef struct coons__ld_curve_row {
    coons_curve_type type;
    coons__ld_curve_fn read;
} coons__ld_curve_row;
typedef struct coons__ld_patch_row {
    coons_patch_type type;
    coons__ld_patch_fn read;
} coons__ld_patch_row;
typedef struct coons__ld_body_row {
    coons_body_type type;
    coons__ld_body_fn read;
} coons__ld_body_row;

/* A curve, patch or body object of any type (the tables pick the reader). */
coons_status coons__ld_curve(coons__ld *L, size_t obj, coons_curve **out);
coons_status coons__ld_patch(coons__ld *L, size_t obj, coons_patch **out);
coons_status coons__ld_body(coons__ld *L, size_t obj, size_t index, coons_body **out);

/* Readers (read_curve_*.c, read_patch_*.c, read_body*.c). */
coons_status coons__ld_read_line(coons__ld *L, coons__ld_obj *o, coons_curve **out);
coons_status coons__ld_read_polyline(coons__ld *L, coons__ld_obj *o, coons_curve **out);
coons_status coons__ld_read_bezier(coons__ld *L, coons__ld_obj *o, coons_curve **out);
coons_status coons__ld_read_hermite(coons__ld *L, coons__ld_obj *o, coons_curve **out);
coons_status coons__ld_read_coons_cubic(coons__ld *L, coons__ld_obj *o, coons_curve **out);
coons_status coons__ld_read_clamped_cubic(coons__ld *L, coons__ld_obj *o, coons_curve **out);
coons_status coons__ld_read_bspline(coons__ld *L, coons__ld_obj *o, coons_curve **out);

coons_status coons__ld_read_bilinear(coons__ld *L, coons__ld_obj *o, coons_patch **out);
coons_status coons__ld_read_ruled(coons__ld *L, coons__ld_obj *o, coons_patch **out);
coons_status coons__ld_read_coons(coons__ld *L, coons__ld_obj *o, coons_patch **out);
coons_status coons__ld_read_hermite_coons(coons__ld *L, coons__ld_obj *o, coons_patch **out);
coons_status coons__ld_read_bezier_surface(coons__ld *L, coons__ld_obj *o, coons_patch **out);
coons_status coons__ld_read_bspline_surface(coons__ld *L, coons__ld_obj *o, coons_patch **out);
coons_status coons__ld_read_network(coons__ld *L, coons__ld_obj *o, coons_patch **out);

coons_status coons__ld_read_body0(coons__ld *L, coons__ld_obj *o, coons_body **out);
coons_status coons__ld_read_body1(coons__ld *L, coons__ld_obj *o, coons_body **out);
coons_status coons__ld_read_body2(coons__ld *L, coons__ld_obj *o, coons_body **out);
coons_status coons__ld_read_bezier_volume(coons__ld *L, coons__ld_obj *o, coons_body **out);
coons_status coons__ld_read_bspline_volume(coons__ld *L, coons__ld_obj *o, coons_body **out);
coons_status coons__ld_read_shell(coons__ld *L, coons__ld_obj *o, coons_body **out);
coons_status coons__ld_read_morph(coons__ld *L, coons__ld_obj *o, coons_body **out);

/* ---- shared by the Coons patch readers (read_patch_boundary.c) ------------ */

void coons__ld_free_curves(coons_curve **c, size_t n);
/* An object of the four curves t0 t1 s0 s1 under key `key` (a boundary or
 * cross); tokv gets their tokens. c is not used in pass 1. */
coons_status coons__ld_four_curves(coons__ld *L, size_t tok, const char *key, const char *what,
                                   coons_curve *c[4], size_t tokv[4]);
/* The agreement of the boundary corners, as an error at the first curve. */
coons_status coons__ld_patch_corners(coons__ld *L, coons_curve *const c[4], const size_t tokv[4]);

/* ---- shared by the body readers (read_body.c) ----------------------------- */

/* members() of a body (keys "type", "name", ...), its name (pass 1). */
coons_status coons__ld_body_keys(coons__ld *L, coons__ld_obj *o, const char *const *keys,
                                 size_t *val);
/* The object of parts under key (body1 "edges": 12 curves into c, body2
 * "faces": 6 patches into f); sub gets their tokens. */
coons_status coons__ld_body_parts(coons__ld *L, coons__ld_obj *o, size_t val, int is1,
                                  coons_curve *c[12], coons_patch *f[6], size_t sub[12]);
/* The constructor's own refusal after the readers' checks passed. */
coons_status coons__ld_body_built(coons__ld *L, coons__ld_obj *o, size_t val, const char *key,
                                  coons_status r, const coons_error *e);

 /* ---- definitions and references (read_ref.c) ----------------------------- */

/* Reads "define" (pass 1): the names, sorted, each once. */
coons_status coons__ld_defines(coons__ld *L, size_t tok);
/* Is obj an object with a "ref"? */
int coons__ld_is_ref(const coons__ld *L, size_t obj);
/* The reference obj where an object of kind (COONS__LD_KIND_*) stands;
 * index: the body's index in "bodies" (bodies at the top level only, else
 * (size_t)-1). *out (NULL in pass 1) gets a new object. */
coons_status coons__ld_ref(coons__ld *L, size_t obj, int kind, size_t index, void **out);
/* After the bodies: the definitions no body reached, read (pass 1, outside
 * the box) or built and dropped (pass 2). */
coons_status coons__ld_unused_defs(coons__ld *L);
/* " (in definition ..., referenced at ...)" for an error inside a
 * definition, or "". */
void coons__ld_via_text(const coons__ld *L, char *out, size_t cap);
void coons__ld_defs_free(coons__ld *L);

/* ---- the model (read_model.c) -------------------------------------------- */

/* Reads and builds the whole model from the tokens L->j. */
coons_status coons__ld_model(coons__ld *L, coons_model **out);

#endif
