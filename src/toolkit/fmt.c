/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Shortest round-trip decimal text for the text writers (OFF, SCAD, ASCII
 * STL), never depending on the process locale (STYLE 18; OpenSCAD's
 * export_stl.cc calls setlocale, which a library must not do).
 *
 * Doubles: glibc's printf("%.*e") is exact, strtod is correctly rounded, so
 * the shortest of 15, 16, 17 significant digits that strtod reads back to
 * the same bits is taken (17 always does; up to 15 digits the correctly
 * rounded text is the shortest one padded with zeros, because any decimal
 * of <= 15 digits survives decimal -> double -> decimal; subnormals, with
 * fewer significant bits, search from 1 digit). Both run under a
 * thread-local "C" locale installed with uselocale().
 *
 * Floats: done in double arithmetic, which has 29 bits more than a float.
 * A candidate D*10^q is accepted only if it lies inside the float's
 * rounding interval with a relative margin of 1e-6 of the half-gap; the
 * few roundings made computing D*10^q (< 1e-15 relative) cannot move it
 * across that margin, so every accepted text reads back exactly (where
 * D*10^q is an integer below 2^53 the test is exact and takes ties, which
 * strtof breaks towards the even significand). Nine
 * digits always pass: their error is <= 0.5e-8 |v| while the smallest
 * half-gap of a float is 2^-26 |v| ~ 1.49e-8 |v|. */
#define _XOPEN_SOURCE 700
#include "fmt.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int coons__fmt_begin(coons__fmt_scope *s)
{
    s->c_locale = newlocale(LC_ALL_MASK, "C", (locale_t)0);
    if (s->c_locale == (locale_t)0) return 0;
    s->saved = uselocale(s->c_locale);
    if (s->saved == (locale_t)0) {
        freelocale(s->c_locale);
        s->c_locale = (locale_t)0;
        return 0;
    }
    return 1;
}

void coons__fmt_end(coons__fmt_scope *s)
{
    if (s->c_locale == (locale_t)0) return;
    uselocale(s->saved);
    freelocale(s->c_locale);
    s->c_locale = (locale_t)0;
}

void coons__fmt_suspend(const coons__fmt_scope *s) { uselocale(s->saved); }
void coons__fmt_resume(const coons__fmt_scope *s) { uselocale(s->c_locale); }

size_t coons__fmt_u64(char *out, uint64_t v)
{
    static const char d2[] = "00010203040506070809101112131415161718192021222324252627282930313233"
                             "34353637383940414243444546474849505152535455565758596061626364656667"
                             "6869707172737475767778798081828384858687888990919293949596979899";
    char tmp[24], *p = tmp + sizeof tmp;
    while (v >= 100) {
        unsigned r = (unsigned)(v % 100);
        v /= 100;
        p -= 2;
        p[0] = d2[2 * r];
        p[1] = d2[2 * r + 1];
    }
    if (v >= 10) {
        p -= 2;
        p[0] = d2[2 * v];
        p[1] = d2[2 * v + 1];
    } else {
        *--p = (char)('0' + v);
    }
    size_t n = (size_t)(tmp + sizeof tmp - p);
    for (size_t i = 0; i < n; i++) out[i] = p[i]; /* short: no memcpy call */
    return n;
}

static size_t ndigits(unsigned v)
{
    size_t n = 1;
    while (v >= 10) {
        v /= 10;
        n++;
    }
    return n;
}

/* Writes the decimal digits[0..nd) * 10^(e - nd + 1) (e = exponent of the
 * first digit, no trailing zeros in digits) in fixed or exponent notation,
 * whichever is shorter, fixed on a tie. Returns the length; NUL-terminates. */
