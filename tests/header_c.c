/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Compile-only: <coons.h> alone under -std=c11 -pedantic -Werror. */
#include <coons.h>
int header_c_probe(void);
int header_c_probe(void) { return COONS_VERSION_NUMBER > 0 ? COONS_OK : COONS_E_INTERNAL; }
