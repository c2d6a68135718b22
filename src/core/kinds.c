/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The tables of kinds.h: one row per curve, patch and body type, indexed by
 * the public type enum, with the type's model-format name (coons-model(5)),
 * the one place those names are spelled; the loader, coons2stl and the
 * tests take them from here (coons_*_type_name, coons_*_type_from_name).
 * Names of edges, faces and sides are in names.c. The wrappers of
 * kinds.h (transformed, reversed, reparametrised) are rows without a table
 * entry: they are not types of the format, and report the wrapped type.
 */
#include <string.h>

#include "kinds.h"

/* A row of a table: the type's name and its operations (a
 * coons__curve_kind, coons__patch_kind or coons__body_kind by table). */
typedef struct row {
    const char *name;
    const void *kind;
} row;

static const row CURVES[] = {
    [COONS_CURVE_LINE] = {"line", &coons__line_kind},
    [COONS_CURVE_POLYLINE] = {"polyline", &coons__polyline_kind},
    [COONS_CURVE_BEZIER] = {"bezier", &coons__bezier_kind},
    [COONS_CURVE_HERMITE] = {"hermite", &coons__hermite_kind},
    [COONS_CURVE_COONS_CUBIC] = {"coons-cubic", &coons__coons_cubic_kind},
    [COONS_CURVE_CLAMPED_CUBIC] = {"clamped-cubic", &coons__clamped_cubic_kind},
    [COONS_CURVE_BSPLINE] = {"bspline", &coons__bspline_kind},
};

static const row PATCHES[] = {
    [COONS_PATCH_BILINEAR] = {"bilinear", &coons__bilinear_kind},
    [COONS_PATCH_RULED] = {"ruled", &coons__ruled_kind},
    [COONS_PATCH_COONS] = {"coons", &coons__coons_patch_kind},
    [COONS_PATCH_HERMITE_COONS] = {"hermite-coons", &coons__hermite_coons_kind},
    [COONS_PATCH_BEZIER] = {"bezier-surface", &coons__bezier_surface_kind},
    [COONS_PATCH_BSPLINE] = {"bspline-surface", &coons__bspline_surface_kind},
    [COONS_PATCH_NETWORK] = {"network", &coons__network_kind},
};

static const row BODIES[] = {
    [COONS_BODY_BODY0] = {"body0", &coons__body0_kind},
    [COONS_BODY_BODY1] = {"body1", &coons__body1_kind},
    [COONS_BODY_BODY2] = {"body2", &coons__body2_kind},
    [COONS_BODY_BEZIER] = {"bezier-volume", &coons__bezier_volume_kind},
    [COONS_BODY_BSPLINE] = {"bspline-volume", &coons__bspline_volume_kind},
    [COONS_BODY_SHELL] = {"shell", &coons__shell_kind},
    [COONS_BODY_MORPH] = {"morph", &coons__morph_kind},
};

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

/* Row i of a table of n rows, or NULL (a value outside the enum). */
static const row *row_at(const row *table, size_t n, long i)
{
    return i >= 0 && (size_t)i < n ? &table[i] : NULL;
}

static const void *kind_at(const row *table, size_t n, long i)
{
    const row *r = row_at(table, n, i);
    return r ? r->kind : NULL;
}

static const char *name_at(const row *table, size_t n, long i)
{
    const row *r = row_at(table, n, i);
    return r ? r->name : NULL;
}

/* The index of the row named `name`. */
static coons_status index_of(const row *table, size_t n, const char *name, const char *what,
                             int *out, coons_error *err)
{
    for (size_t i = 0; name && i < n; i++)
        if (strcmp(table[i].name, name) == 0) {
            *out = (int)i;
            return COONS_OK;
        }
    return coons__error_set(err, COONS_E_INVALID, "unknown %s \"%s\"", what, name ? name : "");
}

const coons__curve_kind *coons__curve_kind_of(coons_curve_type type)
{
    return kind_at(CURVES, COUNT(CURVES), (long)type);
}

const coons__patch_kind *coons__patch_kind_of(coons_patch_type type)
{
    return kind_at(PATCHES, COUNT(PATCHES), (long)type);
}

const coons__body_kind *coons__body_kind_of(coons_body_type type)
{
    return kind_at(BODIES, COUNT(BODIES), (long)type);
}

const char *coons_curve_type_name(coons_curve_type type)
{
    return name_at(CURVES, COUNT(CURVES), (long)type);
}

const char *coons_patch_type_name(coons_patch_type type)
{
    return name_at(PATCHES, COUNT(PATCHES), (long)type);
}

const char *coons_body_type_name(coons_body_type type)
{
    return name_at(BODIES, COUNT(BODIES), (long)type);
}

coons_status coons_curve_type_from_name(const char *name, coons_curve_type *out,
                                        coons_error *err)
{
    int i = 0;
    coons_status st = index_of(CURVES, COUNT(CURVES), name, "curve type", &i, err);
    if (!st) *out = (coons_curve_type)i;
    return st;
}

coons_status coons_patch_type_from_name(const char *name, coons_patch_type *out,
                                        coons_error *err)
{
    int i = 0;
    coons_status st = index_of(PATCHES, COUNT(PATCHES), name, "patch type", &i, err);
    if (!st) *out = (coons_patch_type)i;
    return st;
}

coons_status coons_body_type_from_name(const char *name, coons_body_type *out,
                                       coons_error *err)
{
    int i = 0;
    coons_status st = index_of(BODIES, COUNT(BODIES), name, "body type", &i, err);
    if (!st) *out = (coons_body_type)i;
    return st;
}
