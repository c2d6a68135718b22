/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Test hooks: internal functions for the tests, never exported from the
 * shared library (hidden visibility; link coons_static to reach them). Not
 * thread-safe: set them before any other call, as coons_set_allocator().
 * Plain C. */
#ifndef COONS_TEST_HOOKS_H
#define COONS_TEST_HOOKS_H

#include "coons.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Makes the C++ guard (src/cxx_guard.hpp) of the extern "C" entry named
 * `entry` (e.g. "coons_mesh_check") throw std::bad_alloc before any work,
 * at every call until cleared; NULL clears. The string is not copied. */
void coons__cxx_inject_bad_alloc(const char *entry);
/* Number of times an injected std::bad_alloc was thrown so far. */
unsigned long coons__cxx_injected_count(void);
/* Nonzero when the guard of `entry` is to throw (called by the guard). */
int coons__cxx_injected(const char *entry);

/* Nonzero: coons_mesh_solidify() throws a CGAL failure ("injected failure
 * (testing)") once the parts are known, as if CGAL could not complete; its
 * message names the bodies. Set by the test-only build of coons2stl
 * (tests/tools/coons2stl_csg_failure.c); the installed coons2stl cannot. */
void coons__csg_inject_failure(int on);
int coons__csg_failure_injected(void);

/* Nonzero: the fast union corefines whole shells with CGAL's Boolean, as
 * before the near chain (only the triangles near the other shell
 * corefined, patches classified by the library), to compare the two. */
void coons__csg_whole_corefinement(int on);
int coons__csg_whole_corefinement_set(void);

/* Nonzero: the solid writer (src/write/occt.cpp) builds every face that
 * has interior control points with the middle one moved by 1e-4 of the
 * body's size (a knot moved instead changes the edges, and the writer then
 * refuses the body: its faces no longer close): a wrong spline that Open
 * CASCADE still finds valid, for the tests to see their point-distance
 * check fail. Set by the test-only coons2stl
 * (tests/tools/coons2stl_wrong_spline.c). */
void coons__occt_inject_wrong_spline(int on);
int coons__occt_wrong_spline_injected(void);

/* The error estimate of coons_body_deform() (src/sample/deform.c): mode
 * 0, on, nothing counted (the default); 1, on, and the triangles it
 * decided (left whole unmeasured) counted; 2, off: every triangle is
 * measured. coons__deform_estimated(): the count of the last call (0 in
 * mode 0 and 2... as last set). */
void coons__deform_estimates(int mode);
size_t coons__deform_estimated(void);

/* The count of coons_mesh_count_self_intersections() on `m` as it is (no
 * scaling), on `threads` threads; with `old_tri` (one flag per triangle, or
 * NULL) the local count of the union's final check, where pairs of two
 * flagged triangles are not tested; `reference` nonzero: by the earlier
 * method (CGAL's box_intersection_d and the 3-D tests alone), to compare.
 * Zero-area triangles are counted in *degenerate (may be NULL).
 * ::COONS_E_UNSUPPORTED without CGAL. */
coons_status coons__csg_count_pairs(const coons_mesh *m, const unsigned char *old_tri,
                                    int reference, unsigned threads, size_t *pairs,
                                    size_t *degenerate, coons_error *err);

/* Reads an STL, OFF, OBJ, PLY or OM file with OpenMesh's readers (chosen by
 * extension) into a new mesh of one part named after the file: for tests
 * that read back what the writers wrote. ::COONS_E_IO when the file cannot
 * be read or holds no face; ::COONS_E_UNSUPPORTED without OpenMesh. */
coons_status coons__mesh_read(const char *path, coons_mesh **out, coons_error *err);

#ifdef __cplusplus
}
#endif
#endif
