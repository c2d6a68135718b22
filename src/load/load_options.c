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
    if (!o) return COONS_OK;
    return COONS__RECORD_CHECK(err, "model load options", o->version, COONS_MODEL_LOAD_OPTIONS);
}
