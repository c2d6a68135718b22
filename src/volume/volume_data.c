/* SPDX-License-Identifier: GPL-3.0-or-later */
/* What a volume mesh carries besides its geometry: named scalar fields per
 * node or per cell, and named node, cell and face sets
 * (include/coons/volume.h). As for nodes and cells, every input is checked
 * before anything changes. */
#include <stdio.h>
#include <string.h>

#include "volume_impl.h"

static const char *const LOCATION[2] = {"node", "cell"};
static const char *const SET_KIND[3] = {"a node set", "a cell set", "a face set"};

void coons__vfields_free(coons_volume_mesh *vm)
{
    for (int l = 0; l < 2; l++) {
        coons__vfield *f = vm->fields[l].items;
        for (size_t i = 0; i < vm->fields[l].count; i++) {
            coons__free(f[i].name);
            coons__free(f[i].values);
        }
        coons__free(f);
    }
    for (int k = 0; k < 3; k++) {
        coons__vset *s = vm->sets[k].items;
        for (size_t i = 0; i < vm->sets[k].count; i++) {
            coons__free(s[i].name);
            coons__free(s[i].items);
        }
        coons__free(s);
    }
}

static int is_identifier(const char *s)
{
    if (!((*s >= 'A' && *s <= 'Z') || (*s >= 'a' && *s <= 'z') || *s == '_')) return 0;
    for (; *s; s++)
        if (!((*s >= 'A' && *s <= 'Z') || (*s >= 'a' && *s <= 'z') || (*s >= '0' && *s <= '9') ||
              *s == '_'))
            return 0;
    return 1;
}

/* The checks of a new field (all but its values) and, when they pass, the
 * field itself with room for its values. */
static coons_status new_field(coons_volume_mesh *vm, coons_field_location location,
                              const char *name, coons_field_type type, void **values,
                              coons_error *err)
{
    if (!vm) return coons__error_set(err, COONS_E_INVALID, "no volume mesh given");
    if (location != COONS_FIELD_NODE && location != COONS_FIELD_CELL)
        return coons__error_set(err, COONS_E_INVALID, "field location %d: expected node (0) or "
                                "cell (1)", (int)location);
    if (type != COONS_FIELD_FLOAT64 && type != COONS_FIELD_INT32)
        return coons__error_set(err, COONS_E_INVALID, "field type %d: expected Float64 (0) or "
                                "Int32 (1)", (int)type);
    coons__vlist *list = &vm->fields[location];
    char what[32];
    snprintf(what, sizeof what, "a %s field", LOCATION[location]);
    coons_status st = coons__vname_check(name, what, list->items, list->count,
                                         sizeof(coons__vfield), err);
    if (st != COONS_OK) return st;
    if (!is_identifier(name))
        return coons__error_set(err, COONS_E_INVALID,
                                "field name '%s' is not an identifier ([A-Za-z_][A-Za-z0-9_]*)",
                                name);
    size_t n = location == COONS_FIELD_NODE ? vm->nn : vm->nc;
    if (values && n && !*values)
        return coons__error_set(err, COONS_E_INVALID, "no values given for the %s field '%s'",
                                LOCATION[location], name);
    if (values && type == COONS_FIELD_FLOAT64)
        for (size_t i = 0; i < n; i++)
            if (!isfinite(((const double *)*values)[i]))
                return coons__error_set(err, COONS_E_INVALID,
                                        "%s field '%s': the value of %s %zu is not finite",
                                        LOCATION[location], name, LOCATION[location], i);
    size_t size = type == COONS_FIELD_FLOAT64 ? sizeof(double) : sizeof(int32_t);
    coons__vfield f = {coons__vstrdup(name), type, coons__malloc_array(n, size)};
    if (!f.name || !f.values ||
        !coons__vgrow(&list->items, &list->cap, list->count + 1, sizeof f)) {
        coons__free(f.name);
        coons__free(f.values);
        return coons__error_nomem(err);
    }
    if (n && values) memcpy(f.values, *values, n * size);
    if (values) *values = f.values;
    ((coons__vfield *)list->items)[list->count++] = f;
    return COONS_OK;
}

coons_status coons_volume_mesh_add_field(coons_volume_mesh *vm, coons_field_location location,
                                         const char *name, coons_field_type type,
                                         const void *values, coons_error *err)
{
    void *v = (void *)(uintptr_t)values;
    return new_field(vm, location, name, type, &v, err);
}

void *coons__volume_mesh_reserve_field(coons_volume_mesh *vm, coons_field_location location,
                                       const char *name, coons_field_type type, coons_error *err)
{
    void *v = NULL;
    if (new_field(vm, location, name, type, NULL, err) != COONS_OK) return NULL;
    v = ((coons__vfield *)vm->fields[location].items)[vm->fields[location].count - 1].values;
    return v;
}

/* Adds set `kind` of n entries of `width` indices each (1, or 2 for the
 * (cell, local face) pairs of face sets). */
