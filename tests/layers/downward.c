/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A source of the sample stage that keeps the layer rule: its own stage's
 * header and those of earlier stages (mesh, core, toolkit). It must compile
 * with the sample stage's include directories, so that the failure of
 * upward.c is the rule's and not a broken include path. */
#include "sampling.h"
#include "mesh_impl.h"
#include "body_impl.h"
#include "coons_internal.h"

int coons_layer_probe_downward(void) { return 0; }
