# SPDX-License-Identifier: GPL-3.0-or-later
"""Every call into libcoons, in one module (a rename of a C function touches
only this file; python/build_support/gen_cdef.py fails the build when a
name used here is not declared by the public headers).

cffi in ABI mode over the package's own libcoons.so, with the declarations
generated at build time from include/coons/*.h (_cdef.h). cffi releases the
GIL around every C call, so long calls (sampling, unions, volume meshes)
let other Python threads run. Functions here take C pointers from
:class:`coons._handle.Handle` and return Python or numpy values; shapes and
values are checked by the callers (model.py, mesh.py, builders.py).
"""
import os

import numpy as np
from cffi import FFI

from . import errors

_here = os.path.dirname(os.path.abspath(__file__))
ffi = FFI()
with open(os.path.join(_here, "_cdef.h"), encoding="utf-8") as _f:
    ffi.cdef(_f.read())
lib = ffi.dlopen(os.path.join(_here, "libcoons.so"))
# Resolve every declared name now: cffi's ABI-mode `lib` creates each
# accessor on first use under a non-reentrant lock, and a garbage
# collection inside that lock that frees a model (Handle.__del__ ->
# coons_model_free, first use) would wait for the lock forever.
for _name in dir(lib):
    try:
        getattr(lib, _name)
    except Exception:  # a declared function the library does not export
        pass

FACE_NAMES = ("u0", "u1", "v0", "v1", "w0", "w1")


def _dp(a):
    return ffi.NULL if a is None else ffi.cast("double *", ffi.from_buffer(a))


def _str(p):
    return ffi.string(p).decode("utf-8", "replace") if p != ffi.NULL else ""


def new_error():
    return ffi.new("coons_error *")


def check(rc, err):
    if rc != lib.COONS_OK:
        raise errors.from_status(rc, _str(err.message) or _str(lib.coons_strerror(rc)))


def _enc(s):
    return s.encode("utf-8") if isinstance(s, str) else s


def version():
    return _str(lib.coons_version_string())


def csg_available():
    return bool(lib.coons_csg_is_available())


# ---- models ---------------------------------------------------------------

def _load_options(limits):
    o = ffi.new("coons_model_load_options *")
    lib.coons_model_load_options_init(o)
    for k in ("max_bytes", "max_values", "max_depth", "max_points"):
        v = limits.get(k)
        if v is not None:
            if int(v) < 0:
                raise errors.InvalidError("%s must be >= 0" % k)
            setattr(o, k, int(v))
    return o


def _load_failed(rc, err):
    return errors.load_error(rc, _str(err.message) or _str(lib.coons_strerror(rc)),
                             _str(err.file), err.line, err.column, _str(err.path))


def model_load_file(path, limits):
    out = ffi.new("coons_model **")
    err = new_error()
    rc = lib.coons_model_load_file(_enc(path), _load_options(limits), out, err)
    if rc != lib.COONS_OK:
        raise _load_failed(rc, err)
    return out[0]


def model_load_memory(data, name, limits):
    out = ffi.new("coons_model **")
    err = new_error()
    buf = ffi.from_buffer(data)
    rc = lib.coons_model_load_memory(buf, len(data), _enc(name), _load_options(limits), out, err)
    if rc != lib.COONS_OK:
        raise _load_failed(rc, err)
    return out[0]


def model_free(m):
    lib.coons_model_free(m)


def model_body_count(m):
    return lib.coons_model_body_count(m)


def model_body(m, i):
    return lib.coons_model_body(m, i)


def model_body_name(m, i):
    return _str(lib.coons_model_body_name(m, i))


def model_find_body(m, name):
    return lib.coons_model_find_body(m, _enc(name))


def model_tolerance(m):
    return lib.coons_model_tolerance(m)


def model_units(m):
    return _str(lib.coons_model_units(m))


def model_operation(m):
    return "none" if lib.coons_model_operation(m) == lib.COONS_OP_NONE else "union"


def model_control_bbox(m):
    lo, hi = ffi.new("double[3]"), ffi.new("double[3]")
    lib.coons_model_control_bbox(m, lo, hi)
    return list(lo), list(hi)


def model_morph_count(m):
    return lib.coons_model_morph_count(m)


