/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A 3MF package read back with lib3mf's own reader (tests/tools/read3mf.cpp,
 * C++ behind this C interface), for tests/unit/write/test_3mf.c: the unit, the
 * Title metadata, every mesh object in resource order and every build
 * item. Shares no code with the library's writer. */
#ifndef COONS_TEST_READ3MF_H
#define COONS_TEST_READ3MF_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* lib3mf's MODELUNIT_* values (3MF core specification 3.4). */
enum { R3MF_MICRON = 0, R3MF_MILLIMETER, R3MF_CENTIMETER, R3MF_INCH, R3MF_FOOT, R3MF_METER };

typedef struct r3mf_object {
    uint32_t id;      /* resource id */
    int type;         /* lib3mf MODELOBJECTTYPE_*: 1 is "model" */
    char name[256];
    size_t nv, nt;
    float *v;         /* 3 per vertex */
    uint32_t *t;      /* 3 per triangle, local to the object */
    int manifold;     /* lib3mf_meshobject_ismanifoldandoriented */
} r3mf_object;

typedef struct r3mf {
    int unit;
    char title[256];  /* "" when there is no Title metadata */
    size_t nobj, nitems;
    r3mf_object *obj;
    uint32_t *item;   /* the object id of each build item */
    int item_transform; /* 1 if any build item has a transform */
} r3mf;

/* Reads `path`; 0 on success, else -1 with lib3mf's message in msg. */
int r3mf_read(const char *path, r3mf *out, char *msg, size_t cap);
void r3mf_free(r3mf *m);

#ifdef __cplusplus
}
#endif
#endif
