/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A source of the sample stage that breaks the layer rule on purpose: it
 * includes the writers' header, a later stage. Compiled with the sample
 * stage's include directories (src/CMakeLists.txt), it must not compile
 * (tests/CMakeLists.txt: layer_rule_upward). */
#include "sampling.h"
#include "writer.h"

int coons_layer_probe_upward(void) { return 0; }
