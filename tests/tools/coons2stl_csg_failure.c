/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * coons2stl with every CGAL step failing, for the tests of how the command
 * reports a failed repair or union (tests/cli/test_cli_union.py,
 * test_cli_manifold.py): the command's own sources, its main() renamed
 * coons2stl_main (tests/CMakeLists.txt), linked to coons_static for the
 * test hook coons__csg_inject_failure() (src/coons_test_hooks.h). The
 * installed coons2stl has no such hook.
 */
#undef main
#include "coons_test_hooks.h"

int coons2stl_main(int argc, char **argv);

int main(int argc, char **argv)
{
    coons__csg_inject_failure(1);
    return coons2stl_main(argc, argv);
}
