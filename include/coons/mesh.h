/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/mesh.h
 * @brief Triangle meshes of body boundaries: sampling, checks, writers.
 * (Filled in by the meshing work.)
 */
#ifndef COONS_MESH_H
#define COONS_MESH_H

#include "coons/types.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __cplusplus
}
#endif
#endif
