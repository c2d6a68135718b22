/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The entry points of the model loader (coons_model_load_file(),
 * coons_model_load_memory(), libcoons(3)):
 * the limits, reading the file, and errors about the file as a whole; the
 * model itself is read by read_model.c (loader.h).
 */
#include <stdio.h>
#include <string.h>

#include "loader.h"
#include "load_options.h"
#include "read_file.h"

static void resolve(const coons_model_load_options *o, coons_model_load_options *r)
{
    coons_model_load_options d = COONS_MODEL_LOAD_OPTIONS_INIT;
    if (o) d = *o;
    if (!d.max_bytes) d.max_bytes = COONS_MODEL_MAX_BYTES;
    if (!d.max_values) d.max_values = COONS_MODEL_MAX_VALUES;
    if (!d.max_depth) d.max_depth = COONS_MODEL_MAX_DEPTH;
    if (d.max_depth > COONS__JSON_DEPTH_CEILING) d.max_depth = COONS__JSON_DEPTH_CEILING;
    if (!d.max_points) d.max_points = COONS_MODEL_MAX_POINTS;
    *r = d;
}

coons_status coons_model_load_memory(const char *data, size_t size, const char *name,
                                     const coons_model_load_options *opts,
                                     coons_model **out, coons_error *err)
{
    if (out) *out = NULL;
    const char *file = name ? name : "<buffer>";
    if (!out || (!data && size))
        return coons__file_error(err, COONS_E_INVALID, file, "no data or no place for the model");
    coons_status vrc = coons__model_load_options_check(opts, err);
    if (vrc) return vrc;
    coons_model_load_options o;
    resolve(opts, &o);
    if (size > o.max_bytes)
        return coons__file_error(err, COONS_E_LIMIT, file,
                          "the model is %zu bytes, above the limit of %zu bytes (raise "
                          "max_bytes; coons2stl --max-bytes N)",
                          size, o.max_bytes);
    coons__ld L;
    memset(&L, 0, sizeof L);
    L.buf = data ? data : "";
    L.len = size;
    L.file = file;
    L.err = err;
    L.max_points = o.max_points;
    L.max_values = o.max_values;
    L.op = COONS_OP_UNION;

    coons__json *j = NULL;
    coons__json_where where;
    coons_status rc = coons__json_parse(L.buf, size, o.max_values, o.max_depth, &j, &where, err);
    if (rc) {
        if (rc == COONS_E_NOMEM || !err) return rc;
        char msg[COONS_ERROR_MESSAGE_MAX];
        snprintf(msg, sizeof msg, "%s", err->message);
        snprintf(L.path, sizeof L.path, "%s", where.path);
        return coons__ld_fail_at(&L, where.offset, rc, msg);
    }
    L.j = j;
    rc = coons__ld_model(&L, out);
    if (L.names) {
        size_t nb = coons__json_size(j, L.bodies_tok);
        for (size_t i = 0; i < nb; i++) coons__free(L.names[i].name);
        coons__free(L.names);
    }
    coons__ld_defs_free(&L);
    coons__json_free(j);
    return rc;
}

coons_status coons_model_load_file(const char *path, const coons_model_load_options *opts,
                                   coons_model **out, coons_error *err)
{
    if (out) *out = NULL;
    if (!path || !out) return coons__file_error(err, COONS_E_INVALID, "?", "no file name");
    coons_status vrc = coons__model_load_options_check(opts, err);
    if (vrc) return vrc;
    coons_model_load_options o;
    resolve(opts, &o);
    unsigned char *buf = NULL;
    size_t len = 0;
    coons_status rc = coons__read_file(path, "model", "raise max_bytes; coons2stl --max-bytes N",
                                       o.max_bytes, &buf, &len, err);
    if (rc) return rc;
    rc = coons_model_load_memory((const char *)buf, len, path, &o, out, err);
    coons__free(buf);
    return rc;
}
