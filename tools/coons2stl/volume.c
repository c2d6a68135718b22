/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Volume meshes: -o FILE.msh | .vtu | .inp | .vtk (coons2stl(1), "VOLUME
 * MESHES"), and the "volume_mesh" object of --info. The mesh is the
 * library's (coons_model_volume_mesh(), or coons_body_volume_mesh() for
 * --body); this file adds the policy: an inverted cell refuses the write
 * (exit 3, naming the body and the cell's parameters) unless
 * --allow-inverted, and the write is atomic like every output.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"

cli_volume cli_volume_of(const options *o)
{
    cli_volume v = {o->element, {o->resolution3[0], o->resolution3[1], o->resolution3[2]},
                    o->tolerance, o->allow_inverted, cli_threads(o->jobs)};
    return v;
}

coons_status cli_volume_mesh(const coons_model *m, long body, const cli_volume *v,
                             coons_volume_mesh **out, coons_error *err)
{
    coons_volume_options vo = COONS_VOLUME_OPTIONS_INIT;
    vo.element = v->element;
    for (int d = 0; d < 3; d++) vo.resolution[d] = v->resolution[d];
    vo.tolerance = v->tolerance > 0 ? v->tolerance : coons_model_tolerance(m);
    vo.progress = cli_progress_on() ? cli_on_progress : NULL;
    vo.userdata = (void *)(uintptr_t)"volume mesh";
    vo.threads = v->threads;
    if (body < 0) return coons_model_volume_mesh(m, &vo, out, err);
    return coons_body_volume_mesh(coons_model_body(m, (size_t)body), &vo,
                                  coons_model_body_name(m, (size_t)body), out, err);
}

static void number(double x)
{
    if (isfinite(x))
        printf("%.17g", x);
    else
        printf("null");
}

static const char *element_name(coons_element e)
{
    return e == COONS_ELEMENT_HEX27 ? "hex27" : e == COONS_ELEMENT_HEX20 ? "hex20" : "hex8";
}

void cli_print_volume_quality(const coons_volume_mesh *vm, size_t part)
{
    coons_volume_quality q = COONS_VOLUME_QUALITY_INIT;
    if (coons_volume_mesh_quality(vm, part, &q, NULL) != COONS_OK) {
        printf("null");
        return;
    }
    printf("{\"cells\": %zu, \"nodes\": %zu, \"element\": \"%s\",\n       "
           "\"min_scaled_jacobian\": ",
           q.cells, q.nodes, element_name(q.element));
    number(q.min_scaled_jacobian);
    printf(", \"mean_scaled_jacobian\": ");
    number(q.mean_scaled_jacobian);
    printf(",\n       \"inverted\": %zu, \"below_0_2\": %zu, \"collapsed\": %zu, "
           "\"worst_cell_uvw\": [",
           q.inverted, q.below_0_2, q.collapsed);
    for (int d = 0; d < 3; d++) {
        if (d) printf(", ");
        number(q.worst_uvw[d]);
    }
    printf("]}");
}

/* Whether the mesher's cell field scaled_jacobian (the value
 * coons_volume_mesh_quality() computes) has a value <= 0: only then can a
 * cell be inverted, and the quality report is worth its second pass. */
static int may_be_inverted(const coons_volume_mesh *vm)
{
    for (size_t i = 0; i < coons_volume_mesh_field_count(vm, COONS_FIELD_CELL); i++) {
        coons_field_type type;
        const void *values;
        const char *name = coons_volume_mesh_field(vm, COONS_FIELD_CELL, i, &type, &values);
        if (strcmp(name, "scaled_jacobian") != 0 || type != COONS_FIELD_FLOAT64) continue;
        const double *sj = values;
        for (size_t c = 0; c < coons_volume_mesh_cell_count(vm); c++)
            if (!(sj[c] > 0)) return 1;
        return 0;
    }
    return 1;
}

/* Exit 3 (reported) when a part has an inverted cell, else 0. */
static int refuse_inverted(const coons_volume_mesh *vm, const char *shown)
{
    if (!may_be_inverted(vm)) return 0;
    for (size_t p = 0; p < coons_volume_mesh_part_count(vm); p++) {
        coons_volume_quality q = COONS_VOLUME_QUALITY_INIT;
        if (coons_volume_mesh_quality(vm, p, &q, NULL) != COONS_OK || !q.inverted) continue;
        cli_message(0,
                    "%s: body '%s' has %zu inverted cell%s (scaled Jacobian <= 0; the worst, "
                    "%.6g, at (u, v, w) = (%.6g, %.6g, %.6g)): the body folds there; nothing "
                    "was written (--allow-inverted writes it anyway)",
                    shown, coons_volume_mesh_part_name(vm, p), q.inverted,
                    q.inverted == 1 ? "" : "s", q.min_scaled_jacobian, q.worst_uvw[0],
                    q.worst_uvw[1], q.worst_uvw[2]);
        return EXIT_GEOMETRY;
    }
    return 0;
}

/* "dir/part.msh" -> "part" (the model name some formats carry). */
static void base_name(const char *path, char *out, size_t cap)
{
    out[0] = '\0';
    if (!path || strcmp(path, "-") == 0) return;
    const char *base = strrchr(path, '/');
    snprintf(out, cap, "%s", base ? base + 1 : path);
    char *dot = strrchr(out, '.');
    if (dot && dot != out) *dot = '\0';
}

int cli_write_volume(const coons_model *m, long body, const cli_volume *v,
                     const cli_output *out)
{
    coons_error err = COONS_ERROR_INIT;
    int to_stdout = !out->path || strcmp(out->path, "-") == 0;
    const char *shown = to_stdout ? "<stdout>" : out->path;
    coons_volume_mesh *vm = NULL;
    coons_status rc = cli_volume_mesh(m, body, v, &vm, &err);
    if (rc != COONS_OK) {
        cli_message(0, "%s: %s; nothing was written", shown, err.message);
        return EXIT_GEOMETRY;
    }
    int status = cli_write_volume_mesh(vm, v, out);
    coons_volume_mesh_free(vm);
    return status;
}

int cli_write_volume_mesh(coons_volume_mesh *vm, const cli_volume *v, const cli_output *out)
{
    coons_error err = COONS_ERROR_INIT;
    int to_stdout = !out->path || strcmp(out->path, "-") == 0;
    const char *shown = to_stdout ? "<stdout>" : out->path;
    int status = v->allow_inverted ? 0 : refuse_inverted(vm, shown);
    if (status) return status;
    if (out->scale != 1.0 && coons_volume_mesh_scale(vm, out->scale, &err) != COONS_OK) {
        cli_message(0, "%s: %s; nothing was written", shown, err.message);
        return EXIT_GEOMETRY;
    }
    coons_status rc;
    char name[256];
    base_name(to_stdout ? out->input : out->path, name, sizeof name);
    coons_write_options wopts = COONS_WRITE_OPTIONS_INIT;
    wopts.units = out->units;
    wopts.name = name[0] ? name : NULL;
    int from_file = out->input && strcmp(out->input, "-") != 0;
    wopts.protect_path = from_file ? out->input : NULL;
    wopts.written = cli_progress_on() ? cli_on_written : NULL;
    wopts.written_ctx = (void *)(uintptr_t)shown;
    rc = to_stdout ? coons_volume_mesh_write_stream(vm, stdout, out->format, &wopts, &err)
                   : cli_write_volume_file(vm, out->path, out->format, &wopts, &err);
    cli_progress_end();
    if (cli_caught_signal()) cli_die_of_caught_signal(rc, shown);
    if (rc != COONS_OK) {
        cli_message(0, "%s", err.message);
        return EXIT_GEOMETRY;
    }
    return 0;
}
