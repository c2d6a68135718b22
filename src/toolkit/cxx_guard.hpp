/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The C++ boundary, written once (GEOS's execute()): every extern "C" entry
 * of the C++ layers (src/mesh/openmesh.cpp, src/csg/cgal_solid.cpp) runs its
 * work through coons::guard(), so no exception ever reaches C.
 *
 *   std::bad_alloc        -> COONS_E_NOMEM, "out of memory"
 *   std::exception        -> the entry's status, "<prefix><what()>", or what
 *                            the entry's own describe(err, e) makes of it
 *   anything else         -> COONS_E_INTERNAL, the entry's `unknown` text
 *
 * The guard is noexcept and its catch path allocates nothing: the message
 * is formatted by snprintf (coons__error_set) into the caller's coons_error.
 * A describe() must be noexcept too (checked at compile time). This header
 * includes no CGAL or OpenMesh: an entry that must recognise CGAL's
 * exception does so in its describe(), inside the CGAL translation unit.
 *
 * Test hook (coons_test_hooks.h): coons__cxx_inject_bad_alloc(name) makes
 * the guard of the entry `name` throw std::bad_alloc before any work. */
#ifndef COONS_CXX_GUARD_HPP
#define COONS_CXX_GUARD_HPP

#include <exception>
#include <new>
#include <utility>

extern "C" {
#include "coons_internal.h"
#include "coons_test_hooks.h"
}

namespace coons {

/* What an entry says about an exception that is not std::bad_alloc. */
struct guard_text {
    coons_status code;   /* status for a std::exception */
    const char *prefix;  /* put before e.what() */
    const char *unknown; /* the whole message for anything else (COONS_E_INTERNAL) */
};

/* Runs body() (returning coons_status) for the extern "C" entry `entry`;
 * describe(err, e) turns a std::exception other than std::bad_alloc into
 * the status and message. */
template <typename Body, typename Describe>
coons_status guard(const char *entry, coons_error *err, const char *unknown, Body &&body,
                   Describe &&describe) noexcept
{
    try {
        if (coons__cxx_injected(entry)) throw std::bad_alloc();
        return std::forward<Body>(body)();
    } catch (const std::bad_alloc &) {
        return coons__error_nomem(err);
    } catch (const std::exception &e) {
        static_assert(noexcept(describe(err, e)), "a guard's describe() must be noexcept");
        return describe(err, e);
    } catch (...) {
        return coons__error_set(err, COONS_E_INTERNAL, "%s", unknown);
    }
}

/* The common case: a std::exception becomes t.code with t.prefix + what(). */
template <typename Body>
coons_status guard(const char *entry, coons_error *err, const guard_text &t, Body &&body) noexcept
{
    return guard(entry, err, t.unknown, std::forward<Body>(body),
                 [&t](coons_error *e, const std::exception &x) noexcept {
                     return coons__error_set(e, t.code, "%s%s", t.prefix, x.what());
                 });
}

} // namespace coons

#endif
