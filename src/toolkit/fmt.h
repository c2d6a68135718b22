/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Number formatting for the text writers: shortest round-trip text of
 * doubles and floats, and unsigned integers, independent of the locale. */
#ifndef COONS_IO_FMT_H
#define COONS_IO_FMT_H

#include <locale.h>
#include <stddef.h>
#include <stdint.h>

/* Longest text any formatter below produces, plus the terminating NUL. */
#define COONS__FMT_MAX 32

/* coons__fmt_double() needs the "C" locale for snprintf/strtod on the
 * calling thread: begin() creates it and installs it with uselocale()
 * (per thread, never setlocale()), end() restores the caller's locale.
 * begin() returns 0 when the locale object cannot be created. */
typedef struct coons__fmt_scope {
    locale_t c_locale;
    locale_t saved;
} coons__fmt_scope;
int coons__fmt_begin(coons__fmt_scope *s);
void coons__fmt_end(coons__fmt_scope *s);
/* Temporarily back to the caller's locale (around user callbacks). */
void coons__fmt_suspend(const coons__fmt_scope *s);
void coons__fmt_resume(const coons__fmt_scope *s);

/* Shortest decimal text that strtod() reads back to exactly v (a finite
 * double), written NUL-terminated into out[COONS__FMT_MAX]; returns its
 * length. Fixed or exponent notation, whichever is shorter (fixed on a
 * tie): "0.1", "-0", "1e-300", "9007199254740992", "4.9406564584124654e-324".
 * Requires an active coons__fmt_begin() scope on this thread. */
size_t coons__fmt_double(char *out, double v);

/* Same for a finite float: shortest text that strtof() reads back to
 * exactly v. Pure arithmetic (no libc formatting, no locale), fast enough
 * for ASCII STL; see fmt.c for why double arithmetic is exact enough. */
size_t coons__fmt_float(char *out, float v);

/* Decimal text of an unsigned integer; returns its length (no NUL). */
size_t coons__fmt_u64(char *out, uint64_t v);

#endif
