/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons.h
 * @brief libcoons: Coons curves, patches and bodies, their boundary meshes,
 *        and the model files that describe them. The one header users include.
 *
 * Rules that hold for the whole API (see libcoons(3)):
 * - Every fallible function returns a ::coons_status (0 = ::COONS_OK, errors
 *   negative) and fills the caller-owned ::coons_error given as its last
 *   argument, which may be NULL. Nothing is printed, nothing exits.
 * - Constructors deep-copy their inputs. Everything returned belongs to the
 *   caller and is released with its own coons_X_free(), which accepts NULL.
 *   `const` pointers returned by accessors are borrowed views, valid until
 *   the owning object is freed. The caller never free()s library memory.
 * - One naming rule: constructors are coons_<object>_new_<what>(), each
 *   object is released by coons_<object>_free(); accessors are
 *   coons_<object>_<attribute>() with no `get_` (coons_mesh_vertex_count(),
 *   coons_model_units(), coons_body_kind()); the one setter is
 *   coons_<object>_set_<attribute>() (coons_model_set_time()); predicates
 *   are coons_<object>_is_<adjective>() (coons_csg_is_available()); every
 *   other operation is coons_<object>_<verb>[_<noun>]() (coons_body_sample(),
 *   coons_mesh_count_self_intersections()). tools/migrate-0.3.py rewrites
 *   the 0.2 names 0.3 changed (tools/abi-0.3-renames.txt).
 * - Objects are immutable after construction; there is no global mutable
 *   state apart from the allocator (coons_set_allocator()), so concurrent
 *   calls on the same objects from many threads are safe.
 */
#ifndef COONS_H
#define COONS_H

#include "coons/version.h"
#include "coons/types.h"
#include "coons/curve.h"
#include "coons/patch.h"
#include "coons/body.h"
#include "coons/nurbs.h"
#include "coons/model.h"
#include "coons/mesh.h"
#include "coons/sample.h"
#include "coons/iso.h"
#include "coons/check.h"
#include "coons/deform.h"
#include "coons/mesh_read.h"
#include "coons/volume.h"
#include "coons/csg.h"
#include "coons/io.h"
#include "coons/brep.h"

#endif
