/* SPDX-License-Identifier: GPL-3.0-or-later */
/* bench_csg: from a model file to a written binary STL of the union of its
 * bodies (load, sample each body on a fixed lattice, repair + union with the
 * CGAL layer, write), with the time of each stage. Also writes each body's
 * own shell as DIR/body<i>.stl, the inputs the peers (OpenSCAD, manifold3d)
 * unite in tools/bench/bench_csg.sh.
 *
 *   bench_csg MODEL [--resolution N] [--dir DIR] [--repeat R]
 *
 * Prints "key value" lines; times are the minimum over R runs. */
#define _XOPEN_SOURCE 700
#include <coons.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void check(coons_status rc, const char *what, const coons_error *e)
{
    if (rc == COONS_OK) return;
    fprintf(stderr, "bench_csg: %s: %s\n", what, e->message);
    exit(1);
}

int main(int argc, char **argv)
{
    const char *model = NULL, *dir = ".";
    unsigned res = 92;
    int repeat = 3;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--resolution") && i + 1 < argc)
            res = (unsigned)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--dir") && i + 1 < argc)
            dir = argv[++i];
        else if (!strcmp(argv[i], "--repeat") && i + 1 < argc)
            repeat = atoi(argv[++i]);
        else
            model = argv[i];
    }
    if (!model) {
        fprintf(stderr, "usage: bench_csg MODEL [--resolution N] [--dir DIR] [--repeat R]\n");
        return 2;
    }
    coons_error err = COONS_ERROR_INIT;
    char path[4096];
    double best[5] = {1e30, 1e30, 1e30, 1e30, 1e30}; /* load, sample, union, write, total */
    size_t tin = 0, tout = 0;
    coons_csg_report last;
    memset(&last, 0, sizeof last);
    double vol = 0;
    for (int r = 0; r < repeat; r++) {
        double t0 = now();
        coons_model *m = NULL;
        check(coons_model_load_file(model, NULL, &m, &err), "load", &err);
        double t1 = now();
        coons_mesh *all = NULL;
        check(coons_mesh_new(&all, &err), "mesh", &err);
        coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
        so.resolution = res;
        for (size_t b = 0; b < coons_model_body_count(m); b++) {
            coons_mesh *one = NULL;
            check(coons_body_sample(coons_model_body(m, b), &so, coons_model_body_name(m, b), &one,
                                    &err),
                  "sample", &err);
            check(coons_mesh_add_part(all, coons_model_body_name(m, b), coons_mesh_vertices(one),
                                      coons_mesh_vertex_count(one), coons_mesh_triangles(one),
                                      coons_mesh_triangle_count(one), &err),
                  "add", &err);
            if (r == 0) {
                snprintf(path, sizeof path, "%s/body%zu.stl", dir, b);
                check(coons_mesh_write(one, path, COONS_FORMAT_STL_BINARY, NULL, &err), "write",
                      &err);
            }
            coons_mesh_free(one);
        }
        double t2 = now();
        coons_csg_options co = COONS_CSG_OPTIONS_INIT;
        coons_csg_report rep = COONS_CSG_REPORT_INIT;
        coons_mesh *u = NULL;
        check(coons_mesh_solidify(all, &co, &u, &rep, &err), "union", &err);
        double t3 = now();
        snprintf(path, sizeof path, "%s/union.stl", dir);
        check(coons_mesh_write(u, path, COONS_FORMAT_STL_BINARY, NULL, &err), "write", &err);
        double t4 = now();
        double t[5] = {t1 - t0, t2 - t1, t3 - t2, t4 - t3, t4 - t0};
        for (int k = 0; k < 5; k++)
            if (t[k] < best[k]) best[k] = t[k];
        last = rep;
        tin = coons_mesh_triangle_count(all);
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
    printf("load_s %.4f\nsample_s %.4f\nunion_s %.4f\nwrite_s %.4f\ntotal_s %.4f\n", best[0],
           best[1], best[2], best[3], best[4]);
    return 0;
}
