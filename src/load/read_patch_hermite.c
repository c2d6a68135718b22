/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Reader of the hermite-coons patch (seed 001 section 1.2.1): four
 * boundary curves, optionally the four cross curves (tangents across the
 * boundary, which must agree with the boundary's tangents at the corners)
 * and the twist.
 */
#include "agree.h"
#include "loader.h"

static const char *const KEYS[] = {"type", "boundary", "cross", "twist", NULL};

static coons_status twist(coons__ld *L, size_t tok, coons_hermite_options *o)
{
    static const char *const NAMES[] = {"zero", "adini", "bessel", NULL};
    static const coons_twist VALS[] = {COONS_TWIST_ZERO, COONS_TWIST_ADINI, COONS_TWIST_BESSEL};
    coons__json_type t = coons__json_type_of(L->j, tok);
    const char *desc = "\"zero\", \"adini\", \"bessel\" or an array of 4 twist vectors";
    if (t == COONS__JSON_STRING) {
        for (int i = 0; NAMES[i]; i++)
            if (coons__json_string_eq(L->j, tok, NAMES[i])) {
                o->twist = VALS[i];
                return COONS_OK;
            }
        char s[64];
        coons__ld_text_of(L, tok, s, sizeof s);
        return coons__ld_fail(L, tok, COONS_E_INVALID, "unknown twist \"%s\"; expected %s", s,
                              desc);
    }
    if (t != COONS__JSON_ARRAY)
        return coons__ld_fail(L, tok, COONS_E_INVALID, "expected %s, found %s", desc,
                              coons__ld_kind(L, tok));
    if (coons__json_size(L->j, tok) != 4)
        return coons__ld_fail(L, tok, COONS_E_INVALID,
                              "expected 4 twist vectors [x_st(0,0), x_st(1,0), x_st(0,1), "
                              "x_st(1,1)], found %zu",
                              coons__json_size(L->j, tok));
    size_t e = tok + 1;
    for (int i = 0; i < 4; i++, e = coons__json_next(L->j, e)) {
        size_t old = coons__ld_push_index(L, (size_t)i);
        coons_status rc = coons__ld_vec(L, e, COONS__LD_VECTOR, o->twists[i]);
        coons__ld_pop(L, old);
        if (rc) return rc;
    }
    o->twist = COONS_TWIST_EXPLICIT;
    return COONS_OK;
}

/* Cross curves against the boundary tangents, as an error at the boundary
 * curve. */
static coons_status cross_check(coons__ld *L, coons_curve *const bd[4], coons_curve *const cr[4],
                                const size_t btok[4])
{
    const coons_curve *const b[4] = {bd[0], bd[1], bd[2], bd[3]};
    const coons_curve *const c[4] = {cr[0], cr[1], cr[2], cr[3]};
    coons__agree r;
    if (!coons__agree_cross(b, c, L->ctol, &r)) return COONS_OK;
    const char *k = coons_patch_side_name(r.at), *other = coons_patch_side_name(r.b);
    char sa[96], sb[96];
    coons__ld_fmt3(sa, sizeof sa, r.pa);
    coons__ld_fmt3(sb, sizeof sb, r.pb);
    return coons__ld_fail_in(L, "boundary", other, btok[r.b], COONS_E_INCOMPATIBLE,
                             "cross curve %s disagrees with boundary curve %s: cross.%s(%d) = %s "
                             "but %s'(%d) = %s, %.3g apart, more than the tolerance %.3g",
                             k, other, k, (int)r.ta, sa, other, (int)r.tb, sb, r.dist, L->ctol);
}

/* "cross" (tok 0: none) and "twist". */
static coons_status cross_and_twist(coons__ld *L, size_t vcross, size_t vtwist,
                                    coons_curve *cr[4], coons_hermite_options *ho)
{
    coons_status rc = COONS_OK;
    if (vcross) {
        size_t ctok[4] = {0};
        int was = L->bbox_on;
        L->bbox_on = 0; /* cross curves are tangents, not points */
        rc = coons__ld_four_curves(L, vcross, "cross", "cross", cr, ctok);
        L->bbox_on = was;
        if (rc) return rc;
    }
    if (vtwist) {
        size_t old = coons__ld_push_key(L, "twist");
        rc = twist(L, vtwist, ho);
        coons__ld_pop(L, old);
    }
    return rc;
}

coons_status coons__ld_read_hermite_coons(coons__ld *L, coons__ld_obj *o, coons_patch **out)
{
    size_t v[4], btok[4] = {0};
    coons_curve *bd[4] = {0}, *cr[4] = {0};
    coons_hermite_options ho = COONS_HERMITE_OPTIONS_INIT;
    coons_status rc = coons__ld_keys(L, o, KEYS, v);
    if (!rc) rc = coons__ld_need(L, o->tok, v[1], "boundary", o->need);
    if (!rc) rc = coons__ld_four_curves(L, v[1], "boundary", "a boundary", bd, btok);
    if (!rc) rc = cross_and_twist(L, v[2], v[3], cr, &ho);
    if (!rc && L->build) rc = coons__ld_patch_corners(L, bd, btok);
    if (!rc && L->build && v[2]) rc = cross_check(L, bd, cr, btok);
    if (!rc && L->build) {
        if (v[2])
            for (int k = 0; k < 4; k++) ho.cross[k] = cr[k];
        ho.tol = L->ctol;
        coons_error e = COONS_ERROR_INIT;
        rc = coons__ld_built(L, o->tok, coons_patch_new_hermite_coons(bd, &ho, out, &e), o->what,
                             &e);
    }
    coons__ld_free_curves(bd, 4);
    coons__ld_free_curves(cr, 4);
    return rc;
}
