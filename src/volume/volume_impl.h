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

#endif
