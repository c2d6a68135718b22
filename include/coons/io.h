/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/io.h
 * @brief Writing meshes: binary and ASCII STL, OFF and OpenSCAD source
 *        (triangle meshes), legacy VTK and Gmsh MSH (volume meshes).
 *
 * Each format holds one kind of mesh (coons_format_kind()): the surface
 * formats a ::coons_mesh (coons/mesh.h), written by coons_mesh_write(), the
 * volume formats a ::coons_volume_mesh (coons/volume.h), written by
 * coons_volume_mesh_write(). Both write through the same atomic file
 * protocol described at coons_mesh_write(). All writers are
 * deterministic: the same mesh and options always give byte-identical
 * output, whatever the locale of the process (the library never calls
 * setlocale()).
 *
 * Formats and the precision they carry:
 * - ::COONS_FORMAT_STL_BINARY: the default for `.stl`. 80-byte header that
 *   never starts with "solid" (it carries the header text and the units),
 *   a little-endian uint32 triangle count, then per triangle the unit facet
 *   normal and the three vertices as little-endian IEEE float32 and a zero
 *   attribute word. Vertices are rounded to float32 by the format, and the
 *   normal is that of the rounded (stored) vertices, so that it agrees with
 *   the facet a reader sees (0 0 0 where rounding makes the facet
 *   degenerate); a mesh of
 *   2^32 or more triangles, or with a coordinate beyond the float32 range,
 *   is refused (::COONS_E_LIMIT).
 * - ::COONS_FORMAT_STL_ASCII: `solid NAME` ... `endsolid NAME`. The numbers
 *   are the same float32 values the binary writer stores, each printed as
 *   the shortest text that reads back (strtof) to exactly that float.
 * - ::COONS_FORMAT_OFF: `OFF`, `#` comment lines (writer, units, parts), the
 *   counts, the vertices in full double precision, then `3 a b c` faces.
 * - ::COONS_FORMAT_SCAD: OpenSCAD source. One module per mesh part, named
 *   MODEL_PART (the model's name, then the part's), holding a
 *   `polyhedron(points=..., faces=...)`; one
 *   module for the whole model calling every part module; and a top-level
 *   call of that module. `use <file.scad>` therefore imports the modules
 *   and `include <file.scad>` also renders the model. Vertices carry full
 *   double precision.
 * - ::COONS_FORMAT_VTK (volume): legacy VTK, ASCII, `# vtk DataFile Version
 *   3.0`, `DATASET UNSTRUCTURED_GRID` (VTK file formats, "Simple Legacy
 *   Formats"): the header text (and units) as title, `POINTS` in double,
 *   `CELLS` and `CELL_TYPES` 12 (VTK_HEXAHEDRON), 25
 *   (VTK_QUADRATIC_HEXAHEDRON) or 29 (VTK_TRIQUADRATIC_HEXAHEDRON), with
 *   each cell's nodes permuted from the mesh's Gmsh order to VTK's (corners
 *   alike; VTK's edges are 0-1 1-2 3-2 0-3 4-5 5-6 7-6 4-7 0-4 1-5 2-6 3-7,
 *   its face nodes r=0 r=1 s=0 s=1 t=0 t=1, then the centre), then
 *   `POINT_DATA` and `CELL_DATA` with every field as `SCALARS NAME double`
 *   or `int`, in the order they were added. Parts and sets are not written:
 *   the legacy format has no place for them.
 * - ::COONS_FORMAT_MSH2 (what `.msh` means) and ::COONS_FORMAT_MSH4
 *   (volume): Gmsh MSH 2.2 and 4.1 ASCII (Gmsh reference manual, "MSH file
 *   format"). Node n is node n + 1, cell c element c + 1, as a Gmsh
 *   hexahedron (type 5, 17, 12 for hex8, hex20, hex27) in Gmsh's order, the
 *   mesh's own; a hex8 cell at a collapsed edge becomes a prism (6), one at
 *   a face collapsed to a point a pyramid (7); other collapsed cells stay
 *   degenerate hexahedra. Part i is physical volume i + 1, named after it.
 *   Each face set with faces is a physical surface (tags after the parts')
 *   of its faces as quadrangles (3, 16, 10), counter-clockwise seen from
 *   outside the cell, triangles (2, 9) where one edge collapsed, nothing
 *   where a face collapsed to a line or point; sets holding the same faces
 *   node for node (a face two bodies share) are one surface named
 *   `A+B` (set order) with the first set's faces. Node fields are
 *   `$NodeData`; cell fields `$ElementData` in 4.1 only, over every element
 *   (a face has its cell's values), since meshio 5.0 cannot read them in
 *   2.2. 4.1 adds `$Entities` (a volume per part, a surface
 *   per physical surface) and lists each node once, in the block of the
 *   part of the first cell using it. No header text or units. A physical
 *   name longer than 252 bytes (Gmsh 4.8 reads no more) is refused with
 *   ::COONS_E_LIMIT before anything is written.
 * - ::COONS_FORMAT_VTU (volume, `.vtu`): VTK XML UnstructuredGrid, version
 *   1.0 (VTK file formats, "XML File Formats"), `header_type="UInt64"`,
 *   every DataArray appended in one `<AppendedData encoding="base64">`
 *   section as [UInt64 byte count][little-endian values], base64-encoded
 *   as one stream, offsets counted in encoded characters. Points Float64,
 *   connectivity and offsets Int64, types UInt8, then every field as
 *   Float64 or Int32 point or cell data, in order. Cell types and node
 *   orders as for ::COONS_FORMAT_VTK; in a hex8 mesh a cell with repeated
 *   corners is a VTK wedge (13: triangle 0 1 2 with its right-hand normal
 *   pointing away from 3 4 5) or pyramid (14: base counter-clockwise seen
 *   from the apex 4) where it collapses so, else a degenerate hexahedron.
 *   The header text and units are an XML comment. Parts and sets are not
 *   written. ::COONS_FORMAT_VTU_ASCII (no extension) is the same document
 *   with `format="ascii"` arrays of shortest round-trip numbers.
 * - ::COONS_FORMAT_INP (volume, `.inp`): Abaqus / CalculiX input deck of
 *   model data only (no material, no step): a `**` header comment,
 *   `*HEADING` (`model=NAME units=UNITS`), `*NODE, NSET=NALL` (ids from 1),
 *   `*ELEMENT, TYPE=C3D8` or `C3D20, ELSET=EALL` (element c + 1 is cell c;
 *   C3D20 nodes 9-12 on the edges 1-2 2-3 3-4 4-1, 13-16 on 5-6 6-7 7-8 8-5,
 *   17-20 on 1-5 2-6 3-7 4-8), hex8 cells with two collapsed parallel
 *   edges as `C3D6` wedges in their own block (pyramids and other
 *   collapsed cells stay C3D8 with repeated nodes: CalculiX has no
 *   pyramid), `*ELSET` per part and per cell set that does not repeat a
 *   part, `*NSET` per node set, and per face set element sets `SET_S1` ..
 *   `SET_S6` (the cells whose face in the set has that label: S1 = t0,
 *   S2 = t1, S3 = s0, S4 = r1, S5 = s1, S6 = r0) and
 *   `*SURFACE, NAME=SET_S, TYPE=ELEMENT` naming them with their labels.
 *   Names are upper-cased, every byte other than A-Z 0-9 _ becoming `_`;
 *   two that become one name of the same kind are refused
 *   (::COONS_E_INVALID, naming both), longer than 80 characters too
 *   (::COONS_E_UNSUPPORTED), as are hex27 meshes. At most 16 entries a
 *   line (a C3D20 element continues after its 15th node, the line ending
 *   with a comma); numbers are the shortest round-trip text when it fits
 *   the 20 characters CalculiX reads, else the most digits that fit.
 * - ::COONS_FORMAT_3MF (surface, `.3mf`): a 3MF package (3MF core
 *   specification 1.x) made with lib3mf: one mesh object of type "model"
 *   per part, named after it, one build item each, float32 coordinates
 *   (lib3mf 1.8 cuts them to 6 decimals), `unit` from the options' units
 *   ("um"/"micron", "mm", "cm", "in", "ft", "m" and their spelled-out
 *   names, any case; millimeter when none; any other: ::COONS_E_UNSUPPORTED),
 *   the name as "Title" metadata, UUIDs from the part index (deterministic).
 *   A part that is empty or not a closed surface running every edge once
 *   each way is refused (::COONS_E_UNSUPPORTED) before anything is
 *   created, as is every 3MF write of a library built without lib3mf.
 *
 * Numbers in OFF and SCAD are the shortest decimal text that strtod() reads
 * back to the identical double (-0 stays "-0"); non-finite values are
 * refused (::COONS_E_INVALID). Triangles are counter-clockwise seen from
 * outside in STL and OFF (the mesh's own order) and clockwise in
 * OpenSCAD's polyhedron(), as OpenSCAD expects: the SCAD writer reverses
 * each triangle.
 *
 * Part names become OpenSCAD identifiers: every byte outside
 * `[A-Za-z0-9_]` becomes `_`, a leading digit or an empty name gets a `_`
 * prefix, a name that is an OpenSCAD keyword or built-in module (`cube`,
 * `hull`, `for`, ...) gets a `_` suffix, and a name already taken gets
 * `_2`, `_3`, ... . The original names appear in comments. Every module
 * name carries the model's name (coons_write_options::name): the model's
 * module is that name made an identifier, a part's is MODEL_PART made an
 * identifier ("spool_union"); the model's module is named first, then the
 * parts' in order. Files written under different names can so be
 * `include`d into one design without one replacing the other's modules.
 */
#ifndef COONS_IO_H
#define COONS_IO_H

#include <stdio.h>

#include "coons/types.h"
#include "coons/volume.h"
#include "coons/mesh.h"
#include "coons/sample.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Output formats. */
typedef enum coons_format {
    COONS_FORMAT_AUTO = 0,       /**< chosen from the output path's extension */
    COONS_FORMAT_STL_BINARY = 1, /**< binary STL (what `.stl` means) */
    COONS_FORMAT_STL_ASCII = 2,  /**< ASCII STL */
    COONS_FORMAT_OFF = 3,        /**< Object File Format, text */
    COONS_FORMAT_SCAD = 4,       /**< OpenSCAD source */
    COONS_FORMAT_VTK = 5,        /**< legacy VTK unstructured grid, ASCII (volume) */
    COONS_FORMAT_MSH2 = 6,       /**< Gmsh MSH 2.2 ASCII (volume; what `.msh` means) */
    COONS_FORMAT_MSH4 = 7,       /**< Gmsh MSH 4.1 ASCII (volume) */
    COONS_FORMAT_VTU = 8,        /**< VTK XML UnstructuredGrid, version 1.0 (volume) */
    COONS_FORMAT_INP = 9,        /**< Abaqus / CalculiX input deck (volume) */
    COONS_FORMAT_VTU_ASCII = 10, /**< VTK XML UnstructuredGrid, ASCII data (volume) */
    COONS_FORMAT_3MF = 11,       /**< 3MF package, core specification 1.x (needs lib3mf) */
    COONS_FORMAT_STEP = 12,      /**< STEP AP214 exact solids (needs OCCT; coons/brep.h) */
    COONS_FORMAT_STEP_AP242 = 13, /**< STEP AP242 exact solids (needs OCCT) */
    COONS_FORMAT_IGES = 14,      /**< IGES 5.3 BRep solids (needs OCCT) */
    COONS_FORMAT_BREP = 15       /**< Open CASCADE BREP text (needs OCCT) */
} coons_format;

/** The kind of mesh a format holds (coons_format_kind()). */
typedef enum coons_mesh_kind {
    COONS_MESH_KIND_NONE = 0,    /**< not a format */
    COONS_MESH_KIND_SURFACE = 1, /**< a triangle mesh, ::coons_mesh */
    COONS_MESH_KIND_VOLUME = 2,  /**< a volume mesh, ::coons_volume_mesh */
    COONS_MESH_KIND_SOLID = 3    /**< exact solids of a model, coons_model_write_solid() */
} coons_mesh_kind;

/** Version of ::coons_write_options this header describes. Version 2:
 *  `written` and `written_ctx`; records of version 1 are still accepted
 *  (as without them). */
#define COONS_WRITE_OPTIONS_VERSION 2

/**
 * Options of the writers. Initialise with ::COONS_WRITE_OPTIONS_INIT and set
 * the fields you need; passing NULL instead of a pointer means all defaults.
 * Strings are borrowed for the duration of the call only.
 */
typedef struct coons_write_options {
    /** Must be ::COONS_WRITE_OPTIONS_VERSION. */
    unsigned int version;
    /** Model name: the ASCII STL `solid` name and the OpenSCAD module that
     *  renders the whole model (sanitised as described above).
     *  NULL or "": "coons_model". */
    const char *name;
    /** Units (e.g. "mm"), copied into formats that carry them: the binary
     *  STL header text ("units=mm") and an OFF/SCAD comment. NULL or "":
     *  no units are written. */
    const char *units;
    /** Text for the binary STL header and the first OFF/SCAD comment line.
     *  NULL: "libcoons VERSION". Control characters become spaces; a text
     *  starting with "solid" (in any case, after blanks) is prefixed so the
     *  header never starts with "solid"; it is cut to fit 80 bytes. */
    const char *header;
    /** A file that must not be overwritten, normally the input model. If
     *  the output names the same file (same device and inode, also through
     *  a link), the write is refused with ::COONS_E_INVALID before anything
     *  is created. NULL: no check. */
    const char *protect_path;
    /** Cancellation: polled before the output is created, after every
     *  buffer written (at most 1 MiB apart) and just before the final rename.
     *  A non-zero return stops the write: the temporary file is removed,
     *  the previous output is untouched and ::COONS_E_IO ("cancelled") is
     *  returned. It may read a `volatile sig_atomic_t` flag set by a signal
     *  handler, which is how coons2stl removes nothing but its own
     *  temporary file on SIGINT/SIGTERM. NULL: never cancelled. */
    int (*cancel)(void *ctx);
    /** Passed to `cancel`. */
    void *cancel_ctx;
    /** OpenSCAD: the indices of the parts that are context, not geometry
     *  (e.g. each body's boundary around its isoparametric surfaces, see
     *  coons_model_iso_surfaces()): the model's module calls them with the
     *  background modifier `%` (drawn transparent in the preview, left out
     *  of renders and exports). Other formats write them as ordinary
     *  parts. An index that is no part of the mesh is refused with
     *  ::COONS_E_INVALID before anything is created. NULL: none. */
    const size_t *background;
    /** Number of indices in `background`. */
    size_t nbackground;
    /** (version 2) Progress of the write: called from the calling thread
     *  after every buffer written (at most 1 MiB apart) and once at the end,
     *  with the number of bytes of the output written so far (a file's
     *  final size at the end). Keep it cheap; it must not call back into
     *  the library. NULL: no reports. */
    void (*written)(void *ctx, unsigned long long bytes);
    /** (version 2) Passed to `written`. */
    void *written_ctx;
} coons_write_options;

/** Default options. */
#ifndef __cplusplus
#define COONS_WRITE_OPTIONS_INIT {.version = COONS_WRITE_OPTIONS_VERSION}
#else
#define COONS_WRITE_OPTIONS_INIT COONS_RECORD_INIT_CXX_(coons_write_options, r_.version = COONS_WRITE_OPTIONS_VERSION)
#endif

/**
 * Sets `*o` to ::COONS_WRITE_OPTIONS_INIT (for language bindings that
 * cannot use the macro); NULL is a harmless no-op.
 */
COONS_EXPORT void coons_write_options_init(coons_write_options *o);

/**
 * Format implied by a path's extension, compared without regard to case:
 * `.stl` gives ::COONS_FORMAT_STL_BINARY, `.off` ::COONS_FORMAT_OFF,
 * `.scad` ::COONS_FORMAT_SCAD, `.vtk` ::COONS_FORMAT_VTK.
 * @param[in]  path file name (only the part after the last '/' is used)
 * @param[out] out  the format
 * @param[in,out] err may be NULL
 * @return ::COONS_OK, or ::COONS_E_INVALID for any other or no extension.
 */
COONS_EXPORT coons_status coons_format_from_path(const char *path, coons_format *out,
                                                 coons_error *err);

/**
 * Format named by a string, compared without regard to case: "stl" and
 * "stl-binary" (binary STL), "stl-ascii", "off", "scad", "vtk".
 * @return ::COONS_OK, or ::COONS_E_INVALID for any other name (the message
 *         lists the known ones).
 */
COONS_EXPORT coons_status coons_format_from_name(const char *name, coons_format *out,
                                                 coons_error *err);

/** Canonical name of a format ("stl-binary", "stl-ascii", "off", "scad",
 *  "vtk", "auto"); a static string, never NULL ("unknown" for other values). */
COONS_EXPORT const char *coons_format_name(coons_format format);

/**
 * The kind of mesh a format holds: ::COONS_MESH_KIND_SURFACE (STL, OFF,
 * SCAD), ::COONS_MESH_KIND_VOLUME (VTK) or ::COONS_MESH_KIND_SOLID (STEP,
 * IGES, BREP: exact solids, no mesh); ::COONS_MESH_KIND_NONE for
 * ::COONS_FORMAT_AUTO and values that are no format. The formats are
 * numbered 1, 2, ... without gaps, so a program lists them all by counting
 * up from 1 until this returns ::COONS_MESH_KIND_NONE.
 */
COONS_EXPORT coons_mesh_kind coons_format_kind(coons_format format);

/**
 * The extension that implies a format with coons_format_from_path(), such
 * as ".stl"; a static string, or NULL for a format that no extension
 * implies (::COONS_FORMAT_STL_ASCII: `.stl` means binary) and for values
 * that are no format.
 */
COONS_EXPORT const char *coons_format_extension(coons_format format);

/**
 * Writes a mesh to a file, atomically.
 *
 * The output is written to a new temporary file in the same directory
 * (`.NAME.coons-XXXXXX`, created with O_EXCL and mode 0666 minus the umask,
 * or with the mode of the file it replaces), flushed to disk with fsync(),
 * closed, and only then renamed over `path`. On any error, including a full
 * disk, a file size limit or cancellation, the temporary file is removed
 * and an existing file at `path` is left byte-for-byte unchanged; no partial
 * output ever appears under `path`. If `path` is a symbolic link, the file
 * it points to is replaced. If the process is killed outright (SIGKILL,
 * power loss) a stray temporary file may remain, never a partial `path`.
 *
 * @param[in] m       the mesh
 * @param[in] path    output file name
 * @param[in] format  a format, or ::COONS_FORMAT_AUTO for the one implied
 *                    by the extension of `path`
 * @param[in] opts    options, or NULL for the defaults
 * @param[in,out] err may be NULL
 * @return ::COONS_OK;
 *         ::COONS_E_INVALID: unknown extension with ::COONS_FORMAT_AUTO,
 *         a volume format (use coons_volume_mesh_write()),
 *         bad options version, `path` names `opts->protect_path` or a
 *         directory or another non-regular file, a non-finite vertex or a
 *         triangle index out of range;
 *         ::COONS_E_LIMIT: 2^32 triangles or more in binary STL, or (both
 *         STL formats) a coordinate beyond the float32 range, +-3.4e38;
 *         ::COONS_E_IO: the file could not be created, written, synced,
 *         closed or renamed, or the write was cancelled (the message names
 *         the file and the system error);
 *         ::COONS_E_NOMEM.
 * Thread safety: safe for concurrent calls on the same mesh. A file of
 * more than one 1 MiB buffer is written by a second thread while the next
 * buffer is formatted (the same bytes); that thread only calls write(2):
 * `cancel` and `written` run on the calling thread, and it allocates
 * nothing.
 */
COONS_EXPORT coons_status coons_mesh_write(const coons_mesh *m, const char *path,
                                           coons_format format,
                                           const coons_write_options *opts, coons_error *err);

/**
 * Writes a mesh to an open stdio stream (for example stdout), then fflush()es
 * it; the stream stays open. Nothing is atomic here: on error part of the
 * output may already have been written. If `opts->protect_path` is set and
 * the stream has a file descriptor naming that file, the write is refused.
 *
 * @param[in] format any format but ::COONS_FORMAT_AUTO
 * @return as coons_mesh_write(); ::COONS_E_IO when the stream reports an
 *         error (e.g. writing to /dev/full).
 */
COONS_EXPORT coons_status coons_mesh_write_stream(const coons_mesh *m, FILE *fp,
                                                  coons_format format,
                                                  const coons_write_options *opts,
                                                  coons_error *err);

/**
 * Writes a volume mesh to a file, atomically, exactly as coons_mesh_write()
 * writes a triangle mesh: temporary file, fsync(), rename(); on any error
 * an existing file at `path` is left byte for byte and no temporary file
 * remains; `opts` (protect_path, cancel, name, units, header) means the
 * same.
 *
 * @param[in] vm      the volume mesh
 * @param[in] path    output file name
 * @param[in] format  a volume format (::COONS_FORMAT_VTK), or
 *                    ::COONS_FORMAT_AUTO for the one implied by the
 *                    extension of `path`
 * @param[in] opts    options, or NULL for the defaults
 * @param[in,out] err may be NULL
 * @return ::COONS_OK;
 *         ::COONS_E_INVALID: a surface format (use coons_mesh_write()), an
 *         unknown extension with ::COONS_FORMAT_AUTO, bad options version,
 *         `path` names `opts->protect_path` or a non-regular file;
 *         ::COONS_E_UNSUPPORTED: the format cannot hold the mesh's element
 *         kind; ::COONS_E_IO as coons_mesh_write(); ::COONS_E_NOMEM.
 * Thread safety: safe for concurrent calls on the same mesh.
 */
COONS_EXPORT coons_status coons_volume_mesh_write(const coons_volume_mesh *vm, const char *path,
                                                  coons_format format,
                                                  const coons_write_options *opts,
                                                  coons_error *err);

/**
 * Writes a volume mesh to an open stdio stream and fflush()es it, as
 * coons_mesh_write_stream() does for triangle meshes (not atomic).
 * @param[in] format any volume format (not ::COONS_FORMAT_AUTO)
 * @return as coons_volume_mesh_write(); ::COONS_E_IO when the stream
 *         reports an error.
 */
COONS_EXPORT coons_status coons_volume_mesh_write_stream(const coons_volume_mesh *vm, FILE *fp,
                                                         coons_format format,
                                                         const coons_write_options *opts,
                                                         coons_error *err);

/**
 * Writes the OpenSCAD animation of a model with morph bodies (coons-model(5)
 * "morph"; outputs.md "Metamorphosis") atomically to `path`: every morph
 * as the vertex arrays of its keys on one lattice with one face list and a
 * function of the time that blends them with the path's weights in
 * OpenSCAD, a module NAME(t) per body (NAME its sanitised name) and one
 * for the model (wo->name) that unites them with union(), and a top-level
 * call passing $t, so that View > Animate plays the metamorphosis. Bodies
 * without morphs are plain polyhedra sampled with `so`. `openscad -D
 * '$t=T'` gives, for each morph, the vertices and faces that
 * coons_model_set_time(T) and coons_model_sample() with the same `so`
 * give, to the printed digits: every mesh of a morph uses one lattice and
 * face list for its whole path, the lattice the file names in a comment:
 * `so->resolution` when set, else the smallest uniform lattice whose mesh,
 * with the face list fixed, is within the tolerance at every key time and
 * at 4 times inside each interval between keys.
 * @param[in] body -1 for every body, else the index of the one body written
 * @return ::COONS_OK, ::COONS_E_INVALID, ::COONS_E_LIMIT (triangle budget),
 *         ::COONS_E_UNSUPPORTED (a morph whose lattice collapses
 *         differently at different times: no one face list serves every
 *         frame), ::COONS_E_IO, ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_model_write_scad_animation(const coons_model *m, long body,
                                                           const coons_sample_options *so,
                                                           const char *path,
                                                           const coons_write_options *wo,
                                                           coons_error *err);

/**
 * coons_model_write_scad_animation() to an open stream (flushed, not closed).
 * @return as coons_model_write_scad_animation(): ::COONS_OK,
 *         ::COONS_E_INVALID, ::COONS_E_LIMIT, ::COONS_E_UNSUPPORTED,
 *         ::COONS_E_IO (a write or the flush failed), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_model_write_scad_animation_stream(const coons_model *m,
                                                                  long body,
                                                                  const coons_sample_options *so,
                                                                  FILE *fp,
                                                                  const coons_write_options *wo,
                                                                  coons_error *err);

#ifdef __cplusplus
}
#endif
#endif
