/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Internal: the version check of coons_model_load_options (load_options.c). */
#ifndef COONS_LOAD_OPTIONS_H
#define COONS_LOAD_OPTIONS_H

#include "coons.h"

/* COONS_E_INVALID unless o (may be NULL) has the version this library knows. */
coons_status coons__model_load_options_check(const coons_model_load_options *o, coons_error *err);

#endif
