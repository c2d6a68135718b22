/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The volume mesh container: nodes, hexahedral cells of one element kind
 * and the parts they belong to (include/coons/volume.h). Every input is
 * validated completely before anything is allocated or changed, so a
 * failed call leaves the mesh as it was. */
#include <stdio.h>
#include <string.h>

#include "volume_impl.h"

coons_status coons_volume_mesh_new(coons_element element, coons_volume_mesh **out,
                                   coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "no output pointer given");
    *out = NULL;
    if (element != COONS_ELEMENT_HEX8 && element != COONS_ELEMENT_HEX20 &&
        element != COONS_ELEMENT_HEX27)
        return coons__error_set(err, COONS_E_INVALID,
                                "element kind %d: expected hex8 (8), hex20 (20) or hex27 (27)",
                                (int)element);
    coons_volume_mesh *vm = coons__calloc(1, sizeof *vm);
    if (!vm) return coons__error_nomem(err);
    vm->element = element;
    vm->npc = (size_t)element;
    *out = vm;
    return COONS_OK;
}

void coons_volume_mesh_free(coons_volume_mesh *vm)
{
    if (!vm) return;
    char **names = vm->parts.items;
    for (size_t i = 0; i < vm->parts.count; i++) coons__free(names[i]);
    coons__free(names);
    coons__vfields_free(vm);
    coons__free(vm->xyz);
    coons__free(vm->cell);
    coons__free(vm->part);
    coons__free(vm);
}

coons_status coons_volume_mesh_add_nodes(coons_volume_mesh *vm, const double *xyz, size_t n,
                                         size_t *first, coons_error *err)
{
    if (!vm) return coons__error_set(err, COONS_E_INVALID, "no volume mesh given");
    /* The second bound matters where size_t has 32 bits. */
    if (n > (size_t)UINT32_MAX - vm->nn || n > SIZE_MAX / (3 * sizeof(double)) - vm->nn)
        return coons__error_set(err, COONS_E_LIMIT,
                                "a volume mesh holds at most %lu nodes: %zu plus %zu is more",
                                (unsigned long)UINT32_MAX, vm->nn, n);
    if (n && !xyz) return coons__error_set(err, COONS_E_INVALID, "no node coordinates given");
    if (n && vm->fields[COONS_FIELD_NODE].count)
        return coons__error_set(err, COONS_E_INVALID,
                                "nodes cannot be added after a node field ('%s')",
                                *(char *const *)vm->fields[COONS_FIELD_NODE].items);
    for (size_t i = 0; i < 3 * n; i++)
        if (!isfinite(xyz[i]))
            return coons__error_set(err, COONS_E_INVALID,
                                    "node %zu (new node %zu) has a coordinate that is not finite",
                                    vm->nn + i / 3, i / 3);
    if (!coons__vgrow((void **)&vm->xyz, &vm->cap_n, vm->nn + n, 3 * sizeof(double)))
        return coons__error_nomem(err);
    if (n) memcpy(vm->xyz + 3 * vm->nn, xyz, 3 * n * sizeof(double));
    if (first) *first = vm->nn;
    vm->nn += n;
    return COONS_OK;
}

coons_status coons_volume_mesh_add_part(coons_volume_mesh *vm, const char *name, size_t *index,
                                        coons_error *err)
{
    if (!vm) return coons__error_set(err, COONS_E_INVALID, "no volume mesh given");
    if (vm->parts.count >= (size_t)UINT32_MAX)
        return coons__error_set(err, COONS_E_LIMIT, "a volume mesh holds at most %lu parts",
                                (unsigned long)UINT32_MAX);
    char buf[32];
    if (!name) {
        snprintf(buf, sizeof buf, "part%zu", vm->parts.count);
        name = buf;
    }
    coons_status st = coons__vname_check(name, "a part", vm->parts.items, vm->parts.count,
                                         sizeof(char *), err);
    if (st != COONS_OK) return st;
    char *copy = coons__vstrdup(name);
    if (!copy || !coons__vgrow(&vm->parts.items, &vm->parts.cap, vm->parts.count + 1,
                               sizeof(char *))) {
        coons__free(copy);
        return coons__error_nomem(err);
    }
    ((char **)vm->parts.items)[vm->parts.count] = copy;
    if (index) *index = vm->parts.count;
    vm->parts.count++;
    return COONS_OK;
}

