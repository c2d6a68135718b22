/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The sampler's options and limits (sample.c): resolving the public options,
 * the triangle and cell budgets of a lattice, the prediction from the last
 * scan of what a tolerance needs (refused at once far above a budget), and
 * the refusal's message with a tolerance it has checked by sampling. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "body_impl.h"
#include "coons_internal.h"
#include "morph_lattice.h"
#include "sampler.h"
#include "union_find.h"

/* A lattice predicted above this many times a budget is refused before
 * refining (predict_budget). The prediction assumes the deviation falls
 * like h^2; halving overshoots it, so it is low: over every example and
 * tests/data model at tolerances 0.3 to 0.0003 (984 samplings), no round
 * predicted more than the final count (the spool at 1e-6: 5.2e7 predicted
 * from the first round, 5.0e7 on the 2048^3 lattice refinement reaches). */
#define PREDICT_MARGIN 2.0
/* A tolerance suggested by a budget refusal is checked by sampling to it:
 * within the whole of a budget up to SUGGEST_FULL, within SUGGEST_SHARE
 * of a larger one (a check that costs a fraction of a sampling at the
 * limit), in at most SUGGEST_TRIES tries at least SUGGEST_STEP apart. */
#define SUGGEST_FULL 1e6
#define SUGGEST_SHARE 0.125
#define SUGGEST_TRIES 6
#define SUGGEST_STEP 3.0

static size_t tri_estimate(const size_t n[3], unsigned skip)
{
    /* Two triangles per cell of the faces sampled, before degenerate ones
     * drop; the lattice sizes are bounded far below overflow by the caller. */
    size_t t = 0;
    for (int f = 0; f < 6; f++)
        if (!(skip & 1u << f)) t += 2 * n[coons__faces[f].a] * n[coons__faces[f].b];
    return t;
}

static coons_status limit_error(sampler *s, size_t need)
{
    if (s->o->resolution)
        return coons__error_set(s->err, COONS_E_LIMIT,
                                "body '%s': resolution %u gives %zu triangles, more than the "
                                "limit of %zu; raise max_triangles (coons2stl --max-triangles N) "
                                "or lower the resolution",
                                s->name, s->o->resolution, need, s->o->max_triangles);
    return coons__error_set(s->err, COONS_E_LIMIT,
                            "body '%s': sampling to tolerance %g needs more than %zu triangles "
                            "(the limit); raise max_triangles (coons2stl --max-triangles N) or "
                            "loosen the tolerance",
                            s->name, s->o->tolerance, s->o->max_triangles);
}

/* The triangles and volume cells refinement would reach from the
 * deviations the last scan measured (note_need), into s->pred (each
 * interval no narrower than COONS__SAMPLE_MIN_WIDTH) and s->pred_free (unbounded). */
static void predict(sampler *s)
{
    double m[3], mf[3];
    for (int d = 0; d < 3; d++) {
        m[d] = mf[d] = 0;
        for (size_t i = 0; i < s->n[d]; i++) {
            double most = (s->t[d][i + 1] - s->t[d][i]) / COONS__SAMPLE_MIN_WIDTH;
            m[d] += dmax(1.0, dmin(s->need[d][i], most));
            mf[d] += dmax(1.0, s->need[d][i]);
        }
    }
    s->pred[0] = s->pred_free[0] = 0;
    for (int f = 0; f < 6; f++)
        if (!(s->skip & 1u << f)) {
            s->pred[0] += 2 * m[coons__faces[f].a] * m[coons__faces[f].b];
            s->pred_free[0] += 2 * mf[coons__faces[f].a] * mf[coons__faces[f].b];
        }
    s->pred[1] = m[0] * m[1] * m[2];
    s->pred_free[1] = mf[0] * mf[1] * mf[2];
    s->pred_dev = s->dev;
    for (int d = 0; d < 3; d++) s->pred_n[d] = s->n[d];
}

coons_status coons__sampler_check_budget(sampler *s)
{
    size_t need = tri_estimate(s->n, s->skip);
    if (!(need > s->o->max_triangles)) return COONS_OK;
    if (s->o->resolution) return limit_error(s, need);
    /* Adaptive: the lattice of this round already exceeds the budget; the
     * last scan's prediction, when higher, is what the tolerance needs. */
    s->pred[0] = fmax(s->pred[0], (double)need);
    s->pred_free[0] = fmax(s->pred_free[0], (double)need);
    s->refused = 1;
    return COONS_E_LIMIT;
}

