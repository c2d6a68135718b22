/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/mesh_read.h
 * @brief Reading triangle meshes: STL (binary and ASCII) and OFF.
 *
 * coons_mesh_read_file() and coons_mesh_read_memory() tell the formats
 * apart by content and check every count against the input size before
 * allocating (::coons_mesh_read_options).
 */
#ifndef COONS_MESH_READ_H
#define COONS_MESH_READ_H

#include "coons/types.h"
#include "coons/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Default largest mesh file coons_mesh_read_file() reads (1 GiB). */
#define COONS_MESH_READ_MAX_BYTES ((size_t)1 << 30)

/** Version of ::coons_mesh_read_options this header describes. */
#define COONS_MESH_READ_OPTIONS_VERSION 1

/** Limits of the mesh reader; NULL instead of options means the defaults. */
typedef struct coons_mesh_read_options {
    /** ::COONS_MESH_READ_OPTIONS_VERSION. */
    unsigned int version;
    /** Largest file, in bytes; 0: ::COONS_MESH_READ_MAX_BYTES. */
    size_t max_bytes;
    /** Largest number of triangles; 0: ::COONS_MESH_MAX_TRIANGLES. */
    size_t max_triangles;
} coons_mesh_read_options;

#ifndef __cplusplus
#define COONS_MESH_READ_OPTIONS_INIT {.version = COONS_MESH_READ_OPTIONS_VERSION}
#else
#define COONS_MESH_READ_OPTIONS_INIT COONS_RECORD_INIT_CXX_(coons_mesh_read_options, r_.version = COONS_MESH_READ_OPTIONS_VERSION)
#endif

/**
 * Reads a triangle mesh: binary STL (exactly 84 + 50 * count bytes), ASCII
 * STL (`solid` ... `endsolid`, several solids allowed) or OFF (`OFF`, the
 * counts, vertices, polygons fanned into triangles; `#` comments), told
 * apart by their content. STL vertices are welded by exact coordinate
 * equality (so a closed STL gives a closed indexed mesh); triangles whose
 * corners coincide are dropped. One part, named after the file (without
 * directory and extension).
 *
 * Errors name the file and, for binary STL, the byte offset
 * (`FILE: byte N: ...`), for text the line and column (`FILE:LINE:COL:
 * ...`; also in err->file, err->line, err->column): a truncated file, a
 * triangle count that disagrees with the file size, a non-finite
 * coordinate, a token that is not what the format needs there, a face
 * index out of range. Limits are checked before anything is allocated
 * from a count (every count is first checked against the file size).
 * @return ::COONS_OK; ::COONS_E_IO (cannot open or read); ::COONS_E_PARSE
 *         (malformed); ::COONS_E_LIMIT (more than `max_bytes` or
 *         `max_triangles`; the message says which); ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_mesh_read_file(const char *path,
                                               const coons_mesh_read_options *opts,
                                               coons_mesh **out, coons_error *err);

/**
 * coons_mesh_read_file() of `size` bytes at `data`; `name` (NULL:
 * "<memory>") names the input in messages and the part.
 * @return ::COONS_OK; ::COONS_E_INVALID (`data` NULL with size > 0);
 *         ::COONS_E_PARSE (malformed); ::COONS_E_LIMIT (more than
 *         `max_bytes` or `max_triangles`); ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_mesh_read_memory(const void *data, size_t size, const char *name,
                                                 const coons_mesh_read_options *opts,
                                                 coons_mesh **out, coons_error *err);

#ifdef __cplusplus
}
#endif
#endif
