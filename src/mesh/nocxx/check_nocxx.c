/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Without OpenMesh (COONS_WITH_OPENMESH=OFF): the checks are the index-array
 * ones of check.c alone, and files cannot be read. */
#include "coons_internal.h"
#include "coons_test_hooks.h"
#include "mesh_glue.h"

coons_status coons_mesh_check(const coons_mesh *m, coons_mesh_report *report, coons_error *err)
{
    return coons__mesh_check_c(m, report, err);
}

coons_status coons__mesh_read(const char *path, coons_mesh **out, coons_error *err)
{
    *out = NULL;
    return coons__error_set(err, COONS_E_UNSUPPORTED,
                            "cannot read '%s': libcoons was built without OpenMesh", path);
}
