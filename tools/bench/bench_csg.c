/* SPDX-License-Identifier: GPL-3.0-or-later */
/* bench_csg: from a model file to a written binary STL of the union of its
 * bodies (load, sample each body on a fixed lattice, repair + union with the
 * CGAL layer, write), with the time of each stage. Also writes each body's
 * own shell as DIR/body<i>.stl, the inputs the peers (OpenSCAD, manifold3d)
 * unite in tools/bench/bench_csg.sh.
 *
 *   bench_csg MODEL [--resolution N] [--dir DIR] [--repeat R]
 *
 * Prints "key value" lines; times are the minimum over R runs.
 *
 * With --model-path (coons_model_solidify(): bodies sampled by the library,
 * those joined by shared faces glued by index, on --threads T threads) the
 * time of each stage is taken from the progress reports: sample_s (the
 * bodies), check_s (the self-intersection checks of the input shells),
 * union_core_s (corefinement), verify_s (welding and the final exact check);
 * with several groups on several threads the stages overlap and only
 * solid_s (sampling + repair + union) is meaningful. --no-repair: a body
 * that meets no other passes without the self-intersection check. */
#define _XOPEN_SOURCE 700
#include <coons.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Stage times from the progress callback: the time between a change of
 * stage and the next one is charged to the stage. */
enum { ST_SAMPLE, ST_CHECK, ST_UNION, ST_VERIFY, ST_OTHER, ST_N };
static const char *const stage_key[ST_N] = {"sample_s", "check_s", "union_core_s", "verify_s",
                                            "other_s"};
typedef struct {
    double t[ST_N];
    int cur;
    double since;
} stages;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int stage_of(const char *name)
{
    if (!strcmp(name, "sample")) return ST_SAMPLE;
    if (!strcmp(name, "check")) return ST_CHECK;
    if (!strcmp(name, "union")) return ST_UNION;
    if (!strcmp(name, "verify")) return ST_VERIFY;
    return ST_OTHER;
}

static void on_progress(void *ud, const char *stage, double f)
{
    stages *s = ud;
    double t = now();
    (void)f;
    if (s->cur >= 0) s->t[s->cur] += t - s->since;
    s->cur = strcmp(stage, "done") ? stage_of(stage) : -1;
    s->since = t;
}

static void check(coons_status rc, const char *what, const coons_error *e)
{
    if (rc == COONS_OK) return;
    fprintf(stderr, "bench_csg: %s: %s\n", what, e->message);
    exit(1);
}

/* Each body's own shell as DIR/body<i>.stl (the peers' inputs), untimed. */
static void write_bodies(const coons_model *m, unsigned res, const char *dir)
{
    coons_error err = COONS_ERROR_INIT;
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.resolution = res;
    char path[4096];
    for (size_t b = 0; b < coons_model_body_count(m); b++) {
        coons_mesh *one = NULL;
        check(coons_body_sample(coons_model_body(m, b), &so, coons_model_body_name(m, b), &one,
                                &err),
              "sample", &err);
        snprintf(path, sizeof path, "%s/body%zu.stl", dir, b);
        check(coons_mesh_write(one, path, COONS_FORMAT_STL_BINARY, NULL, &err), "write", &err);
        coons_mesh_free(one);
    }
}

