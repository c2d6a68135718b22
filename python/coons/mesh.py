# SPDX-License-Identifier: GPL-3.0-or-later
"""Mesh (a triangle mesh, coons/mesh.h) and VolumeMesh (hexahedra,
coons/volume.h) as numpy arrays, written by the library's writers
(coons/io.h) exactly as coons2stl writes them."""
import os

import numpy as np

from . import _lib
from ._handle import Handle
from .errors import GeometryError

#: Library (Gmsh) node order -> VTK node order (VTK_QUADRATIC_HEXAHEDRON,
#: VTK_TRIQUADRATIC_HEXAHEDRON), from coons/volume.h's table: VTK lists the
#: edges 01 12 23 30 45 56 67 74 04 15 26 37, then the faces r=0, r=1,
#: s=0, s=1, t=0, t=1 and the centre.
_VTK_ORDER = {
    8: list(range(8)),
    20: list(range(8)) + [8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15],
    27: list(range(8)) + [8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15,
                          22, 23, 21, 24, 20, 25, 26],
}
_MESHIO_TYPE = {8: "hexahedron", 20: "hexahedron20", 27: "hexahedron27"}
_VTK_TYPE = {8: 12, 20: 25, 27: 29, 6: 13, 5: 14}
#: Gmsh prism order (coons_volume_mesh_cell_shape()) -> VTK wedge order:
#: VTK's triangle 0 1 2 faces away from 3 4 5, Gmsh's towards it.
_VTK_WEDGE = [0, 2, 1, 3, 5, 4]


def _cell_blocks(ptr, cells):
    """The cells as the writers write them: runs of one meshio type, in the
    mesh's order, each (type, (m, k) int64 VTK order). A hex8 cell whose
    corners repeat a node is what coons_volume_mesh_cell_shape() says (a
    wedge, a pyramid, or a hexahedron with repeated nodes)."""
    k = cells.shape[1]
    kind = np.zeros(len(cells), dtype=np.int8)  # 0 hexahedron, 1 wedge, 2 pyramid
    shaped = {}
    if len(cells):
        c = np.sort(cells[:, :8], axis=1)
        repeated = np.flatnonzero((c[:, 1:] == c[:, :-1]).any(axis=1))
        for i, (sh, nodes) in zip(repeated, _lib.volume_mesh_cell_shapes(ptr, repeated)):
            kind[i] = sh
            if sh == 1:
                shaped[i] = [nodes[j] for j in _VTK_WEDGE]
            elif sh == 2:
                shaped[i] = nodes
    hexa = cells[:, _VTK_ORDER[k]]
    blocks = []
    start = 0
    edges = np.flatnonzero(kind[1:] != kind[:-1]) + 1
    for end in list(edges) + [len(cells)]:
        if end == start:
            continue
        sh = int(kind[start])
        if sh == 0:
            data = np.ascontiguousarray(hexa[start:end])
            name = _MESHIO_TYPE[k]
        else:
            data = np.array([shaped[i] for i in range(start, end)], dtype=np.int64)
            name = "wedge" if sh == 1 else "pyramid"
        blocks.append((name, data))
        start = end
    return blocks


def output_name(path):
    """"dir/part.stl" -> "part": the model name coons2stl gives a file."""
    base = os.path.basename(path)
    dot = base.rfind(".")
    return base[:dot] if dot > 0 else base


class Mesh:
    """A triangle mesh: ``vertices`` (n, 3) float64, ``triangles`` (m, 3)
    int64 (counter-clockwise seen from outside), ``parts`` (names)."""

    @classmethod
    def _wrap(cls, ptr):
        self = cls.__new__(cls)
        self._h = Handle(ptr, _lib.mesh_free, "mesh")
        self.vertices, self.triangles = _lib.mesh_arrays(ptr)
        self._parts = _lib.mesh_parts(ptr)
        return self

    @property
    def parts(self):
        """Part names, in order."""
        return [p[0] for p in self._parts]

    def part(self, i):
        """(vertices, triangles) of part i, triangles indexing its vertices."""
        _, t0, tn, v0, vn = self._parts[i]
        return self.vertices[v0:v0 + vn], self.triangles[t0:t0 + tn] - v0

    def volume(self):
        """Enclosed volume (divergence theorem over the triangles)."""
        v = self.vertices[self.triangles]
        return float(np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6.0)

    def _refuse_stl_rounding(self, path):
        with self._h.use() as p:
            c = _lib.stl_rounding_crossings(p)
        if c and c[0] and not c[1]:
            raise GeometryError(
                "%s: rounding the coordinates to float32, as STL stores them, would make %d "
                "pair%s of triangles cross (in double precision none do); nothing was written. "
                "Write OFF or SCAD (double precision), or try a coarser tolerance"
                % (path, c[0], "" if c[0] == 1 else "s"))

    def write(self, path, format=None, name=None, units=None, _protect=None):
        """Writes the mesh (STL, OFF, SCAD, 3MF; the format from the extension
        unless `format` names one), atomically. `name` defaults to the file's
        base name, as coons2stl names it."""
        path = os.fspath(path)
        fmt, kind = _lib.format_of(path, format)
        with self._h.use() as p:
            _lib.mesh_write(p, path, fmt, name if name is not None else output_name(path),
                            units, _protect)

    def close(self):
        self._h.close()

    def __repr__(self):
        return "<coons.Mesh %d vertices, %d triangles>" % (len(self.vertices),
                                                          len(self.triangles))


