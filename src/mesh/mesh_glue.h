/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Internal declarations of the mesh stage shared by its C sources and the
 * C++ OpenMesh glue (openmesh.cpp). Plain C: no OpenMesh or C++ types here. */
#ifndef COONS_MESH_GLUE_H
#define COONS_MESH_GLUE_H

#include "coons_internal.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The index-array checks of coons_mesh_check() (check.c): everything but
 * the OpenMesh fields, which are left 0. */
coons_status coons__mesh_check_c(const coons_mesh *m, coons_mesh_report *r, coons_error *err);

#ifdef __cplusplus
}
#endif
#endif