/* Bounded work: from the deviations the last coarse scan measured
 * (note_need), the interval counts refinement would reach, and the
 * triangles (and volume cells) they give. A request predicted above
 * PREDICT_MARGIN times a budget is refused at once, before the rounds
 * that would fill memory; one that may fit runs on to the exact checks
 * (check_budget, the volume mesh's cell count). */
coons_status coons__sampler_predict_budget(sampler *s)
{
    predict(s);
    double tri = s->pred[0], cells = s->pred[1];
    double tmax = (double)s->o->max_triangles, cmax = (double)s->o->max_cells;
    if (!(tri > PREDICT_MARGIN * tmax) && !(cmax > 0 && cells > PREDICT_MARGIN * cmax))
        return COONS_OK;
    s->refused = tri > PREDICT_MARGIN * tmax ? 1 : 2;
    return COONS_E_LIMIT;
}

/* x rounded up to two significant digits, as it would be typed. */
static double round_up2(double x)
{
    char b[32];
    double e = pow(10.0, floor(log10(x)) - 1);
    snprintf(b, sizeof b, "%.2g", ceil(x / e * (1 - 1e-12)) * e);
    double y = strtod(b, NULL);
    return y >= x * (1 - 1e-9) ? y : x;
}

/* The budget a suggested tolerance is checked against: all of a small one
 * (the check is cheap), SUGGEST_SHARE of a large one but not below
 * SUGGEST_FULL. */
static double suggest_budget(double budget)
{
    return budget <= SUGGEST_FULL ? budget : dmax(SUGGEST_FULL, SUGGEST_SHARE * budget);
}

/* Does sampling to tolerance tol fit suggest_budget() of s's budgets? Runs a
 * sampler like s at tol; *count: the count a refusal predicted, or 0. */
static coons_status fits(const sampler *s, double tol, int *ok, double *count)
{
    coons__sample_opts o = *s->o;
    o.tolerance = tol;
    o.max_triangles = (size_t)suggest_budget((double)o.max_triangles);
    o.max_cells = (size_t)suggest_budget((double)o.max_cells);
    o.flags |= COONS__SAMPLE_NO_SUGGEST;
    coons_error err = COONS_ERROR_INIT;
    sampler t;
    coons__sampler_init(&t, s->body, &o, s->name, &err);
    t.skip = s->skip;
    for (int d = 0; d < 3; d++) {
        t.start_t[d] = s->start_t[d];
        t.start_n[d] = s->start_n[d];
    }
    coons_status st = coons__sampler_adapt(&t);
    double cells = (double)t.n[0] * (double)t.n[1] * (double)t.n[2];
    *ok = st == COONS_OK && !(o.max_cells && cells > (double)o.max_cells);
    *count = t.refused ? t.pred_free[t.refused - 1] : 0;
    coons__sampler_free(&t);
    return st == COONS_E_NOMEM ? coons__error_nomem(s->err) : COONS_OK;
}

/* A budget refusal of adaptive sampling: the message names the tolerance,
 * the limit, the predicted count, and a tolerance verified to fit (sampled
 * within suggest_budget() of the limit) when one is found in a few tries. The count goes
 * about as 1 / tolerance (h^2 per face, two directions; cells as
 * tolerance^-3/2); a kink converges more slowly, so each failed try moves
 * on by at least SUGGEST_STEP. */