def model_interfaces(m):
    out = ffi.new("coons_interface **")
    n = ffi.new("size_t *")
    err = new_error()
    check(lib.coons_model_interfaces(m, out, n, err), err)
    try:
        res = []
        for k in range(n[0]):
            it = out[0][k]
            res.append({"body_indices": [it.body[0], it.body[1]],
                        "faces": [_str(lib.coons_body_face_name(it.face[0])),
                                  _str(lib.coons_body_face_name(it.face[1]))],
                        "orientation": it.orientation, "c1_defect": it.c1_defect,
                        "g1_angle": it.g1_angle})
        return res
    finally:
        lib.coons_interfaces_free(out[0])


# ---- bodies ---------------------------------------------------------------

def body_free(b):
    lib.coons_body_free(b)


def body_type(b):
    return _str(lib.coons_body_type_name(lib.coons_body_kind(b)))


def body_at_time(b, t):
    """A new body: morph `b` at time t (free it with body_free)."""
    out = ffi.new("coons_body **")
    err = new_error()
    check(lib.coons_body_at_time(b, t, out, err), err)
    return out[0]


def body_eval(b, q):
    """q: C-contiguous float64 (n, 3) in [0,1] -> (n, 3), in one C call
    (coons_body_eval_points: bitwise coons_body_eval at each point)."""
    n = q.shape[0]
    res = np.empty((n, 3), dtype=np.float64)
    err = new_error()
    check(lib.coons_body_eval_points(b, n, _dp(q), _dp_out(res), ffi.NULL, ffi.NULL, err), err)
    return res


def body_eval_jacobian(b, q):
    """-> points (n, 3), jacobians (n, 3, 3) [row x_r, column q_c], det (n,):
    coons_body_eval_jacobian at each point, in one C call."""
    n = q.shape[0]
    x = np.empty((n, 3), dtype=np.float64)
    jac = np.empty((n, 3, 3), dtype=np.float64)
    det = np.empty(n, dtype=np.float64)
    err = new_error()
    check(lib.coons_body_eval_points(b, n, _dp(q), _dp_out(x), _dp_out(jac), _dp_out(det), err),
          err)
    return x, jac, det


def _dp_out(a):
    return ffi.cast("double *", ffi.from_buffer(a, require_writable=True))


def body_eval_grid(b, u, v, w, threads=0):
    """The grid on `threads` threads (0: every core; byte-identical for any
    count: coons_body_eval_grid_threads)."""
    out = np.empty((len(u), len(v), len(w), 3), dtype=np.float64)
    err = new_error()
    rc = lib.coons_body_eval_grid_threads(b, _dp(u), len(u), _dp(v), len(v), _dp(w), len(w),
                                          _dp_out(out), threads, err)
    check(rc, err)
    return out


def body_control_bbox(b):
    lo, hi = ffi.new("double[3]"), ffi.new("double[3]")
    lib.coons_body_control_bbox(b, lo, hi)
    return list(lo), list(hi)


def body_volume_bounded(b, rel_tol):
    vol, est, n = ffi.new("double *"), ffi.new("double *"), ffi.new("size_t *")
    err = new_error()
    check(lib.coons_body_volume_bounded(b, rel_tol, 0, vol, est, n, err), err)
    return vol[0], est[0]


def body_min_jacobian(b, n):
    det, where = ffi.new("double *"), ffi.new("double[3]")
    err = new_error()
    check(lib.coons_body_min_jacobian(b, n, det, where, err), err)
    return det[0], list(where)


def body_morph_keys(b):
    return lib.coons_body_morph_keys(b)


def body_new_body0(corners, cubic):
    out = ffi.new("coons_body **")
    err = new_error()
    blend = lib.COONS_BLEND_CUBIC if cubic else lib.COONS_BLEND_LINEAR
    check(lib.coons_body_new_body0(ffi.cast("double *", ffi.from_buffer(corners)), blend, out,
                                   err), err)
    return out[0]


def body_new_bezier(points):
    out = ffi.new("coons_body **")
    err = new_error()
    n = ffi.new("size_t[3]", list(points.shape[:3]))
    check(lib.coons_body_new_bezier(ffi.cast("double *", ffi.from_buffer(points)), n, out, err),
          err)
    return out[0]