static coons_status add_set(coons_volume_mesh *vm, int kind, const char *name,
                            const uint32_t *items, size_t n, size_t width, coons_error *err)
{
    if (!vm) return coons__error_set(err, COONS_E_INVALID, "no volume mesh given");
    coons__vlist *list = &vm->sets[kind];
    coons_status st = coons__vname_check(name, SET_KIND[kind], list->items, list->count,
                                         sizeof(coons__vset), err);
    if (st != COONS_OK) return st;
    if (n > SIZE_MAX / sizeof(uint32_t) / width)
        return coons__error_set(err, COONS_E_LIMIT, "%s '%s' of %zu entries is too large",
                                SET_KIND[kind], name, n);
    if (n && !items)
        return coons__error_set(err, COONS_E_INVALID, "no indices given for %s '%s'",
                                SET_KIND[kind], name);
    size_t limit = kind == COONS__VSET_NODE ? vm->nn : vm->nc;
    const char *of = kind == COONS__VSET_NODE ? "node" : "cell";
    for (size_t i = 0; i < n; i++) {
        if (items[width * i] >= limit)
            return coons__error_set(err, COONS_E_INVALID,
                                    "%s '%s', entry %zu: %s %lu, but the mesh has %zu %ss",
                                    SET_KIND[kind], name, i, of, (unsigned long)items[width * i],
                                    limit, of);
        if (width == 2 && items[2 * i + 1] > 5)
            return coons__error_set(err, COONS_E_INVALID,
                                    "%s '%s', entry %zu: local face %lu (a hexahedron has faces "
                                    "0..5)",
                                    SET_KIND[kind], name, i, (unsigned long)items[2 * i + 1]);
    }
    coons__vset s = {coons__vstrdup(name), coons__malloc_array(n, width * sizeof(uint32_t)), n};
    if (!s.name || !s.items || !coons__vgrow(&list->items, &list->cap, list->count + 1, sizeof s)) {
        coons__free(s.name);
        coons__free(s.items);
        return coons__error_nomem(err);
    }
    if (n) memcpy(s.items, items, n * width * sizeof(uint32_t));
    ((coons__vset *)list->items)[list->count++] = s;
    return COONS_OK;
}

coons_status coons_volume_mesh_add_node_set(coons_volume_mesh *vm, const char *name,
                                            const uint32_t *nodes, size_t n, coons_error *err)
{
    return add_set(vm, COONS__VSET_NODE, name, nodes, n, 1, err);
}

coons_status coons_volume_mesh_add_cell_set(coons_volume_mesh *vm, const char *name,
                                            const uint32_t *cells, size_t n, coons_error *err)
{
    return add_set(vm, COONS__VSET_CELL, name, cells, n, 1, err);
}

coons_status coons_volume_mesh_add_face_set(coons_volume_mesh *vm, const char *name,
                                            const uint32_t *pairs, size_t n, coons_error *err)
{
    return add_set(vm, COONS__VSET_FACE, name, pairs, n, 2, err);
}

size_t coons_volume_mesh_field_count(const coons_volume_mesh *vm, coons_field_location location)
{
    return location == COONS_FIELD_NODE || location == COONS_FIELD_CELL
               ? vm->fields[location].count
               : 0;
}
size_t coons_volume_mesh_node_set_count(const coons_volume_mesh *vm)
{
    return vm->sets[COONS__VSET_NODE].count;
}
size_t coons_volume_mesh_cell_set_count(const coons_volume_mesh *vm)
{
    return vm->sets[COONS__VSET_CELL].count;
}
size_t coons_volume_mesh_face_set_count(const coons_volume_mesh *vm)
{
    return vm->sets[COONS__VSET_FACE].count;
}

const char *coons_volume_mesh_field(const coons_volume_mesh *vm, coons_field_location location,
                                    size_t i, coons_field_type *type, const void **values)
{
    const coons__vfield *f = i < coons_volume_mesh_field_count(vm, location)
                                 ? (const coons__vfield *)vm->fields[location].items + i
                                 : NULL;
    if (type) *type = f ? f->type : COONS_FIELD_FLOAT64;
    if (values) *values = f ? f->values : NULL;
    return f ? f->name : NULL;
}

static const char *get_set(const coons_volume_mesh *vm, int kind, size_t i,
                           const uint32_t **items, size_t *count)
{
    const coons__vset *s =
        i < vm->sets[kind].count ? (const coons__vset *)vm->sets[kind].items + i : NULL;
    if (items) *items = s ? s->items : NULL;
    if (count) *count = s ? s->count : 0;
    return s ? s->name : NULL;
}

const char *coons_volume_mesh_node_set(const coons_volume_mesh *vm, size_t i,
                                       const uint32_t **items, size_t *count)
{
    return get_set(vm, COONS__VSET_NODE, i, items, count);
}
const char *coons_volume_mesh_cell_set(const coons_volume_mesh *vm, size_t i,
                                       const uint32_t **items, size_t *count)
{
    return get_set(vm, COONS__VSET_CELL, i, items, count);
}
const char *coons_volume_mesh_face_set(const coons_volume_mesh *vm, size_t i,
                                       const uint32_t **pairs, size_t *count)
{
    return get_set(vm, COONS__VSET_FACE, i, pairs, count);
}
