/* SPDX-License-Identifier: GPL-3.0-or-later */
/* --iso D=V[,V...]: the text of one isoparametric surface option into
 * coons_iso_request records (seed 000 section 2.1: u, v or w = const).
 * Only public API: the command links the library like any user. */
#include "iso_parse.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char DIR_NAME[3] = {'u', 'v', 'w'};

/* Fills err (which may be NULL) the way the library does; returns st. */
static coons_status fail(coons_error *err, coons_status st, const char *fmt, ...)
{
    if (err) {
        memset(err, 0, sizeof *err);
        err->code = st;
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
    }
    return st;
}

coons_status cli_iso_parse(const char *spec, coons_iso_request *out, size_t cap, size_t *count,
                           coons_error *err)
{
    if (!spec || !count || (!out && cap))
        return fail(err, COONS_E_INVALID, "no isoparametric surface option given");
    const char *c = spec;
    int dir = *c == 'u' ? 0 : *c == 'v' ? 1 : *c == 'w' ? 2 : -1;
    if (dir < 0 || c[1] != '=' || !c[2])
        return fail(err, COONS_E_INVALID,
                    "isoparametric surfaces '%s': expected u=, v= or w= and values, "
                    "e.g. u=0.25,0.5",
                    spec);
    c += 2;
    size_t n = *count;
    for (;;) {
        char *end;
        double v = strtod(c, &end);
        if (end == c || (*end && *end != ','))
            return fail(err, COONS_E_INVALID,
                        "isoparametric surfaces '%s': '%.*s' is not a number", spec,
                        (int)strcspn(c, ","), c);
        if (!(v >= 0.0 && v <= 1.0))
            return fail(err, COONS_E_DOMAIN, "isoparametric surfaces '%s': %c=%.*s lies outside [0,1]",
                        spec, DIR_NAME[dir], (int)(end - c), c);
        if (n >= cap)
            return fail(err, COONS_E_LIMIT,
                        "isoparametric surfaces '%s': more than %zu surfaces", spec, cap);
        out[n].direction = dir;
        out[n].value = v;
        n++;
        if (!*end) break;
        c = end + 1;
    }
    *count = n;
    return COONS_OK;
}
