/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A model's bodies as one mesh, one part per body (sample.c does the work;
 * a morph is sampled on the lattice of its whole path, morph_lattice.c).
 * Without the Boolean layer, "union" is honoured only where it is a plain
 * collection: bodies whose sampled boxes, grown by twice the tolerance (the
 * sampled boundary lies within it of the exact one), are disjoint. In a
 * union, bodies joined by shared faces (a control lattice) are one part,
 * joined by index without any Boolean (sample_lattice.c). With threads,
 * bodies are sampled at once into meshes of their own, appended in body
 * order: the same mesh as one thread makes, byte for byte. */
#include "coons_internal.h"
#include "model_glue.h"
#include "mesh_impl.h"
#include "morph_lattice.h"
#include "union_find.h"

#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* Bodies of the model joined by shared faces (shared_faces.c), as
 * components: comp[i] is the lowest body index of body i's component. Only
 * for a union: with "none" every body is its own solid. */
static coons_status components(const coons_model *model, size_t nb, uint32_t *comp,
                               coons__shared_face **sf, size_t *nsf, coons_error *err)
{
    *sf = NULL;
    *nsf = 0;
    for (size_t i = 0; i < nb; i++) comp[i] = (uint32_t)i;
    if (nb < 2 || coons_model_operation(model) != COONS_OP_UNION) return COONS_OK;
    const coons_body **bodies = coons__malloc_array(nb, sizeof *bodies);
    if (!bodies) return coons__error_nomem(err);
    double lo[3], hi[3];
    bbox_empty(lo, hi);
    for (size_t i = 0; i < nb; i++) {
        double a[3], b[3];
        bodies[i] = coons_model_body(model, i);
        coons_body_control_bbox(bodies[i], a, b);
        bbox_add(lo, hi, a);
        bbox_add(lo, hi, b);
    }
    coons_status st = coons__find_shared_faces(bodies, nb, COONS__REL_TOL * bbox_diag(lo, hi), sf, nsf, err);
    coons__free(bodies);
    if (st) return st;
    for (size_t k = 0; k < *nsf; k++)
        coons__uf_union(comp, (uint32_t)(*sf)[k].body[0], (uint32_t)(*sf)[k].body[1]);
    for (size_t i = 0; i < nb; i++) comp[i] = coons__uf_find(comp, (uint32_t)i);
    return COONS_OK;
}

/* The part name of bodies joined by shared faces: their names joined by
 * '+', or the first and last with "+...+" when that is long. */
static char *joined_name(const coons_model *model, const size_t *idx, size_t k)
{
    enum { LONG_NAME = 200 };
    size_t len = 0;
    for (size_t i = 0; i < k; i++) len += strlen(coons_model_body_name(model, idx[i])) + 1;
    const char *first = coons_model_body_name(model, idx[0]);
    const char *last = coons_model_body_name(model, idx[k - 1]);
    size_t cap = len <= LONG_NAME ? len + 1 : strlen(first) + strlen(last) + 8;
    char *s = coons__malloc(cap);
    if (!s) return NULL;
    if (len <= LONG_NAME) {
        s[0] = 0;
        for (size_t i = 0; i < k; i++) {
            if (i) strcat(s, "+");
            strcat(s, coons_model_body_name(model, idx[i]));
        }
    } else {
        snprintf(s, cap, "%s+...+%s", first, last);
    }
    return s;
}

/* Samples the component of body `first` (bodies idx[0..k-1], first ==
 * idx[0]) as one part joined by index (sample_lattice.c). */
static coons_status sample_component(const coons_model *model, const size_t *idx, size_t k,
                                     const coons__shared_face *sf, size_t nsf,
                                     const coons__sample_opts *o, coons_mesh *m, size_t *used,
                                     coons_error *err)
{
    const coons_body **bodies = coons__malloc_array(k, sizeof *bodies);
    const char **names = coons__malloc_array(k, sizeof *names);
    size_t *local = coons__malloc_array(coons_model_body_count(model), sizeof *local);
    coons__shared_face *mine = coons__malloc_array(nsf ? nsf : 1, sizeof *mine);
    char *name = joined_name(model, idx, k);
    coons_status st = COONS_OK;
    if (!bodies || !names || !local || !mine || !name) {
        st = coons__error_nomem(err);
        goto done;
    }
    for (size_t i = 0; i < coons_model_body_count(model); i++) local[i] = SIZE_MAX;
    for (size_t i = 0; i < k; i++) {
        bodies[i] = coons_model_body(model, idx[i]);
        names[i] = coons_model_body_name(model, idx[i]);
        local[idx[i]] = i;
    }
    size_t n = 0;
    for (size_t q = 0; q < nsf; q++)
        if (local[sf[q].body[0]] != SIZE_MAX) {
            mine[n] = sf[q];
            mine[n].body[0] = local[sf[q].body[0]];
            mine[n].body[1] = local[sf[q].body[1]];
            n++;
        }
    st = coons__lattice_sample_into(bodies, names, k, mine, n, o, name, m, used, err);
done:
    coons__free(bodies);
    coons__free(names);
    coons__free(local);
    coons__free(mine);
    coons__free(name);
    return st;
}

