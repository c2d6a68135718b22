/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The table of body readers: one row per body type of the model format,
 * named by coons_body_type_name(). A new type is a read_body_<type>.c and
 * a row here. What the readers share is in read_body_parts.c.
 */
#include <stdio.h>
#include <string.h>

#include "loader.h"

static const coons__ld_body_row BODIES[] = {
    {COONS_BODY_BODY0, coons__ld_read_body0},
    {COONS_BODY_BODY1, coons__ld_read_body1},
    {COONS_BODY_BODY2, coons__ld_read_body2},
    {COONS_BODY_BEZIER, coons__ld_read_bezier_volume},
    {COONS_BODY_BSPLINE, coons__ld_read_bspline_volume},
    {COONS_BODY_SHELL, coons__ld_read_shell},
    {COONS_BODY_MORPH, coons__ld_read_morph},
};
enum { NBODIES = sizeof BODIES / sizeof BODIES[0] };

coons_status coons__ld_body(coons__ld *L, size_t obj, size_t index, coons_body **out)
{
    if (coons__ld_is_ref(L, obj)) {
        void *r = NULL;
        coons_status st = coons__ld_ref(L, obj, COONS__LD_KIND_BODY, index, out ? &r : NULL);
        if (out) *out = r;
        return st;
    }
    const char *names[NBODIES + 1];
    for (int i = 0; i < NBODIES; i++) names[i] = coons_body_type_name(BODIES[i].type);
    names[NBODIES] = NULL;
    int type = 0;
    coons__ld_obj o;
    coons_status rc = coons__ld_typed(L, obj, "a body", names, "", &type, &o);
    if (rc) return rc;
    o.index = index;
    snprintf(o.hint, sizeof o.hint,
             "\"blend\" is allowed on body0, body1 and body2 only, not on a %s", names[type]);
    return BODIES[type].read(L, &o, out);
}
