/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The state of the test hooks of the C++ layers (coons_test_hooks.h): which
 * guarded entry throws std::bad_alloc, and whether the CGAL step fails.
 * Test-only global state, set before any other call. */
#include <string.h>

#include "coons_test_hooks.h"

static const char *bad_alloc_entry;
static unsigned long bad_alloc_count;
static int csg_failure;
static int csg_whole;
static int occt_wrong_spline;

void coons__cxx_inject_bad_alloc(const char *entry) { bad_alloc_entry = entry; }

unsigned long coons__cxx_injected_count(void) { return bad_alloc_count; }

int coons__cxx_injected(const char *entry)
{
    if (!bad_alloc_entry || strcmp(bad_alloc_entry, entry) != 0) return 0;
    bad_alloc_count++;
    return 1;
}

void coons__csg_inject_failure(int on) { csg_failure = on != 0; }

int coons__csg_failure_injected(void) { return csg_failure; }

void coons__csg_whole_corefinement(int on) { csg_whole = on != 0; }

int coons__csg_whole_corefinement_set(void) { return csg_whole; }

void coons__occt_inject_wrong_spline(int on) { occt_wrong_spline = on != 0; }

int coons__occt_wrong_spline_injected(void) { return occt_wrong_spline; }
