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
from .builders import bezier_volume, body, body0, bspline_volume
from .errors import (ClosedError, DomainError, Error, FileError, GeometryError, InvalidError,
                     LimitError, LoadError, LoadGeometryError, LoadLimitError, UnsupportedError)
from .mesh import Mesh, VolumeMesh
from .model import Body, Model, load, loads

__version__ = _lib.version()


def features():
    """Which optional parts this build of libcoons has: {"openmesh": bool,
    "cgal": bool (repair and union), "lib3mf": bool (3MF output)}. Calls that
    need a missing part raise UnsupportedError naming it."""
    return {"openmesh": _features.OPENMESH, "cgal": _features.CGAL and _lib.csg_available(),
            "lib3mf": _features.LIB3MF}


__all__ = ["Body", "ClosedError", "DomainError", "Error", "FileError", "GeometryError",
           "InvalidError", "LimitError", "LoadError", "LoadGeometryError", "LoadLimitError",
           "Mesh", "Model", "UnsupportedError", "VolumeMesh", "bezier_volume", "body", "body0",
           "bspline_volume", "features", "load", "loads"]