def body_new_bspline(degree, points, ku, kv, kw, weights):
    out = ffi.new("coons_body **")
    err = new_error()
    n = ffi.new("size_t[3]", list(points.shape[:3]))
    deg = ffi.new("int[3]", list(degree))
    dp = lambda a: ffi.NULL if a is None else ffi.cast("double *", ffi.from_buffer(a))  # noqa: E731
    check(lib.coons_body_new_bspline(deg, dp(points), n, dp(ku), dp(kv), dp(kw), dp(weights),
                                     out, err), err)
    return out[0]


# ---- curves and patches (coons/curve.h, coons/patch.h) ---------------------

def _made(kind, fn, *args):
    out = ffi.new("coons_%s **" % kind)
    err = new_error()
    check(fn(*args, out, err), err)
    return out[0]


def _handles(kind, ptrs):
    return ffi.new("coons_%s *[]" % kind, list(ptrs))


def curve_free(c):
    lib.coons_curve_free(c)


def curve_type(c):
    return _str(lib.coons_curve_type_name(lib.coons_curve_kind(c)))


def curve_new(type, points, closed=False, degree=0, knots=None, weights=None):
    """points: C-contiguous float64 (n, 3); the arrays are checked by the caller."""
    p, n = _dp(points), points.shape[0]
    if type == "line":
        return _made("curve", lib.coons_curve_new_line, p, p + 3)
    if type == "polyline":
        return _made("curve", lib.coons_curve_new_polyline, p, n)
    if type == "bezier":
        return _made("curve", lib.coons_curve_new_bezier, p, n)
    if type == "coons-cubic":
        return _made("curve", lib.coons_curve_new_coons_cubic, p, n, 1 if closed else 0)
    if type == "clamped-cubic":
        return _made("curve", lib.coons_curve_new_clamped_cubic, p, n)
    if type == "bspline":
        return _made("curve", lib.coons_curve_new_bspline, degree, p, n, _dp(knots),
                     _dp(weights))
    raise errors.InvalidError("unknown curve type %r" % (type,))


def curve_new_hermite(points, tangents):
    p, t = _dp(points), _dp(tangents)
    return _made("curve", lib.coons_curve_new_hermite, p, t, p + 3, t + 3)


def curve_eval(c, t, order):
    """t: C-contiguous float64 (n,) in [0,1] -> (n, order + 1, 3): the point
    and its derivatives d/dt up to order (<= 2)."""
    n = t.shape[0]
    res = np.empty((n, order + 1, 3), dtype=np.float64)
    po = ffi.cast("double (*)[3]", ffi.from_buffer(res, require_writable=True))
    f = lib.coons_curve_eval_derivs
    for i in range(n):
        f(c, float(t[i]), order, po + (order + 1) * i)
    return res


def patch_free(p):
    lib.coons_patch_free(p)


def patch_type(p):
    return _str(lib.coons_patch_type_name(lib.coons_patch_kind(p)))


def patch_new_bilinear(corners):
    return _made("patch", lib.coons_patch_new_bilinear, _dp(corners))


def patch_new_ruled(c0, c1):
    return _made("patch", lib.coons_patch_new_ruled, c0, c1)


def _blend(cubic):
    return lib.COONS_BLEND_CUBIC if cubic else lib.COONS_BLEND_LINEAR


_TWISTS = {"zero": "COONS_TWIST_ZERO", "adini": "COONS_TWIST_ADINI",
           "bessel": "COONS_TWIST_BESSEL"}


def patch_new_coons(boundary, cubic):
    return _made("patch", lib.coons_patch_new_coons, _handles("curve", boundary),
                 _blend(cubic), 0.0)


def patch_new_hermite_coons(boundary, cross, twist, twists):
    o = ffi.new("coons_hermite_options *")
    lib.coons_hermite_options_init(o)
    if cross is not None:
        for i, c in enumerate(cross):
            o.cross[i] = c
    if twists is not None:
        o.twist = lib.COONS_TWIST_EXPLICIT
        for i in range(4):
            for r in range(3):
                o.twists[i][r] = float(twists[i, r])
    else:
        o.twist = getattr(lib, _TWISTS[twist])
    return _made("patch", lib.coons_patch_new_hermite_coons, _handles("curve", boundary), o)


