/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The entry points for volume meshes, coons_volume_mesh_write() and
 * coons_volume_mesh_write_stream(): the same output machinery as the
 * triangle meshes (atomic.c), with the checks of the format's table row.
 * The container (src/mesh/volume) guarantees finite nodes and indices in
 * range, so there is nothing generic left to check here. */
#include "writer.h"

static coons_status prepare(coons__write_job *job, const coons_volume_mesh *vm,
                            coons_format format, const coons_write_options *opts,
                            coons_error *err)
{
    coons_status st =
        coons__write_prepare(job, vm != NULL, format, COONS_MESH_KIND_VOLUME, opts, err);
    if (st != COONS_OK) return st;
    job->surface = NULL;
    job->volume = vm;
    return job->row->check_volume ? job->row->check_volume(vm, err) : COONS_OK;
}

coons_status coons_volume_mesh_write(const coons_volume_mesh *vm, const char *path,
                                     coons_format format, const coons_write_options *opts,
                                     coons_error *err)
{
    coons__write_job job;
    coons_status st = coons__write_resolve(path, &format, err);
    if (st == COONS_OK) st = prepare(&job, vm, format, opts, err);
    return st == COONS_OK ? coons__write_path(&job, path, opts, err) : st;
}

coons_status coons_volume_mesh_write_stream(const coons_volume_mesh *vm, FILE *fp,
                                            coons_format format,
                                            const coons_write_options *opts, coons_error *err)
{
    coons__write_job job;
    if (!fp) return coons__error_set(err, COONS_E_INVALID, "no stream given");
    coons_status st = prepare(&job, vm, format, opts, err);
    return st == COONS_OK ? coons__write_stream(&job, fp, opts, err) : st;
}
