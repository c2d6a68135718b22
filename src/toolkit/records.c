/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The version check of the public options and report records (every
 * coons_*_options and coons_*_report carries its version first): one check
 * and one wording for all of them, "<record> version N, expected M (use
 * <INIT macro>)". */
#include "coons_internal.h"

coons_status coons__record_version_check(const char *record, unsigned version, unsigned oldest,
                                         unsigned current, const char *init, coons_error *err)
{
    if (version >= oldest && version <= current) return COONS_OK;
    return coons__error_set(err, COONS_E_INVALID, "%s version %u, expected %u (use %s)", record,
                            version, current, init);
}
