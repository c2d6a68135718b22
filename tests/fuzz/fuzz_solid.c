/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Fuzz target through repair and union (the CGAL layer): a model from a
 * memory buffer, loaded under small limits, each body sampled on a coarse
 * fixed lattice, then the model's solid made (coons_model_solidify: repair
 * of folds, union of the bodies, shared faces glued) and each body's solid
 * alone (coons_model_solidify_body).
 *
 * What must hold, whatever the input:
 *  - no crash, leak or sanitizer report, and no unbounded allocation;
 *  - an error is one of the statuses the API documents, with a message;
 *  - a solid that comes back is closed, a 2-manifold or reported as not
 *    one (nonmanifold_edges agrees with an independent edge count), and
 *    free of self-intersections by CGAL's exact predicates: the library
 *    promises that a rounding that leaves an intersection is an error,
 *    never a silent result.
 *
 * Built with libFuzzer by `tools/fuzz.sh solid` (clang, CGAL instrumented:
 * slow to build, so on demand); in the ordinary and ASan builds the replay
 * program runs it over tests/fuzz/solid/ and the kept regressions.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <coons.h>
#include <coons/csg.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define CHECK(cond, ...)                                                \
    do {                                                                \
        if (!(cond)) {                                                  \
            fprintf(stderr, "fuzz_solid: check failed: %s: ", #cond);  \
            fprintf(stderr, __VA_ARGS__);                               \
            fputc('\n', stderr);                                        \
            abort();                                                    \
        }                                                               \
    } while (0)

typedef struct edge {
    uint32_t a, b;
} edge;

static int edge_cmp(const void *x, const void *y)
{
    const edge *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return 0;
}

/* Border edges (used once) and edges used more than twice, counted from
 * the triangles by sorting the undirected edges: independent of CGAL. */
static void count_edges(const coons_mesh *m, size_t *border, size_t *over)
{
    *border = *over = 0;
    size_t nt = coons_mesh_triangle_count(m);
    const uint32_t *t = coons_mesh_triangles(m);
    edge *e = malloc((nt > 0 ? 3 * nt : 1) * sizeof *e);
    CHECK(e != NULL, "out of memory for %zu edges", 3 * nt);
    for (size_t i = 0; i < nt; i++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = t[3 * i + k], b = t[3 * i + (k + 1) % 3];
            e[3 * i + k] = a < b ? (edge){a, b} : (edge){b, a};
        }
    qsort(e, 3 * nt, sizeof *e, edge_cmp);
    for (size_t i = 0; i < 3 * nt;) {
        size_t j = i;
        while (j < 3 * nt && edge_cmp(&e[i], &e[j]) == 0) j++;
        if (j - i == 1) (*border)++;
        if (j - i > 2) (*over)++;
        i = j;
    }
    free(e);
}

static void check_solid(const char *what, coons_status rc, const coons_mesh *s,
                        const coons_csg_report *rep, const coons_error *err)
{
    CHECK(rc == COONS_OK || rc == COONS_E_LIMIT || rc == COONS_E_INVALID ||
              rc == COONS_E_UNSUPPORTED || rc == COONS_E_CSG || rc == COONS_E_DOMAIN,
          "%s: status %d: %s", what, rc, err->message);
    if (rc != COONS_OK) {
        CHECK(err->message[0] != '\0', "%s: status %d without a message", what, rc);
        CHECK(s == NULL, "%s: status %d but a mesh", what, rc);
        return;
    }
    CHECK(s != NULL, "%s: COONS_OK without a mesh", what);
    size_t border, over;
    count_edges(s, &border, &over);
    if (coons_mesh_triangle_count(s) > 0)
        CHECK(border == 0, "%s: %zu border edges in a solid", what, border);
    CHECK(rep->nonmanifold_edges == over, "%s: report says %zu non-manifold edges, counted %zu",
          what, rep->nonmanifold_edges, over);
    size_t pairs = 0;
    coons_error e2 = COONS_ERROR_INIT;
    coons_status r2 = coons_mesh_count_self_intersections(s, &pairs, &e2);
    CHECK(r2 == COONS_OK, "%s: self-intersection count: %s", what, e2.message);
    CHECK(pairs == 0, "%s: the solid crosses itself (%zu pairs)", what, pairs);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    coons_model_load_options o = COONS_MODEL_LOAD_OPTIONS_INIT;
    o.max_bytes = 1 << 16;
    o.max_values = 1 << 12;
    o.max_points = 64;
    coons_model *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    int verbose = getenv("FUZZ_SOLID_VERBOSE") != NULL;
    if (coons_model_load_memory((const char *)data, size, "fuzz", &o, &m, &err) != COONS_OK) {
        if (verbose) fprintf(stderr, "load: %s\n", err.message);
        return 0;
    }
    size_t n = coons_model_body_count(m);
    if (verbose) fprintf(stderr, "%zu bodies\n", n);
    if (n == 0 || n > 4) { /* small inputs: the union of many bodies is slow, not wrong */
        coons_model_free(m);
        return 0;
    }
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.resolution = 3;
    so.max_triangles = 2000;
    coons_csg_options co = COONS_CSG_OPTIONS_INIT;

    coons_mesh *s = NULL;
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    coons_status rc = coons_model_solidify(m, &so, &co, &s, &rep, &err);
    if (verbose)
        fprintf(stderr, "solid: %d, %zu triangles %s\n", rc,
                s ? coons_mesh_triangle_count(s) : 0, rc ? err.message : "");
    check_solid("model", rc, s, &rep, &err);
    coons_mesh_free(s);

    for (size_t i = 0; i < n; i++) {
        coons_mesh *b = NULL;
        coons_csg_report rb = COONS_CSG_REPORT_INIT;
        coons_error eb = COONS_ERROR_INIT;
        coons_status rcb = coons_model_solidify_body(m, i, &so, &co, &b, &rb, &eb);
        check_solid("body", rcb, b, &rb, &eb);
        coons_mesh_free(b);
    }
    coons_model_free(m);
    return 0;
}
