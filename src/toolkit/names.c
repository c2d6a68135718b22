/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The names of the model format (coons-model(5)) for a body's edges and
 * faces and a patch's sides: the one place they are spelled; the loader,
 * coons2stl and the tests take them from here. The names of curve, patch
 * and body types are in the type tables (kinds.c).
 */
#include "coons_internal.h"

static const char *const EDGES[] = {"u00", "u01", "u10", "u11", "v00", "v01",
                                    "v10", "v11", "w00", "w01", "w10", "w11"};
static const char *const FACES[] = {"u0", "u1", "v0", "v1", "w0", "w1"};
static const char *const SIDES[] = {"t0", "t1", "s0", "s1"};

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

static const char *name_at(const char *const *names, size_t n, long i)
{
    return i >= 0 && (size_t)i < n ? names[i] : NULL;
}

const char *coons_body_edge_name(int edge) { return name_at(EDGES, COUNT(EDGES), edge); }
const char *coons_body_face_name(int face) { return name_at(FACES, COUNT(FACES), face); }
const char *coons_patch_side_name(int side) { return name_at(SIDES, COUNT(SIDES), side); }