coons_status coons_volume_mesh_add_cells(coons_volume_mesh *vm, const uint32_t *nodes, size_t n,
                                         size_t part, size_t *first, coons_error *err)
{
    if (!vm) return coons__error_set(err, COONS_E_INVALID, "no volume mesh given");
    if (n > (size_t)UINT32_MAX - vm->nc || n > SIZE_MAX / (vm->npc * sizeof(uint32_t)) - vm->nc)
        return coons__error_set(err, COONS_E_LIMIT,
                                "a volume mesh holds at most %lu cells: %zu plus %zu is more",
                                (unsigned long)UINT32_MAX, vm->nc, n);
    if (n && !nodes) return coons__error_set(err, COONS_E_INVALID, "no cell nodes given");
    if (part >= vm->parts.count)
        return coons__error_set(err, COONS_E_INVALID,
                                "cells of part %zu, but the mesh has %zu parts", part,
                                vm->parts.count);
    if (n && vm->fields[COONS_FIELD_CELL].count)
        return coons__error_set(err, COONS_E_INVALID,
                                "cells cannot be added after a cell field ('%s')",
                                *(char *const *)vm->fields[COONS_FIELD_CELL].items);
    size_t npc = vm->npc;
    for (size_t i = 0; i < npc * n; i++)
        if (nodes[i] >= vm->nn)
            return coons__error_set(err, COONS_E_INVALID,
                                    "cell %zu (new cell %zu), node %zu: index %lu, but the mesh "
                                    "has %zu nodes",
                                    vm->nc + i / npc, i / npc, i % npc, (unsigned long)nodes[i],
                                    vm->nn);
    size_t cap = vm->cap_c;
    if (!coons__vgrow((void **)&vm->cell, &cap, vm->nc + n, npc * sizeof(uint32_t)))
        return coons__error_nomem(err);
    cap = vm->cap_c;
    if (!coons__vgrow((void **)&vm->part, &cap, vm->nc + n, sizeof(uint32_t)))
        return coons__error_nomem(err); /* the larger cell array is kept: harmless */
    vm->cap_c = cap;
    if (n) memcpy(vm->cell + npc * vm->nc, nodes, npc * n * sizeof(uint32_t));
    for (size_t i = 0; i < n; i++) vm->part[vm->nc + i] = (uint32_t)part;
    if (first) *first = vm->nc;
    vm->nc += n;
    return COONS_OK;
}

coons_element coons_volume_mesh_element(const coons_volume_mesh *vm) { return vm->element; }
size_t coons_volume_mesh_nodes_per_cell(const coons_volume_mesh *vm) { return vm->npc; }
size_t coons_volume_mesh_node_count(const coons_volume_mesh *vm) { return vm->nn; }
size_t coons_volume_mesh_cell_count(const coons_volume_mesh *vm) { return vm->nc; }
size_t coons_volume_mesh_part_count(const coons_volume_mesh *vm) { return vm->parts.count; }
const double *coons_volume_mesh_nodes(const coons_volume_mesh *vm) { return vm->xyz; }
const uint32_t *coons_volume_mesh_cells(const coons_volume_mesh *vm) { return vm->cell; }
const uint32_t *coons_volume_mesh_cell_parts(const coons_volume_mesh *vm) { return vm->part; }
const char *coons_volume_mesh_part_name(const coons_volume_mesh *vm, size_t i)
{
    return i < vm->parts.count ? ((char *const *)vm->parts.items)[i] : NULL;
}

double *coons__volume_mesh_reserve_nodes(coons_volume_mesh *vm, size_t n, coons_error *err)
{
    if (n > (size_t)UINT32_MAX - vm->nn || n > SIZE_MAX / (3 * sizeof(double)) - vm->nn) {
        coons__error_set(err, COONS_E_LIMIT,
                         "a volume mesh holds at most %lu nodes: %zu plus %zu is more",
                         (unsigned long)UINT32_MAX, vm->nn, n);
        return NULL;
    }
    if (!coons__vgrow((void **)&vm->xyz, &vm->cap_n, vm->nn + n ? vm->nn + n : 1,
                      3 * sizeof(double))) {
        coons__error_nomem(err);
        return NULL;
    }
    double *p = vm->xyz + 3 * vm->nn;
    vm->nn += n;
    return p;
}

uint32_t *coons__volume_mesh_reserve_cells(coons_volume_mesh *vm, size_t n, size_t part,
                                           coons_error *err)
{
    if (n > (size_t)UINT32_MAX - vm->nc || n > SIZE_MAX / (vm->npc * sizeof(uint32_t)) - vm->nc) {
        coons__error_set(err, COONS_E_LIMIT,
                         "a volume mesh holds at most %lu cells: %zu plus %zu is more",
                         (unsigned long)UINT32_MAX, vm->nc, n);
        return NULL;
    }
    size_t need = vm->nc + n ? vm->nc + n : 1, cap = vm->cap_c;
    if (!coons__vgrow((void **)&vm->cell, &cap, need, vm->npc * sizeof(uint32_t))) {
        coons__error_nomem(err);
        return NULL;
    }
    cap = vm->cap_c;
    if (!coons__vgrow((void **)&vm->part, &cap, need, sizeof(uint32_t))) {
        coons__error_nomem(err);
        return NULL;
    }
    vm->cap_c = cap;
    for (size_t i = 0; i < n; i++) vm->part[vm->nc + i] = (uint32_t)part;
    uint32_t *p = vm->cell + vm->npc * vm->nc;
    vm->nc += n;
    return p;
}