coons_status coons__model_sample(const coons_model *model, const coons_sample_options *opts,
                                 void (*progress)(void *, const char *, double),
                                 void *userdata, coons_mesh **out, double *tolerance,
                                 coons_error *err)
{
    return coons__model_sample_threads(model, opts, progress, userdata, 1, out, tolerance, err);
}

typedef struct {
    void (*fn)(void *, const char *, double);
    void *userdata;
} sample_progress;

static coons_status sample_parallel(const coons_model *model, const coons__sample_opts *o,
                                    unsigned threads, const uint32_t *comp, size_t nb,
                                    const coons__shared_face *sf, size_t nsf,
                                    const sample_progress *progress, coons_mesh **out,
                                    int *fallback, coons_error *err);

coons_status coons__model_sample_threads(const coons_model *model,
                                         const coons_sample_options *opts,
                                         void (*progress)(void *, const char *, double),
                                         void *userdata, unsigned threads, coons_mesh **out,
                                         double *tolerance, coons_error *err)
{
    *out = NULL;
    coons__sample_opts o;
    coons_status st = coons__sample_opts_resolve(opts, &o, err);
    if (st) return st;
    if (!(o.tolerance > 0)) o.tolerance = coons_model_tolerance(model);
    if (tolerance) *tolerance = o.tolerance;
    size_t nb = coons_model_body_count(model), budget = o.max_triangles;
    uint32_t *comp = coons__malloc_array(nb ? nb : 1, sizeof *comp);
    size_t *idx = coons__malloc_array(nb ? nb : 1, sizeof *idx);
    coons__shared_face *sf = NULL;
    size_t nsf = 0;
    coons_mesh *m = NULL;
    if (!comp || !idx) st = coons__error_nomem(err);
    if (!st) st = components(model, nb, comp, &sf, &nsf, err);
    int fallback = 1;
    if (!st && threads > 1 && nb > 1) {
        /* Progress from this thread as the workers finish. */
        sample_progress sp = {progress, userdata};
        st = sample_parallel(model, &o, threads, comp, nb, sf, nsf, &sp, &m, &fallback, err);
    }
    if (!st && fallback) st = coons_mesh_new(&m, err);
    for (size_t i = 0; i < nb && !st && fallback; i++) {
        if (comp[i] != i) continue; /* sampled with the first body of its component */
        /* By bodies: a body's share of the time is not known before. */
        if (progress) progress(userdata, "sample", (double)i / (double)nb);
        coons__sample_opts oi = o;
        oi.max_triangles = budget;
        size_t used = 0, k = 0;
        for (size_t j = i; j < nb; j++)
            if (comp[j] == i) idx[k++] = j;
        if (k == 1)
            st = coons__body_sample_path(coons_model_body(model, i), &oi,
                                         coons_model_body_name(model, i), m, &used, err);
        else
            st = sample_component(model, idx, k, sf, nsf, &oi, m, &used, err);
        budget -= used;
    }
    coons__free(comp);
    coons__free(idx);
    coons__free(sf);
    if (st) {
        coons_mesh_free(m);
        return st;
    }
    if (progress) progress(userdata, "sample", 1.0);
    *out = m;
    return COONS_OK;
}

/* Bodies (or components of bodies joined by shared faces) sampled on
 * threads: the component of lead[k] into mesh[k], each with the whole
 * budget (checked in body order afterwards). */
typedef struct {
    const coons_model *model;
    const uint32_t *comp;
    size_t nb;
    const coons__shared_face *sf;
    size_t nsf;
    const coons__sample_opts *o;
    const size_t *lead;
    size_t nlead;
    coons_mesh **mesh;
    size_t *used;
    coons_status *st;
    pthread_mutex_t lock;
    size_t next;
    pthread_cond_t finished; /* signalled as each job ends (with progress) */
    unsigned char *ended;    /* per job: it ended (with progress) */
    int watch;               /* progress is reported: mark and signal */
} sample_jobs;