static size_t compose(char *out, int neg, const char *digits, size_t nd, int e)
{
    size_t fixed_len, sci_len;
    if (e >= (int)nd - 1)
        fixed_len = (size_t)e + 1;
    else if (e >= 0)
        fixed_len = nd + 1;
    else
        fixed_len = nd + 1 + (size_t)(-e);
    sci_len = nd + (nd > 1) + 1 + (e < 0) + ndigits((unsigned)(e < 0 ? -e : e));
    char *p = out;
    if (neg) *p++ = '-';
    if (fixed_len <= sci_len) {
        /* Short copies as loops: a memcpy call costs more than they do. */
        if (e >= (int)nd - 1) {
            for (size_t i = 0; i < nd; i++) *p++ = digits[i];
            for (int i = (int)nd - 1; i < e; i++) *p++ = '0';
        } else if (e >= 0) {
            for (int i = 0; i <= e; i++) *p++ = digits[i];
            *p++ = '.';
            for (size_t i = (size_t)e + 1; i < nd; i++) *p++ = digits[i];
        } else {
            *p++ = '0';
            *p++ = '.';
            for (int i = -1; i > e; i--) *p++ = '0';
            for (size_t i = 0; i < nd; i++) *p++ = digits[i];
        }
    } else {
        *p++ = digits[0];
        if (nd > 1) {
            *p++ = '.';
            for (size_t i = 1; i < nd; i++) *p++ = digits[i];
        }
        *p++ = 'e';
        if (e < 0) *p++ = '-';
        p += coons__fmt_u64(p, (uint64_t)(e < 0 ? -e : e));
    }
    *p = '\0';
    return (size_t)(p - out);
}

static size_t fmt_zero(char *out, int neg)
{
    char *p = out;
    if (neg) *p++ = '-';
    *p++ = '0';
    *p = '\0';
    return (size_t)(p - out);
}

size_t coons__fmt_double(char *out, double v)
{
    if (v == 0.0) return fmt_zero(out, signbit(v) != 0);
    int neg = signbit(v) != 0;
    double a = fabs(v);
    size_t len = 0;
    /* Subnormals have fewer significant digits: search from 1 there. */
    for (int prec = a < DBL_MIN ? 1 : 15; prec <= 17; prec++) {
        char buf[48];
        snprintf(buf, sizeof buf, "%.*e", prec - 1, a);
        /* "d.ddd...e[+-]XX" in the C locale. */
        char digits[24];
        size_t nd = 0;
        const char *s = buf;
        for (; *s && *s != 'e'; s++)
            if (*s >= '0' && *s <= '9') digits[nd++] = *s;
        int e = (int)strtol(s + 1, NULL, 10);
        while (nd > 1 && digits[nd - 1] == '0') nd--;
        len = compose(out, neg, digits, nd, e);
        double back = strtod(out, NULL);
        if (memcmp(&back, &v, sizeof v) == 0) break;
    }
    return len;
}

/* 10^e for -32 <= e <= 56, correctly rounded by the compiler. */
static const double pow10_tab[] = {
    1e-32, 1e-31, 1e-30, 1e-29, 1e-28, 1e-27, 1e-26, 1e-25, 1e-24, 1e-23, 1e-22, 1e-21, 1e-20,
    1e-19, 1e-18, 1e-17, 1e-16, 1e-15, 1e-14, 1e-13, 1e-12, 1e-11, 1e-10, 1e-9,  1e-8,  1e-7,
    1e-6,  1e-5,  1e-4,  1e-3,  1e-2,  1e-1,  1e0,   1e1,   1e2,   1e3,   1e4,   1e5,   1e6,
    1e7,   1e8,   1e9,   1e10,  1e11,  1e12,  1e13,  1e14,  1e15,  1e16,  1e17,  1e18,  1e19,
    1e20,  1e21,  1e22,  1e23,  1e24,  1e25,  1e26,  1e27,  1e28,  1e29,  1e30,  1e31,  1e32,
    1e33,  1e34,  1e35,  1e36,  1e37,  1e38,  1e39,  1e40,  1e41,  1e42,  1e43,  1e44,  1e45,
    1e46,  1e47,  1e48,  1e49,  1e50,  1e51,  1e52,  1e53,  1e54,  1e55,  1e56};
#define POW10(e) pow10_tab[(e) + 32]

/* floor(x + 0.5) for 0 <= x < 2^62, without a libm call. */
static inline double rnd_half_up(double x) { return (double)(int64_t)(x + 0.5); }

