/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/brep.h
 * @brief A model's bodies as exact solids: STEP, IGES and Open CASCADE BREP
 *        files with B-spline / NURBS faces (needs the Open CASCADE layer).
 *
 * Every face of a solid is the exact form of a body face
 * (coons_body_face_to_nurbs(), coons/nurbs.h): a Geom_BSplineSurface,
 * rational when the form has weights; fitted faces (shells) carry the
 * deviation coons_body_face_to_nurbs() measured within the model's
 * tolerance. One solid per body:
 * - the faces are sewn along their shared edges (Open CASCADE's sewing at
 *   1e-7 of the body's size, or 4 times the deviation of fitted faces when
 *   larger, capped by the model's tolerance);
 * - a collapsed face (an apex: all its control points coincide) is left
 *   out, and the edges of its neighbours that collapse to the apex become
 *   degenerate edges: 5 faces;
 * - two faces that coincide (a closed body, such as a ring whose ends
 *   meet) are both left out and the faces between them close on seams;
 * - the solid is oriented outward whatever the sign of the body's
 *   Jacobian (a mirrored body): its volume by Open CASCADE's integration
 *   is made positive.
 *
 * The operation of the model (coons_model_operation()) decides what is
 * written: ::COONS_OP_UNION fuses all solids into one with Open CASCADE's
 * exact Boolean (BRepAlgoAPI_Fuse) with a fuzzy value of 1e-3 of the
 * model's tolerance, gluing the faces bodies share (coons_model_interfaces())
 * when the model has any; ::COONS_OP_NONE writes every solid in one
 * file. Every solid is checked (BRepCheck_Analyzer) before anything is
 * written: a body whose solid is not valid stops the write with
 * ::COONS_E_CSG naming the body and the failed check, and nothing is
 * written.
 *
 * Formats (coons_format, coons/io.h; kind ::COONS_MESH_KIND_SOLID):
 * - ::COONS_FORMAT_STEP (`.step`, `.stp`): ISO 10303-21, application
 *   protocol 214 (automotive design); ::COONS_FORMAT_STEP_AP242 the same
 *   under AP242. One product per solid, named after its body (the union:
 *   after coons_write_options::name); reals with 17 significant digits.
 * - ::COONS_FORMAT_IGES (`.igs`, `.iges`): IGES 5.3 in BRep mode (entities
 *   186 manifold solids, 514 shells, 510 faces, 128 B-spline surfaces),
 *   17 significant digits, names as entity labels.
 * - ::COONS_FORMAT_BREP (`.brep`): Open CASCADE's own text format, the
 *   compound of the solids, 17 significant digits.
 * Units: the options' units, else the model's (coons_model_units()); "mm",
 * "cm", "m", "um", "in", "ft" and their spelled-out names; none means
 * millimetres. Coordinates are written as they are (no scaling).
 *
 * The same model gives the same bytes: the STEP time stamp is
 * 1970-01-01T00:00:00 and the IGES dates 19700101.000000, the author and
 * organisation are empty, the originating system is libcoons and its
 * version, the file's name is coons_write_options::name.
 * The file is written atomically, as every writer of coons/io.h does.
 * The Open CASCADE layer never prints (its message printers are removed).
 * A library built without it refuses these formats with
 * ::COONS_E_UNSUPPORTED, naming Open CASCADE.
 */
#ifndef COONS_BREP_H
#define COONS_BREP_H

#include "coons/types.h"
#include "coons/model.h"
#include "coons/io.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Writes the model's bodies as exact solids to `path`, atomically.
 * @param[in] m       the model (its operation, tolerance, units, body names)
 * @param[in] path    output file
 * @param[in] format  ::COONS_FORMAT_STEP, ::COONS_FORMAT_STEP_AP242,
 *                    ::COONS_FORMAT_IGES, ::COONS_FORMAT_BREP, or
 *                    ::COONS_FORMAT_AUTO for the one `path`'s extension implies
 * @param[in] opts    name (the union's product name), units, protect_path,
 *                    cancel; NULL for defaults
 * @return ::COONS_OK; ::COONS_E_INVALID (NULL argument, a format that is
 *         not a solid format, unknown units); ::COONS_E_UNSUPPORTED (built
 *         without Open CASCADE); ::COONS_E_CSG (a solid that is not valid,
 *         a failed union; the message names the body and the check);
 *         ::COONS_E_LIMIT (a face form too large); ::COONS_E_IO;
 *         ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_model_write_solid(const coons_model *m, const char *path,
                                                  coons_format format,
                                                  const coons_write_options *opts,
                                                  coons_error *err);

/** Nonzero when this library writes solids (built with Open CASCADE). */
COONS_EXPORT int coons_solid_formats_available(void);

#ifdef __cplusplus
}
#endif

#endif
