/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Runs the fuzz target on files, without libFuzzer: the regression test
 * (tests/fuzz/regressions, the example and test models) in ordinary and
 * sanitizer builds and under valgrind. Arguments are files or directories,
 * searched recursively for regular files (hidden ones skipped). Exits 0
 * when every input was read and run; a finding aborts.
 */
#define _GNU_SOURCE /* nftw FTW_ACTIONRETVAL */
#include <ftw.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static size_t g_runs;
static int g_failed;

static int run_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        perror(path);
        return 1;
    }
    size_t cap = 4096, len = 0;
    uint8_t *buf = malloc(cap);
    for (;;) {
        if (!buf) {
            fclose(f);
            fprintf(stderr, "%s: out of memory\n", path);
            return 1;
        }
        len += fread(buf + len, 1, cap - len, f);
        if (len < cap) break;
        uint8_t *nb = realloc(buf, cap *= 2);
        if (!nb) free(buf);
        buf = nb;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        fprintf(stderr, "%s: read error\n", path);
        return 1;
    }
    if (getenv("FUZZ_REPLAY_VERBOSE")) fprintf(stderr, "%s\n", path);
    LLVMFuzzerTestOneInput(buf, len);
    free(buf);
    g_runs++;
    return 0;
}

static int visit(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    const char *base = path + ftw->base;
    if (ftw->level > 0 && base[0] == '.') return flag == FTW_D ? FTW_SKIP_SUBTREE : FTW_CONTINUE;
    if (flag == FTW_F && S_ISREG(st->st_mode)) g_failed |= run_file(path);
    if (flag == FTW_DNR || flag == FTW_NS) {
        fprintf(stderr, "%s: cannot read\n", path);
        g_failed = 1;
    }
    return FTW_CONTINUE;
}

int main(int argc, char **argv)
{
    for (int a = 1; a < argc; a++)
        if (nftw(argv[a], visit, 16, FTW_PHYS | FTW_ACTIONRETVAL) != 0) {
            perror(argv[a]);
            g_failed = 1;
        }
    printf("replayed %zu inputs%s\n", g_runs, g_failed ? " (some could not be read)" : "");
    return g_failed;
}
