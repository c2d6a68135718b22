/* SPDX-License-Identifier: GPL-3.0-or-later */
/* <coons.h> as a whole under -std=c11 -pedantic -Werror; the *_INIT macros
 * (designated initialisers in C) give what their _init() functions give. */
#include "header_records.h"

int main(void)
{
    int bad = records_match();
    if (!bad) printf("every *_INIT macro matches its _init() function (C11)\n");
    return bad ? 1 : 0;
}
