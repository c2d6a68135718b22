# SPDX-License-Identifier: GPL-3.0-or-later
"""Model and Body: a loaded model file (coons-model(5)) and its bodies,
evaluated into numpy arrays (coons/body.h), meshed (coons/csg.h: the solid
coons2stl -o writes) and volume-meshed (coons/volume.h)."""
import contextlib
import json
import os

import numpy as np

from . import _args, _info, _lib
from ._handle import Handle
from .errors import ClosedError, GeometryError, InvalidError
from .mesh import Mesh, VolumeMesh, output_name


def _threads():
    return os.cpu_count() or 1


class Body:
    """One body, parametrised over (u, v, w) in [0, 1]^3.

    A body of a model keeps the model alive; once the model is closed its
    calls raise :class:`coons.ClosedError`. Bodies made by the builders
    (:func:`coons.body0`, ...) own their C object and carry their JSON
    description (:meth:`to_dict`)."""

    def __init__(self, handle, index=None, name=None, spec=None, model=None):
        self._h = handle          # the model's handle (index set) or the body's own
        self._index = index
        self._name = name
        self._spec = spec
        self._model = model

    @contextlib.contextmanager
    def _ptr(self, time=None):
        with self._h.use() as p:
            b = _lib.model_body(p, self._index) if self._index is not None else p
            if time is None:
                yield b
                return
            t = _lib.body_at_time(b, time)
            try:
                yield t
            finally:
                _lib.body_free(t)

    @property
    def name(self):
        """The body's "name", or "body<i>"."""
        return self._name

    @property
    def type(self):
        """The model format's "type" of the body ("body0", "bezier-volume", ...)."""
        with self._ptr() as b:
            return _lib.body_type(b)

    @property
    def model(self):
        """The Model this body belongs to, or None for a standalone body."""
        return self._model

    def eval(self, uvw, time=None):
        """Points of the body: uvw (n, 3) or (3,) -> float64 (n, 3) or (3,),
        the same doubles as ``coons2stl --eval``. ``time`` (in [0, 1]) takes a
        morph body at that time."""
        q, single = _args.params(uvw)
        with self._ptr(_args.time(time)) as b:
            x = _lib.body_eval(b, q)
        return x[0] if single else x

    def jacobian(self, uvw, time=None):
        """Jacobians: uvw (n, 3) or (3,) -> (n, 3, 3) or (3, 3), columns
        d/du, d/dv, d/dw (J[..., r, c] = d x_r / d q_c)."""
        q, single = _args.params(uvw)
        with self._ptr(_args.time(time)) as b:
            _, jac, _ = _lib.body_eval_jacobian(b, q)
        return jac[0] if single else jac

    def det_j(self, uvw, time=None):
        """det J: uvw (n, 3) or (3,) -> (n,) or a float."""
        q, single = _args.params(uvw)
        with self._ptr(_args.time(time)) as b:
            _, _, det = _lib.body_eval_jacobian(b, q)
        return float(det[0]) if single else det

    def grid(self, u, v, w, time=None, threads=None):
        """Points on the tensor grid of 1-D parameter arrays: ->
        (len(u), len(v), len(w), 3); [i, j, k] is the point at (u[i], v[j], w[k])
        (equal to eval within a few ulp: the grid reuses basis values).
        ``threads``: None or 0 every core, else that many; the result is the
        same, byte for byte, for every count."""
        u, v, w = (_args.vector(a, n) for a, n in ((u, "u"), (v, "v"), (w, "w")))
        nthreads = 0 if threads is None else _args.count(threads, "threads", 0, 1024)
        if len(u) * len(v) * len(w) > _args.MAX_POINTS:
            raise _args.LimitError("grid: %d points, more than %d in one call"
                                   % (len(u) * len(v) * len(w), _args.MAX_POINTS))
        with self._ptr(_args.time(time)) as b:
            return _lib.body_eval_grid(b, u, v, w, nthreads)

    def volume(self, rel_tol=1e-9, time=None):
        """The body's signed volume, the integral of det J over [0, 1]^3, to
        the relative accuracy rel_tol (negative for a left-handed body)."""
        rel = _args.positive(rel_tol, "rel_tol")
        with self._ptr(_args.time(time)) as b:
            return _lib.body_volume_bounded(b, rel)[0]

    def control_bbox(self):
        """(lo, hi) of the body's control points, each (3,)."""
        with self._ptr() as b:
            lo, hi = _lib.body_control_bbox(b)
        return np.array(lo), np.array(hi)

    def mesh(self, tolerance=None, resolution=None, repair=True, max_triangles=0, progress=None):
        """This body's closed boundary mesh, as ``coons2stl --body NAME -o``
        writes it (repaired where it crosses itself, when CGAL is built)."""
        if self._index is None:
            return self._standalone_model().mesh(tolerance, resolution, repair, max_triangles,
                                                 progress)
        return self._model._solid(self._index, tolerance, resolution, repair, max_triangles,
                                  progress)

    def volume_mesh(self, element="hex8", resolution=None, tolerance=None, max_cells=0):
        """This body's hexahedral volume mesh (``coons2stl --body NAME -o X.vtu``)."""
        if self._index is None:
            return self._standalone_model().volume_mesh(element, resolution, tolerance, max_cells)
        return self._model._volume(self._index, element, resolution, tolerance, max_cells)

    def to_dict(self):
        """The body's JSON description (model format), for builder bodies."""
        if self._spec is None:
            raise InvalidError("body '%s' has no JSON description of its own (it was loaded "
                               "from a model: use Model.to_json())" % self._name)
        return json.loads(json.dumps(self._spec))

    def _standalone_model(self):
        return Model([self])

    def close(self):
        """Frees a standalone body (a model's bodies close with their model)."""
        if self._index is None:
            self._h.close()

    def __repr__(self):
        return "<coons.Body %r>" % (self._name,)