def patch_new_bezier(points):
    return _made("patch", lib.coons_patch_new_bezier, _dp(points), points.shape[0],
                 points.shape[1])


def patch_new_bspline(degree, points, ks, kt, weights):
    return _made("patch", lib.coons_patch_new_bspline, degree[0], degree[1], _dp(points),
                 points.shape[0], points.shape[1], _dp(ks), _dp(kt), _dp(weights))


def patch_new_network(rows, columns, s_nodes, t_nodes, twist, cubic):
    o = ffi.new("coons_network_options *")
    lib.coons_network_options_init(o)
    o.s_nodes, o.t_nodes = _dp(s_nodes), _dp(t_nodes)
    o.twist = getattr(lib, _TWISTS[twist])
    o.blend = _blend(cubic)
    return _made("patch", lib.coons_patch_new_network, _handles("curve", rows), len(rows),
                 _handles("curve", columns), len(columns), o)


def patch_eval(p, st, order):
    """st: C-contiguous float64 (n, 2) in [0,1] -> (n, k, 3): the point and,
    with order 1, x_s and x_t; with order 2 also x_ss, x_st, x_tt."""
    n, k = st.shape[0], (1, 3, 6)[order]
    res = np.empty((n, 6, 3), dtype=np.float64)
    po = ffi.cast("double (*)[3]", ffi.from_buffer(res, require_writable=True))
    f = lib.coons_patch_eval_derivs
    for i in range(n):
        f(p, float(st[i, 0]), float(st[i, 1]), order, po + 6 * i)
    return res[:, :k]


def patch_eval_grid(p, s, t):
    out = np.empty((len(s), len(t), 3), dtype=np.float64)
    err = new_error()
    check(lib.coons_patch_eval_grid(p, _dp(s), len(s), _dp(t), len(t),
                                    ffi.cast("double *", ffi.from_buffer(out, require_writable=True)),
                                    err), err)
    return out


def body_new_body1(edges, cubic):
    return _made("body", lib.coons_body_new_body1, _handles("curve", edges), _blend(cubic), 0.0)


def body_new_body2(faces, cubic):
    return _made("body", lib.coons_body_new_body2, _handles("patch", faces), _blend(cubic), 0.0)


_SIDES = {"both": "COONS_SHELL_BOTH", "front": "COONS_SHELL_FRONT", "back": "COONS_SHELL_BACK"}


def body_new_shell(surface, thickness, side):
    return _made("body", lib.coons_body_new_shell, surface, thickness, getattr(lib, _SIDES[side]))


def body_new_morph(keys, at, smooth, t):
    path = lib.COONS_MORPH_SMOOTH if smooth else lib.COONS_MORPH_LINEAR
    return _made("body", lib.coons_body_new_morph, _handles("body", keys), len(keys), _dp(at),
                 path, t)


# ---- triangle meshes ------------------------------------------------------

def _sample_options(tolerance, resolution, max_triangles):
    so = ffi.new("coons_sample_options *")
    lib.coons_sample_options_init(so)
    so.tolerance = tolerance
    so.resolution = resolution
    so.max_triangles = max_triangles
    so.threads = min(os.cpu_count() or 1, 1024)  # the same mesh on any count
    if resolution:
        so.flags |= lib.COONS_SAMPLE_UNMEASURED  # as coons2stl: nothing to measure
    return so


def model_solidify(m, body, tolerance, resolution, max_triangles, repair, threads, progress):
    """The solid coons2stl -o writes (tools/coons2stl/solid.c): body < 0 for all."""
    so = _sample_options(tolerance, resolution, max_triangles)
    co = ffi.new("coons_csg_options *")
    lib.coons_csg_options_init(co)
    co.repair = 1 if repair else 0
    co.threads = threads
    cb = None
    if progress is not None:
        def _cb(userdata, stage, fraction):
            try:
                progress(_str(stage), fraction)
            except Exception:
                pass
        cb = ffi.callback("void(void *, const char *, double)", _cb)
        co.progress = cb
    rep = ffi.new("coons_csg_report *")
    lib.coons_csg_report_init(rep)
    out = ffi.new("coons_mesh **")
    err = new_error()
    if body < 0:
        rc = lib.coons_model_solidify(m, so, co, out, rep, err)
    else:
        rc = lib.coons_model_solidify_body(m, body, so, co, out, rep, err)
    if rc != lib.COONS_OK:
        lib.coons_mesh_free(out[0])
        check(rc, err)
    return out[0]


