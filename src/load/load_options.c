/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The loader's options record (coons_model_load_options, coons/model.h):
 * its _init() function and the version check of the loader's entries. */
#include "coons_internal.h"
#include "load_options.h"

void coons_model_load_options_init(coons_model_load_options *o)
{
    const coons_model_load_options d = COONS_MODEL_LOAD_OPTIONS_INIT;
    if (o) *o = d;
}

coons_status coons__model_load_options_check(const coons_model_load_options *o, coons_error *err)
{
    if (o && o->version != COONS_MODEL_LOAD_OPTIONS_VERSION)
        return coons__error_set(err, COONS_E_INVALID,
                                "model load options version %u, expected %u (use "
                                "COONS_MODEL_LOAD_OPTIONS_INIT)",
                                o->version, (unsigned)COONS_MODEL_LOAD_OPTIONS_VERSION);
    return COONS_OK;
}
