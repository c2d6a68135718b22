/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * --iso: the isoparametric surfaces u, v or w = const of the bodies (seed
 * 000 section 2.1, Fig. 2-6: the interior "density" of a body), each its own
 * part, with --with-boundary each body's boundary too (in SCAD a
 * transparent % part: coons_write_options.background), written atomically like every output
 * (coons_model_iso_surfaces(), coons_body_iso_surface()).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static coons_status one_body(const coons_model *m, size_t body, const coons_iso_request *req,
                             size_t n, const coons_sample_options *so, int with_boundary,
                             coons_mesh **out, coons_error *err)
{
    const coons_body *b = coons_model_body(m, body);
    const char *name = coons_model_body_name(m, body);
    coons_mesh *mesh = NULL;
    coons_status st = COONS_OK;
    if (with_boundary) {
        st = coons_body_sample(b, so, name, &mesh, err);
    } else {
        st = coons_mesh_new(&mesh, err);
    }
    for (size_t i = 0; i < n && !st; i++) {
        char part[COONS_ISO_NAME_MAX];
        coons_iso_surface_name(name, req[i].direction, req[i].value, part, sizeof part);
        st = coons_body_iso_surface(b, req[i].direction, req[i].value, so, part, mesh, err);
    }
    if (st) {
        coons_mesh_free(mesh);
        return st;
    }
    *out = mesh;
    return COONS_OK;
}

int cli_write_iso(const coons_model *m, long body, const cli_iso *iso,
                  const coons_sample_options *so, const cli_output *out)
{
    coons_error err = COONS_ERROR_INIT;
    int to_stdout = !out->path || strcmp(out->path, "-") == 0;
    const char *shown = to_stdout ? "<stdout>" : out->path;
    coons_iso_request *req = malloc((iso->n ? iso->n : 1) * sizeof *req);
    if (!req) {
        cli_message(0, "%s: out of memory; nothing was written", shown);
        return EXIT_GEOMETRY;
    }
    for (size_t i = 0; i < iso->n; i++) {
        req[i].direction = iso->dir[i];
        req[i].value = iso->value[i];
    }
    coons_mesh *mesh = NULL;
    coons_status rc =
        body < 0 ? coons_model_iso_surfaces(m, req, iso->n, so,
                                            iso->with_boundary ? COONS_ISO_WITH_BOUNDARY : 0u,
                                            &mesh, &err)
                 : one_body(m, (size_t)body, req, iso->n, so, iso->with_boundary, &mesh, &err);
    free(req);
    cli_progress_end();
    if (rc != COONS_OK) {
        cli_message(0, "%s: %s; nothing was written", shown, err.message);
        return EXIT_GEOMETRY;
    }
    /* The boundaries: part 0 of one body; with every body, each body's
     * first part (its boundary, then its surfaces: coons_model_iso_surfaces()). */
    size_t nb = !iso->with_boundary ? 0 : body < 0 ? coons_model_body_count(m) : 1;
    size_t *bg = nb ? malloc(nb * sizeof *bg) : NULL;
    if (nb && !bg) {
        coons_mesh_free(mesh);
        cli_message(0, "%s: out of memory; nothing was written", shown);
        return EXIT_GEOMETRY;
    }
    for (size_t k = 0; k < nb; k++) bg[k] = k * (iso->n + 1);
    cli_output where = *out;
    where.background = bg;
    where.nbackground = nb;
    int rc2 = cli_write_surface(mesh, &where, shown);
    free(bg);
    return rc2;
}