def mesh_free(p):
    lib.coons_mesh_free(p)


def mesh_arrays(p):
    nv = lib.coons_mesh_vertex_count(p)
    nt = lib.coons_mesh_triangle_count(p)
    v = np.frombuffer(ffi.buffer(lib.coons_mesh_vertices(p), 24 * nv), dtype=np.float64)
    t = np.frombuffer(ffi.buffer(lib.coons_mesh_triangles(p), 12 * nt), dtype=np.uint32)
    return v.reshape(nv, 3).copy(), t.reshape(nt, 3).astype(np.int64)


def mesh_parts(p):
    res = []
    a, b, c, d = (ffi.new("size_t *") for _ in range(4))
    for i in range(lib.coons_mesh_part_count(p)):
        lib.coons_mesh_part_range(p, i, a, b, c, d)
        res.append((_str(lib.coons_mesh_part_name(p, i)), a[0], b[0], c[0], d[0]))
    return res


def format_of(path, name):
    f = ffi.new("coons_format *")
    err = new_error()
    if name:
        check(lib.coons_format_from_name(_enc(name), f, err), err)
    else:
        check(lib.coons_format_from_path(_enc(path), f, err), err)
    kind = lib.coons_format_kind(f[0])
    return int(f[0]), ("volume" if kind == lib.COONS_MESH_KIND_VOLUME else
                       "solid" if kind == lib.COONS_MESH_KIND_SOLID else "surface")


def format_is_stl(fmt):
    return fmt in (lib.COONS_FORMAT_STL_BINARY, lib.COONS_FORMAT_STL_ASCII)


def format_is_scad(fmt):
    return fmt == lib.COONS_FORMAT_SCAD


def _write_options(name, units, protect):
    """The options and the C strings they point to (keep both alive)."""
    keep = [ffi.new("char[]", _enc(s)) if s else ffi.NULL for s in (name, units, protect)]
    o = ffi.new("coons_write_options *")
    lib.coons_write_options_init(o)
    o.name, o.units, o.protect_path = keep
    return o, keep


def model_write_solid(m, path, fmt, name, units, protect):
    """STEP, IGES or BREP solids of every body (coons_model_write_solid)."""
    o, keep = _write_options(name, units, protect)
    err = new_error()
    check(lib.coons_model_write_solid(m, _enc(path), fmt, o, err), err)
    del keep


def solid_formats_available():
    return bool(lib.coons_solid_formats_available())


def stl_rounding_crossings(p):
    """(float32 crossing pairs, double crossing pairs), as coons2stl checks
    an STL before writing it (tools/coons2stl/output.c); None when there is
    no exact test (no CGAL) or the mesh does not fit float32."""
    if not lib.coons_csg_is_available():
        return None
    p32, p64 = ffi.new("size_t *"), ffi.new("size_t *")
    err = new_error()
    rc = lib.coons_mesh_count_self_intersections_float(p, p32, err)
    if rc == lib.COONS_OK and p32[0]:
        rc = lib.coons_mesh_count_self_intersections(p, p64, err)
    if rc == lib.COONS_E_LIMIT:
        return None
    check(rc, err)
    return p32[0], p64[0]


def mesh_write(p, path, fmt, name, units, protect):
    o, keep = _write_options(name, units, protect)
    err = new_error()
    check(lib.coons_mesh_write(p, _enc(path), fmt, o, err), err)
    del keep


def model_write_scad_animation(m, body, tolerance, resolution, max_triangles, path, name, units,
                               protect):
    so = _sample_options(tolerance, resolution, max_triangles)
    o, keep = _write_options(name, units, protect)
    err = new_error()
    check(lib.coons_model_write_scad_animation(m, body, so, _enc(path), o, err), err)
    del keep


# ---- volume meshes --------------------------------------------------------

ELEMENTS = {"hex8": 8, "hex20": 20, "hex27": 27}


