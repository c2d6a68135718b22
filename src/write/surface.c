/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The entry points for triangle meshes, coons_mesh_write() and
 * coons_mesh_write_stream(): the checks every surface format needs, then
 * the format's own (its table row) and the shared output (atomic.c). */
#include "writer.h"

static coons_status prepare(coons__write_job *job, const coons_mesh *m, coons_format format,
                            const coons_write_options *opts, coons_error *err)
{
    coons_status st =
        coons__write_prepare(job, m != NULL, format, COONS_MESH_KIND_SURFACE, opts, err);
    if (st != COONS_OK) return st;
    job->surface = m;
    job->volume = NULL;
    size_t nv = coons_mesh_vertex_count(m), nt = coons_mesh_triangle_count(m);
    for (size_t i = 0; i < job->o.nbackground; i++)
        if (job->o.background[i] >= coons_mesh_part_count(m))
            return coons__error_set(err, COONS_E_INVALID,
                                    "write options: background part %zu, the mesh has %zu parts",
                                    job->o.background[i], coons_mesh_part_count(m));
    if (job->row->max_triangles && nt > job->row->max_triangles)
        return coons__error_set(err, COONS_E_LIMIT, "%s holds at most %llu triangles, the mesh "
                                "has %zu", job->row->title,
                                (unsigned long long)job->row->max_triangles, nt);
    /* The container enforces these; checking again costs one pass and
     * keeps a writer from ever emitting a file that reads back wrong. */
    const double *xyz = coons_mesh_vertices(m);
    for (size_t i = 0; i < 3 * nv; i++)
        if (!isfinite(xyz[i]))
            return coons__error_set(err, COONS_E_INVALID, "vertex %zu is not finite", i / 3);
    const uint32_t *tri = coons_mesh_triangles(m);
    for (size_t i = 0; i < 3 * nt; i++)
        if (tri[i] >= nv)
            return coons__error_set(err, COONS_E_INVALID, "triangle %zu refers to vertex %lu of %zu",
                                    i / 3, (unsigned long)tri[i], nv);
    return job->row->check_surface ? job->row->check_surface(m, err) : COONS_OK;
}

coons_status coons_mesh_write(const coons_mesh *m, const char *path, coons_format format,
                              const coons_write_options *opts, coons_error *err)
{
    coons__write_job job;
    coons_status st = coons__write_resolve(path, &format, err);
    if (st == COONS_OK) st = prepare(&job, m, format, opts, err);
    return st == COONS_OK ? coons__write_path(&job, path, opts, err) : st;
}

coons_status coons_mesh_write_stream(const coons_mesh *m, FILE *fp, coons_format format,
                                     const coons_write_options *opts, coons_error *err)
{
    coons__write_job job;
    if (!fp) return coons__error_set(err, COONS_E_INVALID, "no stream given");
    coons_status st = prepare(&job, m, format, opts, err);
    return st == COONS_OK ? coons__write_stream(&job, fp, opts, err) : st;
}
