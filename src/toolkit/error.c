/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Status strings and the caller-owned error record (no global or
 * thread-local state: the library stays reentrant). */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "coons_internal.h"

const char *coons_strerror(int code)
{
    switch (code) {
    case COONS_OK: return "success";
    case COONS_E_NOMEM: return "out of memory";
    case COONS_E_INVALID: return "invalid argument or value";
    case COONS_E_DOMAIN: return "parameter outside its domain";
    case COONS_E_IO: return "input/output error";
    case COONS_E_PARSE: return "malformed JSON";
    case COONS_E_CSG: return "repair or Boolean operation failed";
    case COONS_E_INTERNAL: return "internal error";
    case COONS_E_LIMIT: return "size limit exceeded";
    case COONS_E_UNSUPPORTED: return "not supported";
    case COONS_E_INCOMPATIBLE: return "curves or patches do not meet";
    default: return "unknown error";
    }
}

coons_status coons__error_set(coons_error *err, coons_status code, const char *fmt, ...)
{
    if (!err) return code;
    err->code = code;
    err->file[0] = '\0';
    err->path[0] = '\0';
    err->line = 0;
    err->column = 0;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->message, sizeof err->message, fmt, ap);
    va_end(ap);
    return code;
}

coons_status coons__error_nomem(coons_error *err)
{
    return coons__error_set(err, COONS_E_NOMEM, "out of memory");
}
