// SPDX-License-Identifier: GPL-3.0-or-later
// Compile-only: <coons.h> from C++ (no C++ type in the public API).
#include <coons.h>
int header_cxx_probe();
int header_cxx_probe() { coons_error e = COONS_ERROR_INIT; return e.code; }
