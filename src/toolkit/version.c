/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "coons_internal.h"

int coons_version(void) { return COONS_VERSION_NUMBER; }
const char *coons_version_string(void) { return COONS_VERSION_STRING; }
