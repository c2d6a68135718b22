/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The 3MF writer of a build without lib3mf (COONS_WITH_LIB3MF=OFF): the
 * format stays in the table, so `.3mf` and `-f 3mf` are recognised, and
 * the format's check refuses every mesh before any output exists. */
#include "writer.h"

coons_status coons__check_3mf(const coons_mesh *m, coons_error *err)
{
    (void)m;
    return coons__error_set(err, COONS_E_UNSUPPORTED,
                            "this libcoons was built without lib3mf, so it cannot write 3MF "
                            "(rebuild with lib3mf-dev installed and -DCOONS_WITH_LIB3MF=ON)");
}

coons_status coons__write_3mf(const coons_mesh *m, const coons__wopts *o, coons__sink *s)
{
    (void)o;
    return s->status = coons__check_3mf(m, s->err);
}