class Model:
    """A model: its bodies, units, tolerance and operation.

    ``Model(bodies, units="mm", tolerance=None, operation="union")`` builds one
    from builder bodies (:func:`coons.body0`, ...) or JSON body objects
    (dicts); :func:`coons.load` and :func:`coons.loads` read one.
    Use as a context manager or call :meth:`close` to free it early."""

    def __init__(self, bodies, units="mm", tolerance=None, operation="union", name="model"):
        doc = {"coons": 1, "units": units}
        if tolerance is not None:
            doc["tolerance"] = _args.positive(tolerance, "tolerance")
        if operation not in ("union", "none"):
            raise InvalidError("operation: expected 'union' or 'none', got %r" % (operation,))
        doc["operation"] = operation
        specs = []
        for b in bodies:
            specs.append(b.to_dict() if isinstance(b, Body) else dict(b))
        if not specs:
            raise InvalidError("a model needs at least one body")
        doc["bodies"] = specs
        text = json.dumps(doc, indent=1)
        self._init(_lib.model_load_memory(text.encode("utf-8"), name, {}), text, None)

    @classmethod
    def _wrap(cls, ptr, text, path):
        self = cls.__new__(cls)
        self._init(ptr, text, path)
        return self

    def _init(self, ptr, text, path):
        self._h = Handle(ptr, _lib.model_free, "model")
        self._text = text
        self._path = path
        with self._h.use() as m:
            n = _lib.model_body_count(m)
            names = [_lib.model_body_name(m, i) for i in range(n)]
        self._bodies = tuple(Body(self._h, i, names[i], None, self) for i in range(n))

    # ---- access ----
    @property
    def bodies(self):
        """The bodies, by position (a tuple of Body)."""
        return self._bodies

    def body(self, name):
        """The body named `name` (KeyError if none)."""
        with self._h.use() as m:
            i = _lib.model_find_body(m, name)
        if i < 0:
            raise KeyError(name)
        return self._bodies[i]

    @property
    def units(self):
        with self._h.use() as m:
            return _lib.model_units(m)

    @property
    def tolerance(self):
        """The model's "tolerance", or 1/1000 of its control box diagonal."""
        with self._h.use() as m:
            return _lib.model_tolerance(m)

    @property
    def operation(self):
        with self._h.use() as m:
            return _lib.model_operation(m)

    @property
    def path(self):
        """The file the model was loaded from, or None."""
        return self._path

    @property
    def closed(self):
        return self._h.closed

    def info(self):
        """A dict with the main fields of ``coons2stl --info``: units,
        tolerance, operation, control_bbox, per body index, name, type,
        bbox, control_bbox, volume, volume_error, min_det_jacobian(_at),
        body_count, total_volume and interfaces (not the sampled meshes'
        checks nor the solid's report)."""
        with self._h.use() as m:
            return _info.model_info(m)

    def to_json(self):
        """A model file (JSON text) that coons2stl reads as this model."""
        if self._h.closed:
            raise ClosedError("the model is closed")
        return self._text

    # ---- meshes ----
    def _solid(self, body, tolerance, resolution, repair, max_triangles, progress):
        with self._h.use() as m:
            tol = _args.positive(tolerance, "tolerance") or _lib.model_tolerance(m)
            res = 0 if resolution is None else _args.count(resolution, "resolution", 1, 1 << 20)
            mt = _args.count(max_triangles, "max_triangles", 0, 1 << 62)
            p = _lib.model_solidify(m, body, tol, res, mt, repair, _threads(), progress)
        return Mesh._wrap(p)

    def mesh(self, tolerance=None, resolution=None, repair=True, max_triangles=0, progress=None):
        """The solid ``coons2stl MODEL -o`` writes: every body sampled to
        `tolerance` (default: the model's) or on a uniform lattice of
        `resolution` intervals, repaired and united as the model's operation
        says (the union needs CGAL: without it, UnsupportedError). ->
        Mesh (.vertices (n, 3) float64, .triangles (m, 3) int64, outward).
        progress(stage, fraction) is called from this thread."""
        return self._solid(-1, tolerance, resolution, repair, max_triangles, progress)

    def _volume(self, body, element, resolution, tolerance, max_cells):
        if element not in _lib.ELEMENTS:
            raise InvalidError("element: expected hex8, hex20 or hex27, got %r" % (element,))
        res = _args.resolution3(resolution)
        mc = _args.count(max_cells, "max_cells", 0, 1 << 62)
        with self._h.use() as m:
            tol = _args.positive(tolerance, "tolerance") or _lib.model_tolerance(m)
            if body is None:
                p = _lib.volume_mesh(m, None, None, element, res, tol, mc)
            else:
                p = _lib.volume_mesh(m, _lib.model_body(m, body), self._bodies[body].name,
                                     element, res, tol, mc)
        return VolumeMesh._wrap(p)

    def volume_mesh(self, element="hex8", resolution=None, tolerance=None, max_cells=0):
        """Hexahedral volume mesh of every body on its (u, v, w) lattice, as
        ``coons2stl MODEL -o X.vtu`` makes it: element "hex8", "hex20" or
        "hex27"; resolution None (the lattice the boundary sampler picks),
        N or (NU, NV, NW). -> VolumeMesh."""
        return self._volume(None, element, resolution, tolerance, max_cells)

    def write(self, path, format=None, body=None, tolerance=None, resolution=None,
              element="hex8", allow_inverted=False, repair=True, max_triangles=0,
              progress=None):
        """Writes exactly what ``coons2stl MODEL -o PATH`` writes (with
        ``-f FORMAT``, ``--body``, ``-t``, ``--resolution``, ``--element``,
        ``--allow-inverted``, ``--no-repair`` as the keywords say). The
        format comes from the extension unless `format` names one; volume
        formats write the volume mesh; STEP, IGES and BREP (``.step``,
        ``.stp``, ``.igs``, ``.iges``, ``.brep``, ``format="step-ap242"``) the
        exact solids of every body, when the library has Open CASCADE
        (``features()["occt"]``). A model file is never overwritten."""
        path = os.fspath(path)
        fmt, kind = _lib.format_of(path, format)
        index = None if body is None else self._index_of(body)
        name = output_name(path)
        protect = self._path
        if kind == "solid":  # STEP, IGES, BREP: every body, exact (coons/brep.h)
            if index is not None:
                raise InvalidError("body=: STEP, IGES and BREP files hold every body (the "
                                   "model's \"operation\" decides their union)")
            with self._h.use() as m:
                _lib.model_write_solid(m, path, fmt, name, self.units, protect)
            return
        if kind == "volume":
            vm = self._volume(index, element, resolution, tolerance, max_cells=0)
            try:
                if not allow_inverted:
                    vm._refuse_inverted(path)
                vm.write(path, format=format, name=name, units=self.units, _protect=protect)
            finally:
                vm.close()
            return
        if resolution is not None and not isinstance(resolution, int):
            resolution = tuple(resolution)[0]  # coons2stl: the first of NU,NV,NW
        if _lib.format_is_scad(fmt):
            with self._h.use() as m:
                morphs = _lib.model_morph_count(m)
            if morphs:
                with self._h.use() as m:
                    tol = _args.positive(tolerance, "tolerance") or _lib.model_tolerance(m)
                    res = 0 if resolution is None else _args.count(resolution, "resolution", 1)
                    _lib.model_write_scad_animation(m, -1 if index is None else index, tol, res,
                                                    max_triangles, path, name, self.units,
                                                    protect)
                return
        mesh = self._solid(-1 if index is None else index, tolerance, resolution, repair,
                           max_triangles, progress)
        try:
            if _lib.format_is_stl(fmt):
                mesh._refuse_stl_rounding(path)
            mesh.write(path, format=format, name=name, units=self.units, _protect=protect)
        finally:
            mesh.close()

    def _index_of(self, body):
        if isinstance(body, str):
            return self._bodies.index(self.body(body))
        return _args.count(body, "body", 0, len(self._bodies) - 1)

    def close(self):
        """Frees the model; its bodies' calls then raise ClosedError."""
        self._h.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __repr__(self):
        return "<coons.Model %d bodies%s>" % (len(self._bodies), " closed" if self.closed else "")


def load(path, **limits):
    """Loads a model file -> Model. Keywords max_bytes, max_values,
    max_depth, max_points raise the loader's limits (coons2stl --max-*).
    Raises LoadError (.file .line .column .path) on a bad model."""
    path = os.fspath(path)
    p = _lib.model_load_file(path, limits)
    try:
        with open(path, "rb") as f:
            text = f.read().decode("utf-8")
    except Exception:
        _lib.model_free(p)
        raise
    return Model._wrap(p, text, path)


def loads(json_text, name="model", **limits):
    """Loads a model from JSON text (str or bytes); `name` is the file name
    in error messages."""
    data = json_text.encode("utf-8") if isinstance(json_text, str) else bytes(json_text)
    p = _lib.model_load_memory(data, name, limits)
    return Model._wrap(p, data.decode("utf-8"), None)


__all__ = ["Body", "Model", "load", "loads", "GeometryError"]
