/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The boundary sampler's record (sample.c, with its measurement in
 * sample_measure.c and its options and limits in sample_limits.c), shared
 * with the control-lattice assembler (sample_lattice.c), which samples
 * several bodies and joins them along their shared faces by lattice index.
 * Internal. */
#ifndef COONS_SAMPLER_H
#define COONS_SAMPLER_H

#include "sampling.h"
#include "union_find.h"

typedef struct face_desc {
    int fixed, a, b; /* fixed direction; the face's (s,t) directions, a < b */
    int flip;        /* 1 when (a,b) is clockwise seen from outside a right-handed body */
    double val;
    const char *name;
} face_desc;

/* u0 u1 v0 v1 w0 w1 (sample.c). */
extern const face_desc coons__faces[6];

typedef struct sampler {
    const coons_body *body;
    const coons__sample_opts *o;
    const char *name;
    coons_error *err;
    double merge_tol;
    double *t[3];          /* lattice values, n[d] + 1 of them, t[d][0] = 0, t[d][n] = 1 */
    size_t n[3];           /* intervals per direction */
    unsigned char *mark[3];/* intervals to halve */
    double *need[3];       /* per interval: the factor by which the last scan
                              predicts it must shrink (budget prediction) */
    size_t nv;             /* raw lattice vertices */
    double *pos;           /* 3 * nv */
    uint32_t *uf;          /* union-find parents over raw vertices */
    uint32_t *ids[6];      /* raw vertex of each face lattice point, (na+1)*(nb+1) */
    unsigned char *diag[6];/* per cell: 0 = diagonal 00-11, 1 = diagonal 10-01 */
    uint32_t *tri;         /* 3 * nt representative raw ids */
    size_t nt;
    double *buf, *bs;      /* evaluation scratch */
    size_t buf_cap, bs_cap;
    int glued;             /* bit d: faces d0 and d1 coincide and are left out */
    int measured;          /* s->dev holds the final measurement */
    double dev;            /* largest deviation found by the last scan */
    /* Control lattices (sample_lattice.c): */
    unsigned skip;         /* bit f: face f is shared with another body: not
                              sampled beyond the points other faces hold,
                              not measured, not emitted */
    const double *start_t[3]; /* starting lattice (NULL: the body's own) */
    size_t start_n[3];
    int sign;              /* with skip: +1 / -1 the body's orientation */
    unsigned char *evaluated; /* per raw vertex: its position was computed */
    /* Scale invariance: positions are the body's points times `scale`, a
     * power of two (exact) that makes the body's extent about 1, so that
     * squared distances and the products of the distance tests neither
     * overflow nor underflow at any size the format allows; `tol` is the
     * tolerance in those units. */
    double scale, tol;
    /* Flat faces (flat.c): the triangles of face f are tri[face_tri[f] ..
     * face_tri[f+1]-1] (emit_cells(), in face order); bit f of flat_faces:
     * face f is meshed from its boundary polygon. */
    size_t face_tri[7];
    unsigned flat_faces;
    /* The parameters (u,v,w) of the Steiner points of flat faces, raw
     * vertices flat_v0 .. nv-1 (3 each; NULL when there are none). */
    double *flat_uvw;
    size_t flat_v0;
    /* bit f: face f, ruled between two straight lines, is meshed as one
     * strip of quads spanning its rulings (flat.c). */
    unsigned ruled_faces;
    /* Bounded work (sample.c): the last scan's prediction of the triangles
     * [0] and volume cells [1] the tolerance needs (pred: as refinement
     * would reach them, never below MIN_WIDTH; pred_free: the same without
     * that floor, for the tolerance to suggest), the deviation and lattice
     * it came from; refused: 1 (triangles) or 2 (cells) after a budget
     * refusal of adaptive sampling. */
    double pred[2], pred_free[2], pred_dev;
    size_t pred_n[3];
    int refused;
} sampler;

/* Internal flag of coons__sample_opts: every face keeps its lattice
 * triangles, also where it is flat (flat.c). */
#define COONS__SAMPLE_LATTICE_FACES (1u << 30)
/* Internal flag: a budget refusal suggests no tolerance (the sampler that
 * checks a suggestion, sample.c). */
#define COONS__SAMPLE_NO_SUGGEST (1u << 29)


/* A sampler for body b (name may be NULL); run it, read it, free it. */
void coons__sampler_init(sampler *s, const coons_body *b, const coons__sample_opts *o,
                         const char *name, coons_error *err);
/* Adaptive (or fixed-resolution) sampling: the lattice, its mesh, the
 * measured deviation. */
coons_status coons__sampler_run(sampler *s);
void coons__sampler_free(sampler *s);
/* Raw vertex of lattice point (ia, ib) of face f. */
static inline uint32_t coons__sampler_id(const sampler *s, int f, size_t ia, size_t ib)
{
    return s->ids[f][ia * (s->n[coons__faces[f].b] + 1) + ib];
}

/* ---- Between sample.c, sample_measure.c and sample_limits.c ---- */

/* 2^-20: the narrowest interval refinement makes. */
#define COONS__SAMPLE_MIN_WIDTH (1.0 / 1048576.0)

static inline double dmin(double a, double b) { return a < b ? a : b; }
static inline double dmax(double a, double b) { return a > b ? a : b; }

/* The position of raw vertex id's representative (union-find root). */
static inline const double *coons__sampler_rep(sampler *s, uint32_t id)
{
    return s->pos + 3 * (size_t)coons__uf_find(s->uf, id);
}

/* sample.c: grows a scratch array (contents dropped); evaluates face f on
 * av[0..na-1] x bv[0..nb-1] into out[(i*nb + j)*3], scaled; (re)allocates
 * the per-interval arrays of the lattice; adaptive or fixed sampling of
 * the lattice (no flat faces), with a budget refusal's message. */
coons_status coons__sampler_ensure(double **p, size_t *cap, size_t need, coons_error *err);
coons_status coons__sampler_eval_face(sampler *s, int f, const double *av, size_t na,
                                      const double *bv, size_t nb, double *out);
coons_status coons__sampler_alloc_lattices(sampler *s);
coons_status coons__sampler_adapt(sampler *s);

/* sample_measure.c: compares F with the mesh at the (r+1)^2 sub-samples of
 * every cell (s->dev: the largest distance; thr > 0: marks intervals to
 * halve and notes their need); halves the marked intervals. */
coons_status coons__sampler_scan(sampler *s, int r, double thr);
coons_status coons__sampler_refine(sampler *s, size_t *split);

/* sample_limits.c: the exact budget check of a build; the prediction
 * from the last scan (refused far above a budget); the message of an
 * adaptive budget refusal, with a tolerance checked to fit. */
coons_status coons__sampler_check_budget(sampler *s);
coons_status coons__sampler_predict_budget(sampler *s);
coons_status coons__sampler_refusal(sampler *s);

/* The body's point of raw vertex v (positions are scaled: see `scale`). */
static inline void coons__sampler_unscaled(const sampler *s, uint32_t v, double out[3])
{
    for (int d = 0; d < 3; d++) out[d] = s->pos[3 * (size_t)v + (size_t)d] / s->scale;
}

#endif
