// SPDX-License-Identifier: GPL-3.0-or-later
// <coons.h> as a whole from C++17 (no C++ type in the public API); the
// *_INIT macros (value-initialised records with their fields set, C++17
// having no designated initialisers) give what their _init() functions give.
#include "header_records.h"

int main()
{
    int bad = records_match();
    if (!bad) printf("every *_INIT macro matches its _init() function (C++17)\n");
    return bad ? 1 : 0;
}