static void sample_one(sample_jobs *j, size_t k)
{
    coons_error e = COONS_ERROR_INIT;
    size_t i = j->lead[k], n = 0;
    size_t *idx = coons__malloc_array(j->nb, sizeof *idx);
    coons_status st = idx ? coons_mesh_new(&j->mesh[k], &e) : COONS_E_NOMEM;
    if (!st) {
        for (size_t b = i; b < j->nb; b++)
            if (j->comp[b] == i) idx[n++] = b;
        if (n == 1)
            st = coons__body_sample_path(coons_model_body(j->model, i), j->o,
                                         coons_model_body_name(j->model, i), j->mesh[k],
                                         &j->used[k], &e);
        else
            st = sample_component(j->model, idx, n, j->sf, j->nsf, j->o, j->mesh[k],
                                  &j->used[k], &e);
    }
    coons__free(idx);
    j->st[k] = st;
}

static void *sample_worker(void *arg)
{
    sample_jobs *j = arg;
    for (;;) {
        pthread_mutex_lock(&j->lock);
        size_t k = j->next < j->nlead ? j->next++ : SIZE_MAX;
        pthread_mutex_unlock(&j->lock);
        if (k == SIZE_MAX) return NULL;
        sample_one(j, k);
        if (j->watch) {
            pthread_mutex_lock(&j->lock);
            j->ended[k] = 1;
            pthread_cond_signal(&j->finished);
            pthread_mutex_unlock(&j->lock);
        }
    }
}

/* The calling thread while the workers sample: the stage "sample" with
 * the first body (in body order) not yet sampled, i / count, each time
 * that body changes: every body before it is done (each body passed over
 * is reported too, in order, as the one-thread run reports it). */
static void report_until_done(sample_jobs *j, const sample_progress *p)
{
    size_t first = 0; /* job of the first body not yet sampled */
    p->fn(p->userdata, "sample", 0.0);
    pthread_mutex_lock(&j->lock);
    while (first < j->nlead) {
        size_t was = first;
        while (first < j->nlead && j->ended[first]) first++;
        if (first == was) {
            pthread_cond_wait(&j->finished, &j->lock);
            continue;
        }
        pthread_mutex_unlock(&j->lock);
        for (size_t k = was + 1; k <= first && k < j->nlead; k++)
            p->fn(p->userdata, "sample", (double)j->lead[k] / (double)j->nb);
        pthread_mutex_lock(&j->lock);
    }
    pthread_mutex_unlock(&j->lock);
}

/* The parts of src appended to dst as they are (metadata included). */
static coons_status append_parts(coons_mesh *dst, const coons_mesh *src, coons_error *err)
{
    for (size_t p = 0; p < src->nparts; p++) {
        const coons__mesh_part *P = &src->parts[p];
        uint32_t *tri = coons__malloc_array(3 * (P->tri_count ? P->tri_count : 1), sizeof *tri);
        if (!tri) return coons__error_nomem(err);
        for (size_t t = 0; t < 3 * P->tri_count; t++)
            tri[t] = src->tri[3 * P->tri_first + t] - (uint32_t)P->vert_first;
        size_t at = dst->nparts;
        coons_status st = coons__mesh_add_part_uvw(
            dst, P->name, src->xyz + 3 * P->vert_first,
            P->has_params && src->uvw ? src->uvw + 3 * P->vert_first : NULL, P->vert_count, tri,
            P->tri_count, err);
        coons__free(tri);
        if (st) return st;
        coons__mesh_part *Q = &dst->parts[at];
        Q->sampled = P->sampled;
        Q->tolerance = P->tolerance;
        Q->deviation = P->deviation;
        for (int d = 0; d < 3; d++) Q->lattice[d] = P->lattice[d];
        Q->glued = P->glued;
    }
    return COONS_OK;
}

/* The threaded sampling; *fallback is set (and nothing made) when it
 * cannot give what one thread gives (a failure or an exhausted budget:
 * the one-thread run then reports it exactly as it would). */