coons_status coons__sampler_refusal(sampler *s)
{
    int cells = s->refused == 2;
    double budget = cells ? (double)s->o->max_cells : (double)s->o->max_triangles;
    double p = cells ? 2.0 / 3.0 : 1.0, tol = s->o->tolerance, count = s->pred_free[cells];
    double sug = 0, cand = tol;
    for (int k = 0; k < SUGGEST_TRIES && !(s->o->flags & COONS__SAMPLE_NO_SUGGEST); k++) {
        double f = count > 0 ? pow(count / suggest_budget(budget), p) : 0;
        cand = round_up2(cand * dmax(f, k ? SUGGEST_STEP : 1.0 + 1e-9));
        int ok;
        coons_status st = fits(s, cand, &ok, &count);
        if (st) return st;
        if (ok) {
            sug = cand;
            break;
        }
    }
    char hint[96];
    if (sug > 0)
        snprintf(hint, sizeof hint, "try %.2g: sampling to it was checked to fit", sug);
    else
        snprintf(hint, sizeof hint, "none up to %.2g was found to fit", cand);
    return coons__error_set(s->err, COONS_E_LIMIT,
                            "body '%s': sampling to tolerance %g needs more than %zu %s (the "
                            "limit): about %.3g predicted from the deviation %.3g on the "
                            "%zu x %zu x %zu lattice; raise %s or loosen the tolerance (%s)",
                            s->name, tol, cells ? s->o->max_cells : s->o->max_triangles,
                            cells ? "volume cells" : "triangles", s->pred[cells],
                            s->pred_dev / s->scale, s->pred_n[0], s->pred_n[1], s->pred_n[2],
                            cells ? "max_cells (or give coons2stl --resolution)"
                                  : "max_triangles (coons2stl --max-triangles N)",
                            hint);
}

coons_status coons__sample_opts_resolve(const coons_sample_options *in, coons__sample_opts *out,
                                        coons_error *err)
{
    coons_sample_options def = COONS_SAMPLE_OPTIONS_INIT;
    if (!in) in = &def;
    /* version 1 has no progress fields */
    if (coons__record_version_check("sample options", in->version, 1,
                                    COONS_SAMPLE_OPTIONS_VERSION, "COONS_SAMPLE_OPTIONS_INIT", err))
        return COONS_E_INVALID;
    if (isnan(in->tolerance) || isinf(in->tolerance))
        return coons__error_set(err, COONS_E_INVALID, "tolerance must be a finite number");
    if (isnan(in->max_aspect) || (in->max_aspect != 0.0 && in->max_aspect < 1.0))
        return coons__error_set(err, COONS_E_INVALID,
                                "max_aspect must be 0 (default) or at least 1, not %g",
                                in->max_aspect);
    /* Caps the lattice so that no size computation can overflow: 2^20
     * intervals per direction is far beyond any triangle budget. */
    if (in->resolution > (1u << 20))
        return coons__error_set(err, COONS_E_LIMIT, "resolution %u is above %u", in->resolution,
                                1u << 20);
    out->tolerance = in->tolerance;
    out->resolution = in->resolution;
    out->max_triangles = in->max_triangles ? in->max_triangles : COONS_MESH_MAX_TRIANGLES;
    out->max_aspect = in->max_aspect != 0.0 ? in->max_aspect : COONS_SAMPLE_DEFAULT_MAX_ASPECT;
    if (in->flags & ~COONS_SAMPLE_UNMEASURED)
        return coons__error_set(err, COONS_E_INVALID, "unknown sample option flags 0x%x",
                                in->flags & ~COONS_SAMPLE_UNMEASURED);
    out->flags = in->flags;
    out->max_cells = 0;
    out->progress = in->version >= 2 ? in->progress : NULL;
    out->userdata = in->version >= 2 ? in->userdata : NULL;
    out->threads = coons__record_threads(in->version >= 3 ? in->threads : 1);
    return COONS_OK;
}

coons_status coons_body_sample(const coons_body *b, const coons_sample_options *opts,
                               const char *name, coons_mesh **out, coons_error *err)
{
    *out = NULL;
    coons__sample_opts o;
    coons_status st = coons__sample_opts_resolve(opts, &o, err);
    if (st) return st;
    if (!(o.tolerance > 0)) {
        double lo[3], hi[3];
        coons_body_control_bbox(b, lo, hi);
        double d = bbox_diag(lo, hi);
        o.tolerance = d > 0 ? 1e-3 * d : 1e-3;
    }
    coons_mesh *m;
    if ((st = coons_mesh_new(&m, err))) return st;
    /* a morph: the one mesh of its whole path, as coons_model_sample() */
    if ((st = coons__body_sample_path(b, &o, name, m, NULL, err))) {
        coons_mesh_free(m);
        return st;
    }
    *out = m;
    return COONS_OK;
}

void coons_sample_options_init(coons_sample_options *o)
{
    const coons_sample_options d = COONS_SAMPLE_OPTIONS_INIT;
    if (o) *o = d;
}
