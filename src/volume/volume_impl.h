/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The volume mesh record (include/coons/volume.h), shared by the files of
 * src/mesh/volume. Writers see it only through the public accessors. */
#ifndef COONS_VOLUME_IMPL_H
#define COONS_VOLUME_IMPL_H

#include "coons_internal.h"

typedef struct coons__vfield {
    char *name;
    coons_field_type type;
    void *values; /* count of its location, double or int32_t */
} coons__vfield;

typedef struct coons__vset {
    char *name;
    uint32_t *items; /* count (node/cell sets) or 2 * count (face sets) */
    size_t count;
} coons__vset;

/* A growable array of records of one kind (fields, sets, part names). */
typedef struct coons__vlist {
    void *items;
    size_t count, cap;
} coons__vlist;

struct coons_volume_mesh {
    coons_element element;
    size_t npc;     /* nodes per cell */
    double *xyz;    /* 3 * nn */
    uint32_t *cell; /* npc * nc */
    uint32_t *part; /* nc */
    size_t nn, nc, cap_n, cap_c;
    coons__vlist parts;     /* char * */
    coons__vlist fields[2]; /* coons__vfield, by coons_field_location */
    coons__vlist sets[3];   /* coons__vset: node, cell, face sets */
};

enum { COONS__VSET_NODE = 0, COONS__VSET_CELL = 1, COONS__VSET_FACE = 2 };

/* Grows *p (capacity *cap elements of `elem` bytes) to hold `need`;
 * returns 0 when that overflows or the allocation fails (*p unchanged). */
int coons__vgrow(void **p, size_t *cap, size_t need, size_t elem);

/* Checks a part or set name (`what` names it in messages): not empty, no
 * control characters, at most COONS_VOLUME_NAME_MAX bytes, and, when
 * `taken`/`stride` are given, not equal to the name at the start of any of
 * the `n` records of `stride` bytes at `taken`. */
coons_status coons__vname_check(const char *name, const char *what, const void *taken, size_t n,
                                size_t stride, coons_error *err);
/* Copy of a checked name, or NULL. */
char *coons__vstrdup(const char *s);

void coons__vfields_free(coons_volume_mesh *vm);

/* The scaled Jacobian (coons_volume_mesh_cell_scaled_jacobian()) of cells
 * [lo, hi) into out[0 .. hi - lo). */
void coons__volume_mesh_scaled_jacobians(const coons_volume_mesh *vm, size_t lo, size_t hi,
                                         double *out);

/* For the mesher, which fills what it reserves with valid values before
 * anyone reads the mesh: n new nodes (3 n doubles), appended uninitialised;
 * NULL (err set, mesh unchanged) over the limits or without memory. */
double *coons__volume_mesh_reserve_nodes(coons_volume_mesh *vm, size_t n, coons_error *err);
/* n new cells of `part` (npc * n node indices, uninitialised). */
uint32_t *coons__volume_mesh_reserve_cells(coons_volume_mesh *vm, size_t n, size_t part,
                                           coons_error *err);
/* A new field of the mesh's nodes or cells, its values uninitialised
 * (they must be finite); NULL (err set) on a bad name or without memory. */
void *coons__volume_mesh_reserve_field(coons_volume_mesh *vm, coons_field_location location,
                                       const char *name, coons_field_type type, coons_error *err);

#endif
