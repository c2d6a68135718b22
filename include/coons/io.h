/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/io.h
 * @brief Writing meshes: binary and ASCII STL, OFF, and OpenSCAD source.
 *
 * All writers see a ::coons_mesh only (see coons/mesh.h) and are
 * deterministic: the same mesh and options always give byte-identical
 * output, whatever the locale of the process (the library never calls
 * setlocale()).
 *
 * Formats and the precision they carry:
 * - ::COONS_FORMAT_STL_BINARY: the default for `.stl`. 80-byte header that
 *   never starts with "solid" (it carries the header text and the units),
 *   a little-endian uint32 triangle count, then per triangle the unit facet
 *   normal and the three vertices as little-endian IEEE float32 and a zero
 *   attribute word. Vertices are rounded to float32 by the format; a mesh of
 *   2^32 or more triangles, or with a coordinate beyond the float32 range,
 *   is refused (::COONS_E_LIMIT).
 * - ::COONS_FORMAT_STL_ASCII: `solid NAME` ... `endsolid NAME`. The numbers
 *   are the same float32 values the binary writer stores, each printed as
 *   the shortest text that reads back (strtof) to exactly that float.
 * - ::COONS_FORMAT_OFF: `OFF`, `#` comment lines (writer, units, parts), the
 *   counts, the vertices in full double precision, then `3 a b c` faces.
 * - ::COONS_FORMAT_SCAD: OpenSCAD source. One module per mesh part, named
 *   after the part, holding a `polyhedron(points=..., faces=...)`; one
 *   module for the whole model calling every part module; and a top-level
 *   call of that module. `use <file.scad>` therefore imports the modules
 *   and `include <file.scad>` also renders the model. Vertices carry full
 *   double precision.
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
 * `_2`, `_3`, ... . The original names appear in comments.
 */
#ifndef COONS_IO_H
#define COONS_IO_H

#include <stdio.h>

#include "coons/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Output formats. */
typedef enum coons_format {
    COONS_FORMAT_AUTO = 0,       /**< chosen from the output path's extension */
    COONS_FORMAT_STL_BINARY = 1, /**< binary STL (what `.stl` means) */
    COONS_FORMAT_STL_ASCII = 2,  /**< ASCII STL */
    COONS_FORMAT_OFF = 3,        /**< Object File Format, text */
    COONS_FORMAT_SCAD = 4        /**< OpenSCAD source */
} coons_format;

/** Version of ::coons_write_options this header describes. */
#define COONS_WRITE_OPTIONS_VERSION 1

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
} coons_write_options;

/** Default options. */
#define COONS_WRITE_OPTIONS_INIT {COONS_WRITE_OPTIONS_VERSION, NULL, NULL, NULL, NULL, NULL, NULL}

/**
 * Sets `*o` to ::COONS_WRITE_OPTIONS_INIT (for language bindings that
 * cannot use the macro); NULL is a harmless no-op.
 */
COONS_EXPORT void coons_write_options_init(coons_write_options *o);

/**
 * Format implied by a path's extension, compared without regard to case:
 * `.stl` gives ::COONS_FORMAT_STL_BINARY, `.off` ::COONS_FORMAT_OFF,
 * `.scad` ::COONS_FORMAT_SCAD.
 * @param[in]  path file name (only the part after the last '/' is used)
 * @param[out] out  the format
 * @param[in,out] err may be NULL
 * @return ::COONS_OK, or ::COONS_E_INVALID for any other or no extension.
 */
COONS_EXPORT coons_status coons_format_from_path(const char *path, coons_format *out,
                                                 coons_error *err);

/**
 * Format named by a string, compared without regard to case: "stl" and
 * "stl-binary" (binary STL), "stl-ascii", "off", "scad".
 * @return ::COONS_OK, or ::COONS_E_INVALID for any other name.
 */
COONS_EXPORT coons_status coons_format_from_name(const char *name, coons_format *out,
                                                 coons_error *err);

/** Canonical name of a format ("stl-binary", "stl-ascii", "off", "scad",
 *  "auto"); a static string, never NULL ("unknown" for other values). */
COONS_EXPORT const char *coons_format_name(coons_format format);

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
 *         bad options version, `path` names `opts->protect_path` or a
 *         directory or another non-regular file, a non-finite vertex or a
 *         triangle index out of range;
 *         ::COONS_E_LIMIT: 2^32 triangles or more in binary STL, or (both
 *         STL formats) a coordinate beyond the float32 range, +-3.4e38;
 *         ::COONS_E_IO: the file could not be created, written, synced,
 *         closed or renamed, or the write was cancelled (the message names
 *         the file and the system error);
 *         ::COONS_E_NOMEM.
 * Thread safety: safe for concurrent calls on the same mesh.
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

#ifdef __cplusplus
}
#endif
#endif
