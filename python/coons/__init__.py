# SPDX-License-Identifier: GPL-3.0-or-later
"""libcoons from Python: Coons bodies (seed 000) loaded from model files or
built from numpy arrays, evaluated, meshed into closed triangle meshes and
volume-meshed into hexahedra for meshio, PyVista, CalculiX and FEniCS.

    import coons
    m = coons.load("examples/nail.json")
    x = m.bodies[0].eval([[0.5, 0.5, 0.5]])     # (1, 3)
    m.mesh().vertices                            # (n, 3)
    m.volume_mesh("hex20").to_meshio().write("nail.vtu")

See docs/python.md.
"""
from . import _features, _lib
from .builders import (bezier, bezier_surface, bezier_volume, bilinear, body, body0, body1, body2,
                       bspline, bspline_surface, bspline_volume, clamped_cubic, coons,
                       coons_cubic, coons_patch, hermite, hermite_coons, line, morph, network,
                       polyline, ruled, shell)
from .errors import (ClosedError, DomainError, Error, FileError, GeometryError, InvalidError,
                     LimitError, LoadError, LoadGeometryError, LoadLimitError, UnsupportedError)
from .mesh import Mesh, VolumeMesh
from .model import Body, Model, load, loads
from .shapes import Curve, Patch

__version__ = _lib.version()


def features():
    """Which optional parts this build of libcoons has: {"openmesh": bool,
    "cgal": bool (repair and union), "lib3mf": bool (3MF output), "occt": bool
    (exact STEP, IGES and BREP solids)}. Calls that
    need a missing part raise UnsupportedError naming it."""
    return {"openmesh": _features.OPENMESH, "cgal": _features.CGAL and _lib.csg_available(),
            "lib3mf": _features.LIB3MF, "occt": _lib.solid_formats_available()}


__all__ = ["Body", "ClosedError", "Curve", "DomainError", "Error", "FileError",
           "GeometryError", "InvalidError", "LimitError", "LoadError", "LoadGeometryError",
           "LoadLimitError", "Mesh", "Model", "Patch", "UnsupportedError", "VolumeMesh",
           "bezier", "bezier_surface", "bezier_volume", "bilinear", "body", "body0", "body1",
           "body2", "bspline", "bspline_surface", "bspline_volume", "clamped_cubic", "coons",
           "coons_cubic", "coons_patch", "features", "hermite", "hermite_coons", "line", "load",
           "loads", "morph", "network", "polyline", "ruled", "shell"]
