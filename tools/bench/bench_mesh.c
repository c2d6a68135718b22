/* SPDX-License-Identifier: GPL-3.0-or-later */
/* bench_mesh: how fast libcoons turns one body into a binary STL file,
 * compared with the disk itself (the I/O floor: the same number of bytes
 * written from memory to the same directory, with the same temporary file,
 * fsync and rename that coons_mesh_write does), plus the ASCII STL writer.
 *
 * The body is a cubic Bezier volume (4x4x4 control points, a cube of side
 * 10 whose face control points bulge out by 2: a "pillow"), sampled on a
 * fixed lattice of N intervals per direction, so 12 N^2 triangles
 * (N = 289: 1.002 million), without measuring the deviation
 * (COONS_SAMPLE_UNMEASURED, as coons2stl --resolution does), on T threads
 * (coons_sample_options.threads; default every online core, as coons2stl).
 *
 *   bench_mesh [--resolution N] [--dir DIR] [--repeat R] [--threads T] [--keep]
 *   bench_mesh --emit-scad FILE [--resolution N]
 *
 * The first form prints "key value" lines (times are the minimum over R
 * runs); --keep leaves DIR/bench.stl for the numpy-stl comparison. The
 * second writes the same body in OpenSCAD's language: the six boundary
 * faces evaluated from their Bezier nets on an N x N grid with list
 * comprehensions, fed to one polyhedron(), the peer a user would write. */
#define _XOPEN_SOURCE 700
#include <coons.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* P[i][j][k], i along u. */
static void pillow(double P[4][4][4][3])
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            for (int k = 0; k < 4; k++) {
                int idx[3] = {i, j, k};
                for (int d = 0; d < 3; d++) {
                    double x = 10.0 * idx[d] / 3.0;
                    /* A point on the face idx[d] in {0,3} whose other two
                     * indices are inner bulges out along axis d. */
                    int e = (d + 1) % 3, f = (d + 2) % 3;
                    int inner = idx[e] > 0 && idx[e] < 3 && idx[f] > 0 && idx[f] < 3;
                    if (inner && idx[d] == 0) x -= 2.0;
                    if (inner && idx[d] == 3) x += 2.0;
                    P[i][j][k][d] = x;
                }
            }
}

static void die(const char *what, const coons_error *e)
{
    fprintf(stderr, "bench_mesh: %s: %s\n", what, e ? e->message : strerror(errno));
    exit(1);
}

/* The I/O floor: nbytes from memory into a temporary file next to `path`,
 * fsync, close, rename: what coons_mesh_write does minus the formatting. */
static double io_floor(const char *path, const char *buf, size_t nbytes)
{
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.floor-tmp", path);
    double t0 = now();
    int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) die(tmp, NULL);
    size_t chunk = (size_t)1 << 20;
    for (size_t off = 0; off < nbytes;) {
        size_t n = nbytes - off < chunk ? nbytes - off : chunk;
        ssize_t w = write(fd, buf + off, n);
        if (w <= 0) die("write", NULL);
        off += (size_t)w;
    }
    if (fsync(fd) != 0 || close(fd) != 0) die("fsync/close", NULL);
    if (rename(tmp, path) != 0) die("rename", NULL);
    return now() - t0;
}

static off_t file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? st.st_size : -1;
}

static void emit_scad(const char *path, unsigned n, double P[4][4][4][3])
{
    FILE *f = fopen(path, "w");
    if (!f) die(path, NULL);
    /* The six face nets as per-coordinate 4x4 matrices, each with a flag
     * saying whether (s, t) -> (s+1, t) -> (s+1, t+1) runs counter-clockwise
     * seen from outside (faces u=1, v=1, w=1 parametrised (v,w), (w,u), (u,v)). */
    fprintf(f, "// bench_mesh peer: the pillow Bezier volume's boundary sampled in OpenSCAD\n");
    fprintf(f, "N = %u;\n", n);
    fprintf(f, "nets = [\n");
    for (int face = 0; face < 6; face++) {
        int axis = face / 2, side = face % 2; /* side 0: param 0, side 1: param 1 */
        fprintf(f, "  [%d, [", side);
        for (int d = 0; d < 3; d++) {
            fprintf(f, "%s[", d ? ", " : "");
            for (int a = 0; a < 4; a++) {
                fprintf(f, "%s[", a ? ", " : "");
                for (int b = 0; b < 4; b++) {
                    int idx[3];
                    idx[axis] = side ? 3 : 0;
                    idx[(axis + 1) % 3] = a;
                    idx[(axis + 2) % 3] = b;
                    fprintf(f, "%s%.17g", b ? ", " : "", P[idx[0]][idx[1]][idx[2]][d]);
                }
                fprintf(f, "]");
            }
            fprintf(f, "]");
        }
        fprintf(f, "]]%s\n", face < 5 ? "," : "");
    }
    fprintf(f, "];\n"
               "function bern(t) = [(1-t)*(1-t)*(1-t), 3*t*(1-t)*(1-t), 3*t*t*(1-t), t*t*t];\n"
               "function patch(F, s, t) = let(bs = bern(s), bt = bern(t))\n"
               "  [for (d = [0:2]) bs * F[d] * bt];\n"
               "M = N + 1;\n"
               "points = [for (f = [0:5]) for (a = [0:N]) for (c = [0:N])\n"
               "  patch(nets[f][1], a / N, c / N)];\n"
               "// Clockwise seen from outside, as polyhedron() wants: a counter-clockwise\n"
               "// (a,c),(a+1,c),(a+1,c+1) on the param-1 faces is listed backwards.\n"
               "faces = [for (f = [0:5]) let(o = f * M * M, up = nets[f][0] == 1)\n"
               "  for (a = [0:N-1]) for (c = [0:N-1]) let(\n"
               "    p = o + a * M + c, q = o + (a + 1) * M + c, r = q + 1, s = p + 1)\n"
               "  each (up ? [[p, r, q], [p, s, r]] : [[p, q, r], [p, r, s]])];\n"
               "polyhedron(points = points, faces = faces, convexity = 2);\n");
    if (fclose(f) != 0) die(path, NULL);
}