size_t coons__fmt_float(char *out, float v)
{
    if (v == 0.0f) return fmt_zero(out, signbit(v) != 0);
    int neg = signbit(v) != 0;
    float fa = fabsf(v);
    double a = fa;
    /* Neighbouring floats by their bit patterns (fa > 0 and finite), and
     * the half-gaps to them (exact in double). */
    uint32_t bits;
    memcpy(&bits, &fa, sizeof bits);
    uint32_t bdown = bits - 1, bup = bits + 1;
    float fdown, fup;
    memcpy(&fdown, &bdown, sizeof fdown);
    memcpy(&fup, &bup, sizeof fup);
    double lo = (a - (double)fdown) * 0.5;
    double hi = isinf(fup) ? lo : ((double)fup - a) * 0.5;
    /* strtof rounds a tie to the even significand: if v's is even, a text
     * exactly half-way to a neighbour still reads back as v. */
    int even = (bits & 1u) == 0;
    /* Decimal exponent k of the first digit: 2^(e2-1) <= a < 2^e2 gives
     * floor((e2-1) log10 2) <= k <= that + 1. */
    int e2 = (int)((bits >> 23) & 0xffu) - 126;
    if (e2 == -126) (void)frexp(a, &e2); /* subnormal */
    int k = (int)floor((e2 - 1) * 0.30102999566398120);
    /* Work in units of 10^(k-8), where the value has 9 digits before the
     * point. f is one rounded power of ten applied alike to the value and
     * the half-gaps, so the comparisons below are off by ~1e-16 relative at
     * most: far inside the 1e-6 margin. */
    double f = POW10(8 - k), s9 = a * f;
    if (s9 >= 1e9) {
        k++;
        f = POW10(8 - k);
        s9 = a * f;
    }
    double lo9 = lo * f * (1.0 - 1e-6), hi9 = hi * f * (1.0 - 1e-6);
    static const double pow10p[] = {1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
    static const double inv10p[] = {1, 1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9};
    uint32_t dig = 0;
    int q = 0;
    if (k < 5 && fa >= FLT_MIN) {
        /* Common case (normal, below 1e5, so every candidate is a fraction):
         * the candidates of 6..9 digits side by side, without a
         * data-dependent loop exit. */
        double d6 = rnd_half_up(s9 * 1e-3), d7 = rnd_half_up(s9 * 1e-2),
               d8 = rnd_half_up(s9 * 1e-1), d9 = rnd_half_up(s9);
        double c6 = d6 * 1e3, c7 = d7 * 1e2, c8 = d8 * 10.0;
        int ok6 = fabs(c6 - s9) < (c6 >= s9 ? hi9 : lo9);
        int ok7 = fabs(c7 - s9) < (c7 >= s9 ? hi9 : lo9);
        int ok8 = fabs(c8 - s9) < (c8 >= s9 ? hi9 : lo9);
        int p = ok6 ? 6 : ok7 ? 7 : ok8 ? 8 : 9;
        double d = ok6 ? d6 : ok7 ? d7 : ok8 ? d8 : d9;
        q = k - p + 1;
        dig = (uint32_t)d;
        if (d >= pow10p[p]) {
            dig = (uint32_t)pow10p[p - 1];
            q++;
        }
    } else {
        /* Any float with a shortest form of <= 6 digits is found at p = 6
         * (FLT_DIG): shorter forms come out by stripping trailing zeros.
         * Subnormals carry fewer digits, so there the search starts at 1. */
        for (int p = fa < FLT_MIN ? 1 : 6; p <= 9; p++) {
            double unit = pow10p[9 - p];
            double d = rnd_half_up(s9 * inv10p[9 - p]);
            q = k - p + 1;
            dig = (uint32_t)d;
            if (d >= pow10p[p]) {
                dig = (uint32_t)pow10p[p - 1];
                q++;
            }
            /* An integer below 2^53 times an exact power of ten is computed
             * exactly, and then so is c - a: decide exactly, ties included. */
            if (q >= 0 && q <= 22) {
                double c = (double)dig * POW10(q); /* 10^q exact for q <= 22 */
                if (c < 9007199254740992.0) {
                    double diff = c >= a ? c - a : a - c, gap = c >= a ? hi : lo;
                    if (diff < gap || (diff == gap && even)) break;
                    continue;
                }
            }
            double c9 = d * unit;
            if (c9 >= s9 ? c9 - s9 < hi9 : s9 - c9 < lo9) break;
        }
    }
    while (dig % 10 == 0) {
        dig /= 10;
        q++;
    }
    char digits[16];
    size_t nd = coons__fmt_u64(digits, dig);
    return compose(out, neg, digits, nd, q + (int)nd - 1);
}
