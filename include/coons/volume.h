/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/volume.h
 * @brief Volume meshes: hexahedral cells of 8, 20 or 27 nodes with per-node
 *        and per-cell fields, named node, cell and face sets, and parts.
 *
 * A ::coons_volume_mesh is the interior counterpart of the triangle mesh
 * ::coons_mesh (coons/mesh.h): it is what the volume-mesh formats are
 * written from (coons_volume_mesh_write(), coons/io.h). It holds
 *
 * - nodes: double x, y, z, addressed by uint32_t index (0-based);
 * - cells: hexahedra, all of one element kind (::coons_element), each a
 *   row of coons_volume_mesh_nodes_per_cell() node indices, and each
 *   belonging to one part (a body, say), addressed by uint32_t index;
 * - fields: named scalar arrays of ::COONS_FIELD_FLOAT64 or
 *   ::COONS_FIELD_INT32 values, one value per node or one per cell (for
 *   example `u`, `v`, `w`, `det_j` per node and `body`, `scaled_jacobian`
 *   per cell);
 * - named node sets, cell sets and face sets; a face is a (cell, local
 *   face) pair.
 *
 * **One element kind per mesh.** Every target format writes a homogeneous
 * block of one element type at a time (Abaqus/CalculiX's `*ELEMENT,
 * TYPE=`, a Gmsh element type, a VTK cell type), a lattice mesher produces
 * one kind, and a fixed stride keeps the cell array flat (no offsets) and
 * the writers simple. A collapsed cell (an apex) is a hexahedron whose
 * corners repeat a node, not another element kind; the writers make
 * wedges and pyramids of them, and coons_volume_mesh_cell_shape() tells
 * which.
 *
 * **Node order within a cell** is Gmsh's (Gmsh reference manual, "Node
 * ordering"), in the cell's own parameters (r, s, t) in [0,1]^3, which for
 * a lattice mesh of a body are the directions of u, v and w:
 *
 *     corners  0 (0,0,0)  1 (1,0,0)  2 (1,1,0)  3 (0,1,0)
 *              4 (0,0,1)  5 (1,0,1)  6 (1,1,1)  7 (0,1,1)
 *     edges    8 (0-1)   9 (0-3)  10 (0-4)  11 (1-2)  12 (1-5)  13 (2-3)
 *             14 (2-6)  15 (3-7)  16 (4-5)  17 (4-7)  18 (5-6)  19 (6-7)
 *     faces   20 t=0 (0,1,2,3)  21 s=0 (0,1,5,4)  22 r=0 (0,3,7,4)
 *             23 r=1 (1,2,6,5)  24 s=1 (2,3,7,6)  25 t=1 (4,5,6,7)
 *     centre  26
 *
 * ::COONS_ELEMENT_HEX8 has nodes 0-7, ::COONS_ELEMENT_HEX20 (serendipity)
 * 0-19, ::COONS_ELEMENT_HEX27 (triquadratic) 0-26. The corner order is the
 * one shared by Gmsh, VTK and Abaqus/CalculiX; edge and face nodes differ
 * between them, and each writer permutes to its format's own order. A
 * valid (positively oriented) cell has corners 1, 3, 4 on the positive r, s
 * and t sides of corner 0: det[x1-x0, x3-x0, x4-x0] > 0 for a parallelepiped.
 *
 * **Local faces** (in face sets), numbered as the body faces
 * (coons_body_face_name(): u0 u1 v0 v1 w0 w1); corners listed
 * counter-clockwise seen from outside the cell:
 *
 *     0 r=0 (0,4,7,3)   1 r=1 (1,2,6,5)   2 s=0 (0,1,5,4)
 *     3 s=1 (3,7,6,2)   4 t=0 (0,3,2,1)   5 t=1 (4,5,6,7)
 *
 * Invariants, checked when data is added: node coordinates and Float64
 * field values are finite, every index refers to an existing node, cell,
 * part or local face, at most 2^32 - 1 nodes, cells and parts, names are
 * unique within their kind. Fields must be added after the nodes (node
 * fields) or cells (cell fields) they describe: once a node field exists,
 * no node can be added, and likewise for cells.
 *
 * Ownership and threads as everywhere (libcoons(3)): the mesh belongs to
 * the caller (coons_volume_mesh_free()); every input is copied; pointers
 * returned by accessors are borrowed views, valid until the mesh is next
 * modified or freed. Concurrent reads are safe; modifying calls need
 * exclusive access.
 */
#ifndef COONS_VOLUME_H
#define COONS_VOLUME_H

#include "coons/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Opaque volume mesh handle. */
typedef struct coons_volume_mesh coons_volume_mesh;

/** Cell kinds; each value is the number of nodes of the cell. */
typedef enum coons_element {
    COONS_ELEMENT_HEX8 = 8,  /**< trilinear hexahedron (corners) */
    COONS_ELEMENT_HEX20 = 20, /**< serendipity hexahedron (corners, edges) */
    COONS_ELEMENT_HEX27 = 27  /**< triquadratic hexahedron (corners, edges, faces, centre) */
} coons_element;

/** Where a field lives. */
typedef enum coons_field_location {
    COONS_FIELD_NODE = 0, /**< one value per node */
    COONS_FIELD_CELL = 1  /**< one value per cell */
} coons_field_location;

/** Value type of a field. */
typedef enum coons_field_type {
    COONS_FIELD_FLOAT64 = 0, /**< `double`, finite */
    COONS_FIELD_INT32 = 1    /**< `int32_t` */
} coons_field_type;

/** Longest field, set or part name, in bytes, without the NUL. */
#define COONS_VOLUME_NAME_MAX 255

/**
 * Creates an empty volume mesh whose cells will all be of kind `element`.
 * @param[in]  element ::COONS_ELEMENT_HEX8, ::COONS_ELEMENT_HEX20 or
 *                     ::COONS_ELEMENT_HEX27
 * @param[out] out     the new mesh (NULL on error)
 * @param[in,out] err  may be NULL
 * @return ::COONS_OK, ::COONS_E_INVALID (another element value, `out` NULL),
 *         ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_volume_mesh_new(coons_element element, coons_volume_mesh **out,
                                                coons_error *err);

/** Releases a volume mesh; NULL is a harmless no-op. */
COONS_EXPORT void coons_volume_mesh_free(coons_volume_mesh *vm);

/**
 * Appends `n` nodes (x, y, z packed: 3n doubles).
 * @param[in,out] vm   the mesh
 * @param[in]  xyz     3n finite coordinates (may be NULL when n is 0)
 * @param[in]  n       number of nodes
 * @param[out] first   if not NULL, the index of the first new node
 * @param[in,out] err  may be NULL
 * @return ::COONS_OK; ::COONS_E_INVALID: a coordinate is not finite (the
 *         message names the node), `xyz` is NULL with n > 0, or a node
 *         field already exists; ::COONS_E_LIMIT: the mesh would have more
 *         than 2^32 - 1 nodes; ::COONS_E_NOMEM. On error nothing is added.
 */
COONS_EXPORT coons_status coons_volume_mesh_add_nodes(coons_volume_mesh *vm, const double *xyz,
                                                      size_t n, size_t *first, coons_error *err);

/**
 * Appends a part (a body, a material region): cells name it by index.
 * @param[in] name     copied; NULL: "part<i>". Not empty, no control
 *                     characters, at most ::COONS_VOLUME_NAME_MAX bytes,
 *                     not the name of another part.
 * @param[out] index   if not NULL, the part's index
 * @return ::COONS_OK, ::COONS_E_INVALID (bad or repeated name),
 *         ::COONS_E_LIMIT (2^32 - 1 parts), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_volume_mesh_add_part(coons_volume_mesh *vm, const char *name,
                                                     size_t *index, coons_error *err);

/**
 * Appends `n` cells of the mesh's element kind, all in part `part`.
 * @param[in] nodes    n * coons_volume_mesh_nodes_per_cell() node indices,
 *                     row by row, each row in the node order described
 *                     above; every index < coons_volume_mesh_node_count()
 * @param[in] n        number of cells
 * @param[in] part     index of an existing part
 * @param[out] first   if not NULL, the index of the first new cell
 * @return ::COONS_OK; ::COONS_E_INVALID: a node index out of range (the
 *         message names the cell and the node), no such part, `nodes` NULL
 *         with n > 0, or a cell field already exists; ::COONS_E_LIMIT: more
 *         than 2^32 - 1 cells; ::COONS_E_NOMEM. On error nothing is added.
 *         Repeated nodes within a cell (a collapsed cell) are allowed.
 */
COONS_EXPORT coons_status coons_volume_mesh_add_cells(coons_volume_mesh *vm,
                                                      const uint32_t *nodes, size_t n,
                                                      size_t part, size_t *first,
                                                      coons_error *err);

/**
 * Adds a named scalar field with one value per node (::COONS_FIELD_NODE,
 * coons_volume_mesh_node_count() values) or per cell (::COONS_FIELD_CELL,
 * coons_volume_mesh_cell_count() values), copied.
 * @param[in] location ::COONS_FIELD_NODE or ::COONS_FIELD_CELL
 * @param[in] name     an identifier: `[A-Za-z_][A-Za-z0-9_]*`, at most
 *                     ::COONS_VOLUME_NAME_MAX bytes, not the name of
 *                     another field at the same location
 * @param[in] type     ::COONS_FIELD_FLOAT64 (`values` points to doubles,
 *                     all finite) or ::COONS_FIELD_INT32 (to int32_t)
 * @param[in] values   the values (may be NULL when there are none)
 * @return ::COONS_OK; ::COONS_E_INVALID: bad location, type or name, a
 *         repeated name, a non-finite value (the message names the field and
 *         the index), `values` NULL; ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_volume_mesh_add_field(coons_volume_mesh *vm,
                                                      coons_field_location location,
                                                      const char *name, coons_field_type type,
                                                      const void *values, coons_error *err);

/**
 * Adds a named set of `n` node indices (kept in the given order; repeats
 * are kept too). Set names follow the rules of part names and are unique
 * among node sets.
 * @return ::COONS_OK; ::COONS_E_INVALID: bad or repeated name, an index
 *         out of range, `nodes` NULL with n > 0; ::COONS_E_LIMIT (a set
 *         too large to hold); ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_volume_mesh_add_node_set(coons_volume_mesh *vm,
                                                         const char *name,
                                                         const uint32_t *nodes, size_t n,
                                                         coons_error *err);

/**
 * Adds a named set of `n` cell indices; as coons_volume_mesh_add_node_set().
 * @return ::COONS_OK; ::COONS_E_INVALID: bad or repeated name (among cell
 *         sets), an index out of range, `cells` NULL with n > 0;
 *         ::COONS_E_LIMIT (a set too large to hold); ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_volume_mesh_add_cell_set(coons_volume_mesh *vm,
                                                         const char *name,
                                                         const uint32_t *cells, size_t n,
                                                         coons_error *err);

/**
 * Adds a named set of `n` cell faces: `pairs` holds 2n values, for each
 * face the cell index and the local face 0..5 (numbered as above).
 * @return ::COONS_OK; ::COONS_E_INVALID: bad or repeated name, a cell
 *         index out of range, a local face above 5, `pairs` NULL with
 *         n > 0; ::COONS_E_LIMIT: 2n overflows; ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_volume_mesh_add_face_set(coons_volume_mesh *vm,
                                                         const char *name,
                                                         const uint32_t *pairs, size_t n,
                                                         coons_error *err);

/** The element kind given to coons_volume_mesh_new(). */
COONS_EXPORT coons_element coons_volume_mesh_element(const coons_volume_mesh *vm);
/** Nodes per cell: 8, 20 or 27. */
COONS_EXPORT size_t coons_volume_mesh_nodes_per_cell(const coons_volume_mesh *vm);
COONS_EXPORT size_t coons_volume_mesh_node_count(const coons_volume_mesh *vm);
COONS_EXPORT size_t coons_volume_mesh_cell_count(const coons_volume_mesh *vm);
COONS_EXPORT size_t coons_volume_mesh_part_count(const coons_volume_mesh *vm);
/** Number of fields at `location` (0 for an unknown location). */
COONS_EXPORT size_t coons_volume_mesh_field_count(const coons_volume_mesh *vm,
                                                  coons_field_location location);
COONS_EXPORT size_t coons_volume_mesh_node_set_count(const coons_volume_mesh *vm);
COONS_EXPORT size_t coons_volume_mesh_cell_set_count(const coons_volume_mesh *vm);
COONS_EXPORT size_t coons_volume_mesh_face_set_count(const coons_volume_mesh *vm);

/** Borrowed view: 3 doubles per node (NULL when there are no nodes). */
COONS_EXPORT const double *coons_volume_mesh_nodes(const coons_volume_mesh *vm);

/**
 * Multiplies every node by `factor` (a change of units); cells, parts,
 * sets and fields stay (a field keeps the units it was computed in).
 * @return ::COONS_OK; ::COONS_E_INVALID (no mesh, or `factor` not a finite
 *         number > 0); ::COONS_E_LIMIT when a coordinate would overflow
 *         (the mesh is then unchanged).
 */
COONS_EXPORT coons_status coons_volume_mesh_scale(coons_volume_mesh *vm, double factor,
                                                  coons_error *err);
/** Borrowed view: coons_volume_mesh_nodes_per_cell() node indices per cell. */
COONS_EXPORT const uint32_t *coons_volume_mesh_cells(const coons_volume_mesh *vm);
/** Borrowed view: the part index of each cell. */
COONS_EXPORT const uint32_t *coons_volume_mesh_cell_parts(const coons_volume_mesh *vm);
/** What a cell is where its body collapses: coons_volume_mesh_cell_shape(). */
typedef enum coons_cell_shape {
    /** A hexahedron: 8 distinct corners, or repeated corners that make no
     *  wedge or pyramid; every ::COONS_ELEMENT_HEX20 and HEX27 cell. */
    COONS_CELL_HEXAHEDRON = 0,
    /** Two parallel edges of one face collapsed (6 distinct corners). */
    COONS_CELL_WEDGE = 1,
    /** One face collapsed to a node (5 distinct corners). */
    COONS_CELL_PYRAMID = 2
} coons_cell_shape;

/** Most nodes coons_volume_mesh_cell_shape() writes: 27. */
#define COONS_VOLUME_CELL_NODES_MAX 27

/**
 * What cell i is, as the writers write it (Gmsh, VTK, CalculiX): a
 * ::COONS_ELEMENT_HEX8 cell whose corners repeat nodes at a collapsed edge
 * is a wedge, at a face collapsed to a node a pyramid; any other cell is a
 * hexahedron (with its repeated nodes, if any). The rule is combinatorial
 * (which corner nodes coincide) and uses the cell's right-handed reference
 * frame, so valid cells give positively oriented shapes.
 * @param[out] shape  the shape
 * @param[out] nodes  COONS_VOLUME_CELL_NODES_MAX entries; receives
 *                    `*count` node indices in Gmsh's order (Gmsh reference
 *                    manual, "Node ordering"): a hexahedron as
 *                    coons_volume_mesh_cells() (8, 20 or 27 nodes); a wedge
 *                    6 nodes, triangle 0 1 2 counter-clockwise seen from
 *                    triangle 3 4 5, node k + 3 across from node k; a
 *                    pyramid 5 nodes, the base 0 1 2 3 counter-clockwise
 *                    seen from the apex 4 (also VTK's pyramid order; VTK's
 *                    wedge is Gmsh's 0 2 1 3 5 4)
 * @param[out] count  number of nodes written: 8, 20 or 27, 6, 5
 * @return ::COONS_OK; ::COONS_E_INVALID: no mesh, no cell i (the message
 *         gives the cell count), or `shape`, `nodes` or `count` NULL
 *         (outputs untouched).
 */
COONS_EXPORT coons_status coons_volume_mesh_cell_shape(const coons_volume_mesh *vm, size_t i,
                                                       coons_cell_shape *shape, uint32_t *nodes,
                                                       size_t *count, coons_error *err);
/** Name of part i (borrowed), or NULL when i is out of range. */
COONS_EXPORT const char *coons_volume_mesh_part_name(const coons_volume_mesh *vm, size_t i);

/**
 * Field i at `location`: returns its name (borrowed) and sets `*type` and
 * `*values` (a borrowed view of node or cell count values, `double` or
 * `int32_t` by type); either out pointer may be NULL. Out of range: returns
 * NULL and sets the outputs to ::COONS_FIELD_FLOAT64 and NULL.
 */
COONS_EXPORT const char *coons_volume_mesh_field(const coons_volume_mesh *vm,
                                                 coons_field_location location, size_t i,
                                                 coons_field_type *type, const void **values);

/**
 * Node set i: returns its name (borrowed) and sets `*items` (borrowed node
 * indices) and `*count`; either out pointer may be NULL. Out of range:
 * NULL, and NULL and 0.
 */
COONS_EXPORT const char *coons_volume_mesh_node_set(const coons_volume_mesh *vm, size_t i,
                                                    const uint32_t **items, size_t *count);
/** Cell set i, as coons_volume_mesh_node_set(). */
COONS_EXPORT const char *coons_volume_mesh_cell_set(const coons_volume_mesh *vm, size_t i,
                                                    const uint32_t **items, size_t *count);
/** Face set i: `*pairs` holds 2 * `*count` values (cell, local face). */
COONS_EXPORT const char *coons_volume_mesh_face_set(const coons_volume_mesh *vm, size_t i,
                                                    const uint32_t **pairs, size_t *count);

/* ------------------------------------------------------------------------ */
/* Meshing bodies into hexahedra on their (u,v,w) lattice                   */
/* ------------------------------------------------------------------------ */

/** Default largest number of cells of coons_body_volume_mesh() and
 *  coons_model_volume_mesh(): 2^22 (4,194,304). */
#define COONS_VOLUME_MAX_CELLS ((size_t)1 << 22)

/** Version of ::coons_volume_options this header describes. Version 2:
 *  `progress` and `userdata`; version 3: `threads`. Records of versions 1
 *  and 2 are still accepted (as one thread). */
#define COONS_VOLUME_OPTIONS_VERSION 3

/**
 * How bodies are meshed. Initialise with ::COONS_VOLUME_OPTIONS_INIT;
 * passing NULL means all defaults.
 */
typedef struct coons_volume_options {
    /** ::COONS_VOLUME_OPTIONS_VERSION. */
    unsigned int version;
    /** ::COONS_ELEMENT_HEX8 (also 0, the default), HEX20 or HEX27. */
    coons_element element;
    /**
     * Intervals of the lattice along u, v, w. All 0: the lattice the
     * boundary sampler picks for `tolerance` (coons_body_sample()), so the
     * volume mesh's boundary is the boundary mesh's lattice. Otherwise each
     * must be >= 1 (a uniform lattice).
     */
    unsigned int resolution[3];
    /** Tolerance of the sampled lattice, model units; <= 0: the model's
     *  tolerance (coons_model_volume_mesh()) or 1/1000 of the body's control
     *  box diagonal (coons_body_volume_mesh()). */
    double tolerance;
    /** Largest number of cells; 0: ::COONS_VOLUME_MAX_CELLS. */
    size_t max_cells;
    /** (version 2) Progress: the stage "lattice" before each body's lattice
     *  is chosen (i / count, then 1), "evaluate" as the bodies' nodes are
     *  evaluated (the share of nodes done), "cells" as the cells are made
     *  (the share of cells). NULL: no reports. */
    coons_progress_fn progress;
    /** (version 2) Passed to `progress`. */
    void *userdata;
    /** (version 3) Threads that sample, evaluate and measure the bodies
     *  and make the cells: 0 or 1, the calling thread only (the default);
     *  N > 1, N threads (at most 1024). The mesh does not depend on
     *  it, byte for byte. Progress is reported from the calling thread; an
     *  allocator set with coons_set_allocator() must be thread-safe. */
    unsigned int threads;
} coons_volume_options;

#ifndef __cplusplus
#define COONS_VOLUME_OPTIONS_INIT {.version = COONS_VOLUME_OPTIONS_VERSION, .element = COONS_ELEMENT_HEX8}
#else
#define COONS_VOLUME_OPTIONS_INIT COONS_RECORD_INIT_CXX_(coons_volume_options, r_.version = COONS_VOLUME_OPTIONS_VERSION, r_.element = COONS_ELEMENT_HEX8)
#endif

/** Sets `*o` to ::COONS_VOLUME_OPTIONS_INIT; NULL is a harmless no-op. */
COONS_EXPORT void coons_volume_options_init(coons_volume_options *o);

/**
 * Meshes one body into hexahedra on a lattice of (u,v,w), as one part
 * named `name` (NULL: "body0").
 *
 * Nodes: lattice points; for ::COONS_ELEMENT_HEX20 also the midpoints of
 * the lattice edges, for ::COONS_ELEMENT_HEX27 also of the lattice faces and
 * cells, all in parameter space. Every node is the body's exact point at its
 * parameters (isoparametric). Lattice nodes that evaluate to the same point
 * (a collapsed edge or face: an apex, a tip) are one node, so cells there
 * repeat nodes (see the node order above).
 *
 * A left-handed body (det J < 0) has each cell's node order mirrored
 * (r -> 1 - r), so that every valid cell is positively oriented; the
 * node field `det_j` keeps the sign of the body's map.
 *
 * Fields: node `u`, `v`, `w`, `det_j` (Float64), cell `body` (Int32, 0
 * here) and `scaled_jacobian` (Float64, see coons_volume_mesh_quality()).
 * Sets: the cell set `name`, and for each of the six faces F (u0 ... w1,
 * coons_body_face_name()) a node set and a face set `name.F` (a face that
 * collapses to a curve or a point has empty sets).
 *
 * Inverted cells are kept: check coons_volume_mesh_quality().
 *
 * @return ::COONS_OK; ::COONS_E_INVALID (bad options, a point not finite);
 *         ::COONS_E_LIMIT (more cells than `max_cells`, said before any
 *         work); ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_volume_mesh(const coons_body *b,
                                                 const coons_volume_options *opts,
                                                 const char *name, coons_volume_mesh **out,
                                                 coons_error *err);

/**
 * Meshes every body of a model into one conformal mesh, one part per body
 * in body order (named coons_model_body_name(); cell field `body` is the
 * body index). Bodies that share a face (the same map up to one of the 8
 * symmetries of the unit square, within 1e-9 of the box diagonal, found by
 * geometry) share its nodes: the directions shared faces connect get one
 * lattice, the union of the bodies' lattices (each still meets its
 * tolerance); the face sets of both sides remain.
 * Bodies that meet only along a whole edge (the same curve in either
 * sense) or at a corner, as diagonal cells of a control lattice do, share
 * those nodes too: a shared edge ties its direction in both bodies.
 * Bodies that overlap or touch otherwise (their shared nodes are not whole
 * faces, whole edges or corners of both, or cells of both meet without
 * sharing nodes) cannot be meshed conformally: ::COONS_E_UNSUPPORTED
 * naming both bodies.
 * Each part's cells are grouped by what the writers make of them
 * (hexahedra, then wedges, then pyramids, each group in lattice order), so
 * that a reader sees at most three blocks per part; face sets list
 * quadrangles, then triangles.
 * @return as coons_body_volume_mesh(), plus ::COONS_E_UNSUPPORTED.
 */
COONS_EXPORT coons_status coons_model_volume_mesh(const coons_model *m,
                                                  const coons_volume_options *opts,
                                                  coons_volume_mesh **out, coons_error *err);

/** Version of ::coons_volume_quality this header describes. */
#define COONS_VOLUME_QUALITY_VERSION 1

/**
 * Cell quality of one part. The scaled Jacobian (Knupp) of a cell is,
 * over its 8 corners, the minimum of det[e1, e2, e3] of the unit vectors
 * along the three cell edges from that corner (in the r, s, t directions
 * of the node order, so > 0 for a valid cell, 1 for a cube). A corner with
 * an edge of zero length (repeated node: a collapsed cell) has no value and
 * is skipped; a cell with no corner left has value 0. A cell is inverted
 * when its value is <= 0 and it is not collapsed; a collapsed cell (one
 * repeated corner node at least) is counted in `collapsed`, never as
 * inverted.
 */
typedef struct coons_volume_quality {
    unsigned int version;        /**< ::COONS_VOLUME_QUALITY_VERSION */
    size_t cells;                /**< cells of the part */
    size_t nodes;                /**< distinct nodes those cells use */
    coons_element element;
    double min_scaled_jacobian;  /**< NaN when there are no cells */
    double mean_scaled_jacobian; /**< NaN when there are no cells */
    size_t inverted;             /**< value <= 0, not collapsed */
    size_t below_0_2;            /**< value < 0.2 (inverted ones included) */
    size_t collapsed;            /**< cells with a repeated corner node */
    size_t worst_cell;           /**< index (in the mesh) of the minimum */
    /** Parameters of the worst cell's centre: the mean of node fields
     *  `u`, `v`, `w` over its corners (NaN without those fields). */
    double worst_uvw[3];
} coons_volume_quality;

#ifndef __cplusplus
#define COONS_VOLUME_QUALITY_INIT {.version = COONS_VOLUME_QUALITY_VERSION, .element = COONS_ELEMENT_HEX8}
#else
#define COONS_VOLUME_QUALITY_INIT COONS_RECORD_INIT_CXX_(coons_volume_quality, r_.version = COONS_VOLUME_QUALITY_VERSION, r_.element = COONS_ELEMENT_HEX8)
#endif

/** Sets `*q` to ::COONS_VOLUME_QUALITY_INIT; NULL is a harmless no-op. */
COONS_EXPORT void coons_volume_quality_init(coons_volume_quality *q);

/**
 * Computes the quality of part `part` from the node coordinates (the
 * linear hexahedron of each cell's corners).
 * @param[in,out] q  initialised with ::COONS_VOLUME_QUALITY_INIT
 * @return ::COONS_OK; ::COONS_E_INVALID (no such part, `q` not
 *         initialised).
 */
COONS_EXPORT coons_status coons_volume_mesh_quality(const coons_volume_mesh *vm, size_t part,
                                                    coons_volume_quality *q, coons_error *err);

/**
 * The scaled Jacobian of cell `cell` as defined for ::coons_volume_quality
 * (NaN when the cell does not exist); `*collapsed` (may be NULL) is set to
 * 1 when the cell repeats a corner node.
 */
COONS_EXPORT double coons_volume_mesh_cell_scaled_jacobian(const coons_volume_mesh *vm,
                                                           size_t cell, int *collapsed);

#ifdef __cplusplus
}
#endif
#endif
