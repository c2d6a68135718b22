/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Shared by tests/header_c.c (C11) and tests/header_cxx.cpp (C++17): every
 * record's *_INIT macro gives, field by field, what its _init() function
 * gives (the function is compiled as C, so this checks the C++ path of the
 * macros against the C one), and the three records without a function hold
 * their version and zeros. Returns the number of mismatches. */
#include <stdio.h>
#include <string.h>

#include <coons.h>

#define SAME(f)                                                              \
    if (memcmp(&a.f, &b.f, sizeof a.f) != 0) {                               \
        fprintf(stderr, "%s: field %s differs from the _init() one\n", what, #f); \
        bad++;                                                               \
    }

static int records_match(void)
{
    int bad = 0;
    {
        const char *what = "COONS_SAMPLE_OPTIONS_INIT";
        coons_sample_options a, b = COONS_SAMPLE_OPTIONS_INIT;
        memset(&a, 0xA5, sizeof a);
        coons_sample_options_init(&a);
        SAME(version)
        SAME(tolerance)
        SAME(resolution)
        SAME(max_triangles)
        SAME(max_aspect)
        SAME(flags)
    }
    {
        const char *what = "COONS_CSG_OPTIONS_INIT";
        coons_csg_options a, b = COONS_CSG_OPTIONS_INIT;
        memset(&a, 0xA5, sizeof a);
        coons_csg_options_init(&a);
        SAME(version)
        SAME(unite)
        SAME(repair)
        SAME(name)
        SAME(progress)
        SAME(userdata)
        SAME(threads)
    }
    {
        const char *what = "COONS_CSG_REPORT_INIT";
        coons_csg_report a, b = COONS_CSG_REPORT_INIT;
        memset(&a, 0xA5, sizeof a);
        coons_csg_report_init(&a);
        SAME(version)
        SAME(triangles_in)
        SAME(degenerate_dropped)
        SAME(intersecting_pairs)
        SAME(parts_in)
        SAME(groups)
        SAME(passed_through)
        SAME(patches)
        SAME(patches_kept)
        SAME(fast_unions)
        SAME(fallbacks)
        SAME(triangles_out)
        SAME(rounding_merged)
        SAME(close_merged)
        SAME(slivers_fixed)
        SAME(closed)
        SAME(nonmanifold_edges)
        SAME(pinch_edges_split)
        SAME(pinch_vertices_split)
    }
    {
        const char *what = "COONS_HERMITE_OPTIONS_INIT";
        coons_hermite_options a, b = COONS_HERMITE_OPTIONS_INIT;
        memset(&a, 0xA5, sizeof a);
        coons_hermite_options_init(&a);
        SAME(version)
        SAME(cross)
        SAME(twist)
        SAME(twists)
        SAME(tol)
    }
    {
        const char *what = "COONS_NETWORK_OPTIONS_INIT";
        coons_network_options a, b = COONS_NETWORK_OPTIONS_INIT;
        memset(&a, 0xA5, sizeof a);
        coons_network_options_init(&a);
        SAME(version)
        SAME(s_nodes)
        SAME(t_nodes)
        SAME(twist)
        SAME(blend)
        SAME(tol)
    }
    {
        const char *what = "COONS_MESH_REPORT_INIT";
        coons_mesh_report a, b = COONS_MESH_REPORT_INIT;
        memset(&a, 0xA5, sizeof a);
        coons_mesh_report_init(&a);
        SAME(version)
        SAME(vertices)
        SAME(unused_vertices)
        SAME(triangles)
        SAME(degenerate_triangles)
        SAME(edges)
        SAME(boundary_edges)
        SAME(nonmanifold_edges)
        SAME(misoriented_edges)
        SAME(nonmanifold_vertices)
        SAME(shells)
        SAME(euler)
        SAME(expected_euler)
        SAME(closed)
        SAME(manifold)
        SAME(oriented)
        SAME(openmesh)
        SAME(openmesh_rejected)
        SAME(openmesh_boundary)
        SAME(volume)
        SAME(area)
    }
    {
        const char *what = "COONS_MODEL_LOAD_OPTIONS_INIT";
        coons_model_load_options a, b = COONS_MODEL_LOAD_OPTIONS_INIT;
        memset(&a, 0xA5, sizeof a);
        coons_model_load_options_init(&a);
        SAME(version)
        SAME(max_bytes)
        SAME(max_values)
        SAME(max_depth)
        SAME(max_points)
    }
    {
        const char *what = "COONS_VOLUME_OPTIONS_INIT";
        coons_volume_options a, b = COONS_VOLUME_OPTIONS_INIT;
        memset(&a, 0xA5, sizeof a);
        coons_volume_options_init(&a);
        SAME(version)
        SAME(element)
        SAME(resolution)
        SAME(tolerance)
        SAME(max_cells)
    }
    {
        const char *what = "COONS_VOLUME_QUALITY_INIT";
        coons_volume_quality a, b = COONS_VOLUME_QUALITY_INIT;
        memset(&a, 0xA5, sizeof a);
        coons_volume_quality_init(&a);
        SAME(version)
        SAME(cells)
        SAME(nodes)
        SAME(element)
        SAME(min_scaled_jacobian)
        SAME(mean_scaled_jacobian)
        SAME(inverted)
        SAME(below_0_2)
        SAME(collapsed)
        SAME(worst_cell)
        SAME(worst_uvw)
    }
    {
        const char *what = "COONS_WRITE_OPTIONS_INIT";
        coons_write_options a, b = COONS_WRITE_OPTIONS_INIT;
        memset(&a, 0xA5, sizeof a);
        coons_write_options_init(&a);
        SAME(version)
        SAME(name)
        SAME(units)
        SAME(header)
        SAME(protect_path)
        SAME(cancel)
        SAME(cancel_ctx)
        SAME(background)
        SAME(nbackground)
    }
    {
        coons_error e = COONS_ERROR_INIT;
        coons_deform_report d = COONS_DEFORM_REPORT_INIT;
        coons_mesh_read_options r = COONS_MESH_READ_OPTIONS_INIT;
        if (e.code != COONS_OK || e.message[0] || e.file[0] || e.line || e.column || e.path[0])
            fprintf(stderr, "COONS_ERROR_INIT is not all zero\n"), bad++;
        if (d.version != COONS_DEFORM_REPORT_VERSION || d.lo[0] != 0.0 || d.hi[2] != 0.0 ||
            d.deviation != 0.0 || d.triangles_in || d.vertices_out || d.rounds || d.reversed)
            fprintf(stderr, "COONS_DEFORM_REPORT_INIT: not the version and zeros\n"), bad++;
        if (r.version != COONS_MESH_READ_OPTIONS_VERSION || r.max_bytes || r.max_triangles)
            fprintf(stderr, "COONS_MESH_READ_OPTIONS_INIT: not the version and zeros\n"), bad++;
    }
    return bad;
}
