/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The command-line syntax of isoparametric surfaces, `u=0.25,0.5` (moved
 * out of the library in 0.3: parsing option text is the command's job). */
#ifndef COONS2STL_ISO_PARSE_H
#define COONS2STL_ISO_PARSE_H

#include <coons.h>

/*
 * Parses `D=V[,V...]` (D one of u, v, w, then one or more comma-separated
 * numbers in [0,1], read by strtod in the C locale, which the command never
 * leaves), appending one request per value at out[*count]; *count grows.
 * Returns COONS_OK; COONS_E_INVALID (not of that form; the message quotes
 * it); COONS_E_DOMAIN (a value outside [0,1]); COONS_E_LIMIT (more than
 * `cap` requests in all). On error *count and the requests before it are
 * unchanged and err (may be NULL) holds the status and the message.
 */
coons_status cli_iso_parse(const char *spec, coons_iso_request *out, size_t cap, size_t *count,
                           coons_error *err);

#endif
