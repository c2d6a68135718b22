/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Union-find over uint32_t ids (parent array uf, uf[i] = i for a root),
 * shared by the sampler (merging lattice vertices) and the mesh checks
 * (shells, vertex links). The lower id always stays the representative,
 * so results do not depend on the order of unions. Internal. */
#ifndef COONS_UNION_FIND_H
#define COONS_UNION_FIND_H

#include <stdint.h>

/* The root of a's set, halving the path on the way. */
static inline uint32_t coons__uf_find(uint32_t *uf, uint32_t a)
{
    while (uf[a] != a) {
        uf[a] = uf[uf[a]];
        a = uf[a];
    }
    return a;
}

/* Joins the sets of the two roots ra, rb (distinct or not). */
static inline void coons__uf_link(uint32_t *uf, uint32_t ra, uint32_t rb)
{
    if (ra != rb) uf[ra > rb ? ra : rb] = ra < rb ? ra : rb;
}

/* Joins the sets of a and b. */
static inline void coons__uf_union(uint32_t *uf, uint32_t a, uint32_t b)
{
    coons__uf_link(uf, coons__uf_find(uf, a), coons__uf_find(uf, b));
}

#endif
