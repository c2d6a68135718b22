/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Writes the isoparametric surfaces of a model file, for the tests that
 * read them with other programs (VTK, OpenSCAD) until coons2stl has the
 * --iso option:
 *
 *     iso_sample MODEL OUT [-b] [-r N] SPEC...
 *
 * SPEC is u=..., v=... or w=... (cli_iso_parse(), coons2stl's parser); -b
 * adds each body's boundary (COONS_ISO_WITH_BOUNDARY), an OpenSCAD background
 * part (coons_write_options.background); -r N samples on
 * a fixed lattice of N intervals. OUT's extension picks the format
 * (.off, .scad, .vtu, .stl). Exit status 0 on success, 1 with a message. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <coons.h>

#include "iso_parse.h"

/* Writes m; with the boundaries, each body's first part is one. */
static coons_status write_surfaces(const coons_model *model, const coons_mesh *m, const char *path,
                          size_t n, unsigned flags, coons_error *err)
{
    size_t bg[64], nb = 0;
    for (size_t k = 0; flags && k < coons_model_body_count(model) && k < 64; k++)
        bg[nb++] = k * (n + 1);
    coons_write_options wo = COONS_WRITE_OPTIONS_INIT;
    wo.background = bg;
    wo.nbackground = nb;
    return coons_mesh_write(m, path, COONS_FORMAT_AUTO, &wo, err);
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: iso_sample MODEL OUT [-b] [-r N] SPEC...\n");
        return 1;
    }
    coons_iso_request req[64];
    size_t n = 0;
    unsigned flags = 0;
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    coons_error err = COONS_ERROR_INIT;
    for (int i = 3; i < argc; i++) {
        if (!strcmp(argv[i], "-b")) {
            flags |= COONS_ISO_WITH_BOUNDARY;
        } else if (!strcmp(argv[i], "-r") && i + 1 < argc) {
            o.resolution = (unsigned)strtoul(argv[++i], NULL, 10);
        } else if (cli_iso_parse(argv[i], req, 64, &n, &err) != COONS_OK) {
            fprintf(stderr, "iso_sample: %s\n", err.message);
            return 1;
        }
    }
    coons_model *model = NULL;
    coons_mesh *m = NULL;
    if (coons_model_load_file(argv[1], NULL, &model, &err) != COONS_OK ||
        coons_model_iso_surfaces(model, req, n, &o, flags, &m, &err) != COONS_OK ||
        write_surfaces(model, m, argv[2], n, flags, &err) != COONS_OK) {
        fprintf(stderr, "iso_sample: %s\n", err.message);
        coons_mesh_free(m);
        coons_model_free(model);
        return 1;
    }
    coons_mesh_free(m);
    coons_model_free(model);
    return 0;
}