static coons_status sample_parallel(const coons_model *model, const coons__sample_opts *o,
                                    unsigned threads, const uint32_t *comp, size_t nb,
                                    const coons__shared_face *sf, size_t nsf,
                                    const sample_progress *progress, coons_mesh **out,
                                    int *fallback, coons_error *err)
{
    *fallback = 0;
    size_t nlead = 0;
    for (size_t i = 0; i < nb; i++) nlead += comp[i] == i;
    sample_jobs j;
    memset(&j, 0, sizeof j);
    j.model = model;
    j.comp = comp;
    j.nb = nb;
    j.sf = sf;
    j.nsf = nsf;
    coons__sample_opts quiet = *o; /* workers report nothing: not the calling thread */
    quiet.progress = NULL;
    quiet.threads = 1; /* the bodies are spread over the threads already */
    j.o = &quiet;
    size_t *lead = coons__malloc_array(nlead, sizeof *lead);
    j.mesh = coons__calloc(nlead, sizeof *j.mesh);
    j.used = coons__calloc(nlead, sizeof *j.used);
    j.st = coons__calloc(nlead, sizeof *j.st);
    pthread_t *tid = coons__malloc_array(threads, sizeof *tid);
    coons_status st = COONS_OK;
    coons_mesh *m = NULL;
    unsigned started = 0;
    size_t budget = o->max_triangles;
    if (!lead || !j.mesh || !j.used || !j.st || !tid) {
        st = coons__error_nomem(err);
        goto done;
    }
    for (size_t i = 0, k = 0; i < nb; i++)
        if (comp[i] == i) lead[k++] = i;
    j.lead = lead;
    j.nlead = nlead;
    if (pthread_mutex_init(&j.lock, NULL)) {
        *fallback = 1;
        goto done;
    }
    /* With progress the calling thread reports while `threads` workers
     * sample (it waits, it does not sample); else it is one of them. */
    j.ended = progress && progress->fn ? coons__calloc(nlead, 1) : NULL;
    j.watch = j.ended && pthread_cond_init(&j.finished, NULL) == 0;
    unsigned first = j.watch ? 0u : 1u;
    for (unsigned t = first; t < threads && t < nlead + first; t++, started++)
        if (pthread_create(&tid[started], NULL, sample_worker, &j)) break;
    if (j.watch && started == 0) j.watch = 0; /* no worker: sample here, unwatched */
    if (j.watch)
        report_until_done(&j, progress);
    else
        sample_worker(&j);
    for (unsigned t = 0; t < started; t++) pthread_join(tid[t], NULL);
    if (first == 0) pthread_cond_destroy(&j.finished);
    pthread_mutex_destroy(&j.lock);
    for (size_t k = 0; k < nlead && !*fallback; k++) {
        if (j.st[k] || j.used[k] > budget) *fallback = 1;
        else budget -= j.used[k];
    }
    if (*fallback) goto done;
    st = coons_mesh_new(&m, err);
    for (size_t k = 0; k < nlead && !st; k++) st = append_parts(m, j.mesh[k], err);
    if (st) {
        coons_mesh_free(m);
        m = NULL;
    }
done:
    coons__free(j.ended);
    for (size_t k = 0; j.mesh && k < nlead; k++) coons_mesh_free(j.mesh[k]);
    coons__free(lead);
    coons__free(j.mesh);
    coons__free(j.used);
    coons__free(j.st);
    coons__free(tid);
    *out = m;
    return st;
}

int coons__parts_meet(const coons_mesh *m, double tol, size_t *pi, size_t *pj)
{
    for (size_t i = 0; i < m->nparts; i++)
        for (size_t j = i + 1; j < m->nparts; j++) {
            double lo[2][3], hi[2][3];
            const size_t pk[2] = {i, j};
            for (int k = 0; k < 2; k++) {
                const coons__mesh_part *P = &m->parts[pk[k]];
                bbox_empty(lo[k], hi[k]);
                for (size_t v = P->vert_first; v < P->vert_first + P->vert_count; v++)
                    bbox_add(lo[k], hi[k], m->xyz + 3 * v);
            }
            int apart = 0;
            for (int d = 0; d < 3; d++)
                if (lo[0][d] > hi[1][d] + 2 * tol || lo[1][d] > hi[0][d] + 2 * tol) apart = 1;
            if (!apart) {
                *pi = i;
                *pj = j;
                return 1;
            }
        }
    return 0;
}

coons_status coons__union_unavailable(const coons_mesh *m, size_t i, size_t j, coons_error *err)
{
    return coons__error_set(err, COONS_E_UNSUPPORTED,
                            "bodies '%s' and '%s' overlap or touch, and their union needs the "
                            "Boolean (CGAL) layer, which is not available here; set "
                            "\"operation\": \"none\" to output each body's own closed shell",
                            m->parts[i].name, m->parts[j].name);
}

coons_status coons_model_sample(const coons_model *model, const coons_sample_options *opts,
                                coons_mesh **out, coons_error *err)
{
    double tol = 0;
    coons_status st = coons__model_sample(model, opts, NULL, NULL, out, &tol, err);
    size_t i, j;
    if (!st && coons_model_operation(model) == COONS_OP_UNION && coons__parts_meet(*out, tol, &i, &j)) {
        st = coons__union_unavailable(*out, i, j, err);
        coons_mesh_free(*out);
        *out = NULL;
    }
    return st;
}