int main(int argc, char **argv)
{
    const char *model = NULL, *dir = ".";
    unsigned res = 92;
    int repeat = 3, model_path = 0, repair = 1;
    unsigned threads = 1;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--resolution") && i + 1 < argc)
            res = (unsigned)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--dir") && i + 1 < argc)
            dir = argv[++i];
        else if (!strcmp(argv[i], "--repeat") && i + 1 < argc)
            repeat = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--threads") && i + 1 < argc)
            threads = (unsigned)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--model-path"))
            model_path = 1;
        else if (!strcmp(argv[i], "--no-repair"))
            repair = 0;
        else
            model = argv[i];
    }
    if (!model) {
        fprintf(stderr, "usage: bench_csg MODEL [--resolution N] [--dir DIR] [--repeat R] "
                        "[--model-path] [--threads T] [--no-repair]\n");
        return 2;
    }
    coons_error err = COONS_ERROR_INIT;
    char path[4096];
    double best[5] = {1e30, 1e30, 1e30, 1e30, 1e30}; /* load, sample, union, write, total */
    double best_st[ST_N] = {0};
    size_t tin = 0, tout = 0;
    coons_csg_report last;
    memset(&last, 0, sizeof last);
    double vol = 0;
    for (int r = 0; r < repeat; r++) {
        double t0 = now();
        coons_model *m = NULL;
        check(coons_model_load_file(model, NULL, &m, &err), "load", &err);
        double t_load = now() - t0;
        if (r == 0) write_bodies(m, res, dir);
        coons_mesh *all = NULL, *u = NULL;
        coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
        so.resolution = res;
        /* as coons2stl --resolution N -o FILE samples (its deviation is
         * measured only for --info) */
        so.flags |= COONS_SAMPLE_UNMEASURED;
        coons_csg_options co = COONS_CSG_OPTIONS_INIT;
        co.threads = threads;
        co.repair = repair;
        co.progress = on_progress;
        stages st;
        memset(&st, 0, sizeof st);
        st.cur = -1;
        co.userdata = &st;
        coons_csg_report rep = COONS_CSG_REPORT_INIT;
        double t_sample, t_union;
        double t1 = now();
        st.cur = ST_SAMPLE; /* until the first report (threads: all of the sampling) */
        st.since = t1;
        if (model_path) {
            check(coons_model_solidify(m, &so, &co, &u, &rep, &err), "solidify", &err);
            on_progress(&st, "done", 1.0);
            t_sample = st.t[ST_SAMPLE];
            t_union = now() - t1 - t_sample;
            tin = rep.triangles_in;
        } else {
            check(coons_mesh_new(&all, &err), "mesh", &err);
            for (size_t b = 0; b < coons_model_body_count(m); b++) {
                coons_mesh *one = NULL;
                check(coons_body_sample(coons_model_body(m, b), &so, coons_model_body_name(m, b),
                                        &one, &err),
                      "sample", &err);
                check(coons_mesh_add_part(all, coons_model_body_name(m, b),
                                          coons_mesh_vertices(one), coons_mesh_vertex_count(one),
                                          coons_mesh_triangles(one),
                                          coons_mesh_triangle_count(one), &err),
                      "add", &err);
                coons_mesh_free(one);
            }
            double t2 = now();
            t_sample = t2 - t1;
            check(coons_mesh_solidify(all, &co, &u, &rep, &err), "union", &err);
            on_progress(&st, "done", 1.0);
            t_union = now() - t2;
            tin = coons_mesh_triangle_count(all);
        }
        double t3 = now();
        snprintf(path, sizeof path, "%s/union.stl", dir);
        check(coons_mesh_write(u, path, COONS_FORMAT_STL_BINARY, NULL, &err), "write", &err);
        double t4 = now();
        double t[5] = {t_load, t_sample, t_union, t4 - t3, t_load + (t4 - t1)};
        if (t[4] < best[4])
            for (int k = 0; k < ST_N; k++) best_st[k] = st.t[k];
        for (int k = 0; k < 5; k++)
            if (t[k] < best[k]) best[k] = t[k];
        last = rep;
        tout = coons_mesh_triangle_count(u);
        vol = coons_mesh_volume(u);
        coons_mesh_free(u);
        coons_mesh_free(all);
        coons_model_free(m);
    }
    printf("triangles_in %zu\ntriangles_out %zu\nvolume %.9g\n", tin, tout, vol);
    printf("groups %zu\nfast_unions %zu\nfallbacks %zu\npatches %zu\nclose_merged %zu\n"
           "slivers_fixed %zu\n",
           last.groups, last.fast_unions, last.fallbacks, last.patches, last.close_merged,
           last.slivers_fixed);
    printf("threads %u\npassed_through %zu\n", threads, last.passed_through);
    printf("load_s %.4f\nsample_s %.4f\nunion_s %.4f\nwrite_s %.4f\ntotal_s %.4f\n", best[0],
           best[1], best[2], best[3], best[4]);
    /* the stages of the run with the best total (repair + union part) */
    for (int k = ST_CHECK; k < ST_N; k++) printf("stage_%s %.4f\n", stage_key[k], best_st[k]);
    return 0;
}