int main(int argc, char **argv)
{
    unsigned n = 289, repeat = 3;
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    unsigned threads = cores > 0 ? (unsigned)cores : 1;
    const char *dir = ".", *scad = NULL;
    int keep = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--resolution") && i + 1 < argc)
            n = (unsigned)strtoul(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--dir") && i + 1 < argc)
            dir = argv[++i];
        else if (!strcmp(argv[i], "--repeat") && i + 1 < argc)
            repeat = (unsigned)strtoul(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--threads") && i + 1 < argc)
            threads = (unsigned)strtoul(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--emit-scad") && i + 1 < argc)
            scad = argv[++i];
        else if (!strcmp(argv[i], "--keep"))
            keep = 1;
        else {
            fprintf(stderr, "usage: bench_mesh [--resolution N] [--dir DIR] [--repeat R] "
                            "[--threads T] [--keep]\n"
                            "       bench_mesh --emit-scad FILE [--resolution N]\n");
            return 2;
        }
    }
    if (n < 1 || repeat < 1 || threads < 1) return 2;
    static double P[4][4][4][3];
    pillow(P);
    if (scad) {
        emit_scad(scad, n, P);
        return 0;
    }
    coons_error e = COONS_ERROR_INIT;
    coons_body *body;
    const size_t dims[3] = {4, 4, 4};
    if (coons_body_new_bezier(&P[0][0][0][0], dims, &body, &e) != COONS_OK) die("body", &e);
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.resolution = n;
    /* As coons2stl --resolution: a fixed lattice, deviation not measured. */
    so.flags |= COONS_SAMPLE_UNMEASURED;
    so.threads = threads;
    char stl[4096], asc[4096], flo[4096];
    snprintf(stl, sizeof stl, "%s/bench.stl", dir);
    snprintf(asc, sizeof asc, "%s/bench-ascii.stl", dir);
    snprintf(flo, sizeof flo, "%s/bench-floor.bin", dir);

    double t_sample = 1e300, t_bin = 1e300, t_floor = 1e300, t_ascii = 1e300;
    coons_mesh *mesh = NULL;
    for (unsigned r = 0; r < repeat; r++) {
        coons_mesh_free(mesh);
        double t0 = now();
        if (coons_body_sample(body, &so, "pillow", &mesh, &e) != COONS_OK) die("sample", &e);
        double t = now() - t0;
        if (t < t_sample) t_sample = t;
    }
    size_t nt = coons_mesh_triangle_count(mesh);
    size_t bytes = 84 + 50 * nt;
    char *junk = malloc(bytes);
    if (!junk) die("malloc", NULL);
    for (size_t i = 0; i < bytes; i++) junk[i] = (char)(i * 2654435761u >> 13);
    coons_write_options wo = COONS_WRITE_OPTIONS_INIT;
    wo.units = "mm";
    /* Interleave writer and floor so both see the same disk state. */
    for (unsigned r = 0; r < repeat; r++) {
        double t0 = now();
        if (coons_mesh_write(mesh, stl, COONS_FORMAT_STL_BINARY, &wo, &e) != COONS_OK)
            die("write", &e);
        double t = now() - t0;
        if (t < t_bin) t_bin = t;
        t = io_floor(flo, junk, bytes);
        if (t < t_floor) t_floor = t;
        t0 = now();
        if (coons_mesh_write(mesh, asc, COONS_FORMAT_STL_ASCII, &wo, &e) != COONS_OK)
            die("write", &e);
        t = now() - t0;
        if (t < t_ascii) t_ascii = t;
    }
    if ((size_t)file_size(stl) != bytes) die("binary STL has the wrong size", NULL);
    printf("resolution %u\n", n);
    printf("threads %u\n", threads);
    printf("triangles %zu\n", nt);
    printf("vertices %zu\n", coons_mesh_vertex_count(mesh));
    printf("volume %.9g\n", coons_mesh_volume(mesh));
    printf("binary_bytes %zu\n", bytes);
    printf("ascii_bytes %lld\n", (long long)file_size(asc));
    printf("sample_s %.4f\n", t_sample);
    printf("write_binary_s %.4f\n", t_bin);
    printf("io_floor_s %.4f\n", t_floor);
    printf("write_ascii_s %.4f\n", t_ascii);
    printf("sample_plus_binary_s %.4f\n", t_sample + t_bin);
    printf("sample_plus_binary_tri_per_s %.0f\n", (double)nt / (t_sample + t_bin));
    printf("binary_write_tri_per_s %.0f\n", (double)nt / t_bin);
    printf("ascii_write_tri_per_s %.0f\n", (double)nt / t_ascii);
    printf("binary_write_over_floor %.2f\n", t_bin / t_floor);
    printf("sample_plus_binary_over_floor %.2f\n", (t_sample + t_bin) / t_floor);
    unlink(flo);
    unlink(asc);
    if (!keep) unlink(stl);
    free(junk);
    coons_mesh_free(mesh);
    coons_body_free(body);
    return 0;
}
