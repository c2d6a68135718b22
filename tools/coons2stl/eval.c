/* SPDX-License-Identifier: GPL-3.0-or-later */
/* --eval and --jacobian: lines "u v w" from standard input, each answered
 * with "x y z" of the body (and with --jacobian its Jacobian, row-major,
 * and det J), 17 significant digits. */
#define _POSIX_C_SOURCE 200809L /* getline */

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

/* The numbers of one line (a '#' starts a comment): their count, 0 for a
 * blank line, 4 for more than three, -1 for anything not a finite number. */
static int parse_line(char *line, double q[3])
{
    char *hash = strchr(line, '#');
    if (hash) *hash = '\0';
    int n = 0;
    const char *p = line;
    for (;;) {
        while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n' || *p == '\v' || *p == '\f')
            p++;
        if (!*p) break;
        if (n == 3) return 4;
        char *end;
        double x = strtod(p, &end);
        if (end == p || !(*end == '\0' || strchr(" \t\r\n\v\f", *end)) || !isfinite(x)) return -1;
        q[n++] = x;
        p = end;
    }
    return n;
}

/* Parameters within rounding of [0, 1] are clamped; others are an error. */
static int check_range(long lineno, double q[3])
{
    static const char names[] = "uvw";
    int status = 0;
    for (int k = 0; k < 3 && !status; k++) {
        if (q[k] < -1e-12 || q[k] > 1 + 1e-12) {
            fprintf(stderr, "%s: <stdin>:%ld: %c = %.17g is outside [0, 1]\n", PROG, lineno,
                    names[k], q[k]);
            status = EXIT_INPUT;
        }
        q[k] = q[k] < 0 ? 0 : q[k] > 1 ? 1 : q[k];
    }
    return status;
}

static void print_point(const coons_body *b, const double q[3], int jacobian)
{
    double x[3], J[3][3];
    if (jacobian) {
        double det = coons_body_eval_jacobian(b, q[0], q[1], q[2], x, J);
        printf("%.17g %.17g %.17g", x[0], x[1], x[2]);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) printf(" %.17g", J[r][c]);
        printf(" %.17g\n", det);
    } else {
        coons_body_eval(b, q[0], q[1], q[2], x);
        printf("%.17g %.17g %.17g\n", x[0], x[1], x[2]);
    }
}

int cli_eval(const coons_body *b, int jacobian)
{
    char *line = NULL;
    size_t cap = 0;
    long lineno = 0;
    int status = 0;
    /* One write per line, so that a program driving coons2stl through a
     * pipe gets each answer at once. */
    setvbuf(stdout, NULL, _IOLBF, 0);
    while (!status && getline(&line, &cap, stdin) != -1) {
        lineno++;
        double q[3];
        int n = parse_line(line, q);
        if (n == 0) continue; /* blank line or comment */
        if (n != 3) {
            fprintf(stderr, "%s: <stdin>:%ld: expected three numbers \"u v w\"\n", PROG, lineno);
            status = EXIT_INPUT;
        } else if (!(status = check_range(lineno, q))) {
            print_point(b, q, jacobian);
        }
    }
    free(line);
    if (!status && ferror(stdin)) {
        fprintf(stderr, "%s: <stdin>: cannot read: %s\n", PROG, strerror(errno));
        status = EXIT_INPUT;
    }
    return status;
}
