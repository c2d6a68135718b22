/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The solid writer of a build without Open CASCADE (COONS_WITH_OCCT=OFF):
 * the STEP, IGES and BREP formats stay in the table, so `.step` and
 * `-f iges` are recognised, and every write is refused before any output
 * exists. */
#include "writer.h"

coons_status coons__check_solid(coons_error *err)
{
    return coons__error_set(err, COONS_E_UNSUPPORTED,
                            "this libcoons was built without Open CASCADE (OCCT), so it cannot "
                            "write STEP, IGES or BREP solids (rebuild with libocct-*-dev and "
                            "libtbb-dev installed and -DCOONS_WITH_OCCT=ON)");
}

coons_status coons__write_solid(const coons_model *m, coons_format format, const coons__wopts *o,
                                coons__sink *s)
{
    (void)m;
    (void)format;
    (void)o;
    return s->status = coons__check_solid(s->err);
}

int coons_solid_formats_available(void) { return 0; }
