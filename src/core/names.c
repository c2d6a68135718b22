/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The names of the model format (coons-model(5)): curve, patch and body
 * types, a body's edges and faces, a patch's sides. The one place they are
 * spelled; the loader, coons2stl and the tests take them from here.
 */
#include <string.h>

#include "coons_internal.h"

static const char *const CURVE_TYPES[] = {"line",        "polyline",      "bezier", "hermite",
                                          "coons-cubic", "clamped-cubic", "bspline"};
static const char *const PATCH_TYPES[] = {"bilinear",      "ruled",          "coons",
                                          "hermite-coons", "bezier-surface", "bspline-surface"};
static const char *const BODY_TYPES[] = {"body0", "body1", "body2", "bezier-volume",
                                         "bspline-volume"};
static const char *const EDGES[] = {"u00", "u01", "u10", "u11", "v00", "v01",
                                    "v10", "v11", "w00", "w01", "w10", "w11"};
static const char *const FACES[] = {"u0", "u1", "v0", "v1", "w0", "w1"};
static const char *const SIDES[] = {"t0", "t1", "s0", "s1"};

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

static const char *name_at(const char *const *names, size_t n, long i)
{
    return i >= 0 && (size_t)i < n ? names[i] : NULL;
}

static coons_status index_of(const char *const *names, size_t n, const char *name,
                             const char *what, int *out, coons_error *err)
{
    for (size_t i = 0; name && i < n; i++)
        if (strcmp(names[i], name) == 0) {
            *out = (int)i;
            return COONS_OK;
        }
    return coons__error_set(err, COONS_E_INVALID, "unknown %s \"%s\"", what, name ? name : "");
}

const char *coons_curve_type_name(coons_curve_type type)
{
    return name_at(CURVE_TYPES, COUNT(CURVE_TYPES), (long)type);
}

const char *coons_patch_type_name(coons_patch_type type)
{
    return name_at(PATCH_TYPES, COUNT(PATCH_TYPES), (long)type);
}

const char *coons_body_type_name(coons_body_type type)
{
    return name_at(BODY_TYPES, COUNT(BODY_TYPES), (long)type);
}

coons_status coons_curve_type_from_name(const char *name, coons_curve_type *out,
                                        coons_error *err)
{
    int i = 0;
    coons_status st = index_of(CURVE_TYPES, COUNT(CURVE_TYPES), name, "curve type", &i, err);
    if (!st) *out = (coons_curve_type)i;
    return st;
}

coons_status coons_patch_type_from_name(const char *name, coons_patch_type *out,
                                        coons_error *err)
{
    int i = 0;
    coons_status st = index_of(PATCH_TYPES, COUNT(PATCH_TYPES), name, "patch type", &i, err);
    if (!st) *out = (coons_patch_type)i;
    return st;
}

coons_status coons_body_type_from_name(const char *name, coons_body_type *out,
                                       coons_error *err)
{
    int i = 0;
    coons_status st = index_of(BODY_TYPES, COUNT(BODY_TYPES), name, "body type", &i, err);
    if (!st) *out = (coons_body_type)i;
    return st;
}

const char *coons_body_edge_name(int edge) { return name_at(EDGES, COUNT(EDGES), edge); }
const char *coons_body_face_name(int face) { return name_at(FACES, COUNT(FACES), face); }
const char *coons_patch_side_name(int side) { return name_at(SIDES, COUNT(SIDES), side); }