def volume_mesh(m, b, name, element, resolution, tolerance, max_cells):
    vo = ffi.new("coons_volume_options *")
    lib.coons_volume_options_init(vo)
    vo.element = ELEMENTS[element]
    for d in range(3):
        vo.resolution[d] = resolution[d]
    vo.tolerance = tolerance
    vo.max_cells = max_cells
    vo.threads = min(os.cpu_count() or 1, 1024)  # the same mesh on any count
    out = ffi.new("coons_volume_mesh **")
    err = new_error()
    if b is None:
        rc = lib.coons_model_volume_mesh(m, vo, out, err)
    else:
        rc = lib.coons_body_volume_mesh(b, vo, _enc(name), out, err)
    if rc != lib.COONS_OK:
        lib.coons_volume_mesh_free(out[0])
        check(rc, err)
    return out[0]


def volume_mesh_free(p):
    lib.coons_volume_mesh_free(p)


def volume_mesh_arrays(p):
    """points (n, 3), cells (m, k) in the library's (Gmsh) node order, cell
    parts (m,), part names, node fields, cell fields."""
    nn = lib.coons_volume_mesh_node_count(p)
    nc = lib.coons_volume_mesh_cell_count(p)
    k = lib.coons_volume_mesh_nodes_per_cell(p)
    pts = np.frombuffer(ffi.buffer(lib.coons_volume_mesh_nodes(p), 24 * nn),
                        dtype=np.float64).reshape(nn, 3).copy()
    cells = np.frombuffer(ffi.buffer(lib.coons_volume_mesh_cells(p), 4 * nc * k),
                          dtype=np.uint32).reshape(nc, k).astype(np.int64)
    parts = np.frombuffer(ffi.buffer(lib.coons_volume_mesh_cell_parts(p), 4 * nc),
                          dtype=np.uint32).astype(np.int64)
    names = [_str(lib.coons_volume_mesh_part_name(p, i))
             for i in range(lib.coons_volume_mesh_part_count(p))]
    fields = []
    for loc, count in ((lib.COONS_FIELD_NODE, nn), (lib.COONS_FIELD_CELL, nc)):
        d = {}
        t = ffi.new("coons_field_type *")
        vals = ffi.new("void **")
        for i in range(lib.coons_volume_mesh_field_count(p, loc)):
            name = _str(lib.coons_volume_mesh_field(p, loc, i, t, vals))
            if t[0] == lib.COONS_FIELD_FLOAT64:
                a = np.frombuffer(ffi.buffer(vals[0], 8 * count), dtype=np.float64)
            else:
                a = np.frombuffer(ffi.buffer(vals[0], 4 * count), dtype=np.int32)
            d[name] = a.copy()
        fields.append(d)
    return pts, cells, parts, names, fields[0], fields[1]


def volume_mesh_cell_shapes(p, which):
    """(shape, nodes) of each cell index in `which`, by
    coons_volume_mesh_cell_shape(): shape 0 hexahedron, 1 wedge, 2 pyramid,
    nodes in the library's (Gmsh) order (6 for a wedge, 5 for a pyramid)."""
    shape = ffi.new("coons_cell_shape *")
    nodes = ffi.new("uint32_t[]", lib.COONS_VOLUME_CELL_NODES_MAX)
    count = ffi.new("size_t *")
    err = new_error()
    out = []
    for i in which:
        check(lib.coons_volume_mesh_cell_shape(p, int(i), shape, nodes, count, err), err)
        out.append((int(shape[0]), list(nodes[0:count[0]])))
    return out


def volume_mesh_inverted(p):
    """(part name, inverted cells, worst value, worst uvw) of the first part
    with inverted cells, or None (coons2stl refuses such a mesh)."""
    for i in range(lib.coons_volume_mesh_part_count(p)):
        q = ffi.new("coons_volume_quality *")
        lib.coons_volume_quality_init(q)
        if lib.coons_volume_mesh_quality(p, i, q, ffi.NULL) != lib.COONS_OK or not q.inverted:
            continue
        return (_str(lib.coons_volume_mesh_part_name(p, i)), q.inverted, q.min_scaled_jacobian,
                list(q.worst_uvw))
    return None


def volume_mesh_write(p, path, fmt, name, units, protect):
    o, keep = _write_options(name, units, protect)
    err = new_error()
    check(lib.coons_volume_mesh_write(p, _enc(path), fmt, o, err), err)
    del keep
