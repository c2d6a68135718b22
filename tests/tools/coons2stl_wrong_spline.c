/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * coons2stl whose solid writer builds every face on a wrong spline (the
 * test hook coons__occt_inject_wrong_spline(), src/toolkit/coons_test_hooks.h:
 * an interior control point moved), for tests/cli/test_step.py to show that
 * its point-distance check fails on such a file although Open CASCADE finds
 * the solid valid. The command's own sources, its main() renamed
 * coons2stl_main (tests/CMakeLists.txt), linked to coons_static. The
 * installed coons2stl has no such hook.
 */
#undef main
#include "coons_test_hooks.h"

int coons2stl_main(int argc, char **argv);

int main(int argc, char **argv)
{
    coons__occt_inject_wrong_spline(1);
    return coons2stl_main(argc, argv);
}