class VolumeMesh:
    """A hexahedral volume mesh: ``points`` (n, 3) float64; ``cells`` a dict
    from the meshio cell type ("hexahedron", "hexahedron20", "hexahedron27";
    "wedge" and "pyramid" where a hex8 body collapses, as the writers write
    them: coons_volume_mesh_cell_shape()) to an (m, k) int64 array in VTK
    node order, each type's cells in the mesh's order; ``blocks`` the same
    cells as runs of one type in the mesh's order, (type, array) each (the
    blocks meshio reads from the .vtu); ``point_data`` (u, v, w, det_j: (n,)
    each); ``cell_data`` (body: (m,) int, the body index; scaled_jacobian:
    (m,)) in the mesh's order; ``parts`` (body names)."""

    @classmethod
    def _wrap(cls, ptr):
        self = cls.__new__(cls)
        self._h = Handle(ptr, _lib.volume_mesh_free, "volume mesh")
        pts, cells, parts, names, nodef, cellf = _lib.volume_mesh_arrays(ptr)
        k = cells.shape[1]
        self.points = pts
        self.element = {8: "hex8", 20: "hex20", 27: "hex27"}[k]
        self.blocks = _cell_blocks(ptr, cells)
        self.cells = {}
        for t, c in self.blocks:
            self.cells.setdefault(t, []).append(c)
        self.cells = {t: c[0] if len(c) == 1 else np.concatenate(c)
                      for t, c in self.cells.items()}
        if not self.cells:
            self.cells = {_MESHIO_TYPE[k]: np.zeros((0, k), dtype=np.int64)}
        self.point_data = nodef
        self.cell_data = {"body": parts}
        self.cell_data.update(cellf)
        self.parts = names
        return self

    def to_meshio(self):
        """A meshio.Mesh of the same points, cells and data."""
        import meshio
        ends = np.cumsum([len(c) for _, c in self.blocks])[:-1]
        return meshio.Mesh(self.points, list(self.blocks),
                           point_data=dict(self.point_data),
                           cell_data={k: np.split(np.asarray(v), ends)
                                      for k, v in self.cell_data.items()})

    def to_pyvista(self):
        """A pyvista.UnstructuredGrid (needs PyVista)."""
        import pyvista
        conn = [np.hstack([np.full((len(c), 1), c.shape[1], dtype=np.int64), c]).ravel()
                for _, c in self.blocks]
        types = [np.full(len(c), _VTK_TYPE[c.shape[1]], dtype=np.uint8) for _, c in self.blocks]
        grid = pyvista.UnstructuredGrid(np.concatenate(conn) if conn else np.zeros(0, np.int64),
                                        np.concatenate(types) if types else np.zeros(0, np.uint8),
                                        self.points)
        for n, v in self.point_data.items():
            grid.point_data[n] = v
        for n, v in self.cell_data.items():
            grid.cell_data[n] = v
        return grid

    def _refuse_inverted(self, path):
        with self._h.use() as p:
            bad = _lib.volume_mesh_inverted(p)
        if bad:
            name, n, worst, uvw = bad
            raise GeometryError(
                "%s: body '%s' has %d inverted cell%s (scaled Jacobian <= 0; the worst, %.6g, "
                "at (u, v, w) = (%.6g, %.6g, %.6g)): the body folds there; nothing was written "
                "(allow_inverted=True writes it anyway)"
                % (path, name, n, "" if n == 1 else "s", worst, uvw[0], uvw[1], uvw[2]))

    def write(self, path, format=None, name=None, units=None, _protect=None):
        """Writes the volume mesh (.vtu, .msh, .inp, .vtk; or `format`) with
        the library's writers, atomically."""
        path = os.fspath(path)
        fmt, kind = _lib.format_of(path, format)
        with self._h.use() as p:
            _lib.volume_mesh_write(p, path, fmt, name if name is not None else output_name(path),
                                   units, _protect)

    def close(self):
        self._h.close()

    def __repr__(self):
        return "<coons.VolumeMesh %d points, %s>" % (
            len(self.points), ", ".join("%d %s" % (len(c), t) for t, c in self.cells.items()))
