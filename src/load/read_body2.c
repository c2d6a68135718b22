/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Reader of body2 (seed 000 section 2.4): the 6 face patches, agreeing
 * along the 12 edges they share (src/core/agree.h), and a blend.
 */
#include <stdio.h>

#include "agree.h"
#include "loader.h"

static const char *const KEYS[] = {"type", "name", "blend", "faces", NULL};

/* The shared edges, as an error at the first face of the two. */
static coons_status edges(coons__ld *L, coons_patch *const f[6], const size_t tok[6])
{
    const coons_patch *ff[6];
    for (int k = 0; k < 6; k++) ff[k] = f[k];
    coons__agree r;
    if (!coons__agree_body2_edges(ff, L->ctol, &r)) return COONS_OK;
    const char *a = coons_body_face_name(r.a), *b = coons_body_face_name(r.b);
    char sa[96], sb[96];
    coons__ld_fmt3(sa, sizeof sa, r.pa);
    coons__ld_fmt3(sb, sizeof sb, r.pb);
    return coons__ld_fail_in(L, "faces", a, tok[r.a], COONS_E_INCOMPATIBLE,
                             "faces %s and %s disagree along their shared edge %s: at %c = %.6g, "
                             "%s gives %s and %s gives %s, %.3g apart, more than the tolerance "
                             "%.3g. Faces that share an edge must be the same curve there at "
                             "the same parameter: give both the same knots and equal control "
                             "points along the edge, or build the faces from the edge curves "
                             "(\"type\": \"coons\")",
                             a, b, coons_body_edge_name(r.at), "uvw"[r.at / 4], r.ta, a, sa, b,
                             sb, r.dist, L->ctol);
}

coons_status coons__ld_read_body2(coons__ld *L, coons__ld_obj *o, coons_body **out)
{
    size_t v[4], sub[12];
    coons_blend bl = COONS_BLEND_LINEAR;
    coons_patch *f[6] = {0};
    coons_status rc = coons__ld_body_keys(L, o, KEYS, v);
    if (!rc) rc = coons__ld_blend(L, v[2], &bl);
    if (!rc) rc = coons__ld_body_parts(L, o, v[3], 0, NULL, f, sub);
    if (!rc && L->build) rc = edges(L, f, sub);
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        coons_status r = coons_body_new_body2(f, bl, L->ctol, out, &e);
        rc = coons__ld_body_built(L, o, v[3], "faces", r, &e);
    }
    for (int k = 0; k < 6; k++) coons_patch_free(f[k]);
    return rc;
}
