# SPDX-License-Identifier: GPL-3.0-or-later
"""Model.volume_mesh() equals the CLI's .vtu after meshio reads both
(points, cells in VTK order, point and cell data), for each element;
Model.write() of volume formats writes the CLI's bytes. (Models whose
bodies collapse, e.g. nail.json, are left out of the .vtu comparison: the
VTU writer turns collapsed hex8 cells into wedges and pyramids, which
VolumeMesh.cells keeps as hexahedra with repeated nodes.)"""
import filecmp
import os

import meshio
import numpy as np
import pytest

import coons
from conftest import example, run_cli


@pytest.mark.parametrize("element", ["hex8", "hex20", "hex27"])
@pytest.mark.parametrize("name", ["thick-cylinder-distorted.json", "lattice-ring.json",
                                  "volume-nurbs.json"])
def test_volume_mesh_equals_cli_vtu(name, element, tmp_path):
    vtu = tmp_path / "cli.vtu"
    run_cli(example(name), "--element", element, "-o", vtu)
    ref = meshio.read(vtu)
    vm = coons.load(example(name)).volume_mesh(element)
    ours = vm.to_meshio()
    assert np.array_equal(ours.points, ref.points)
    assert len(ref.cells) == 1 and len(ours.cells) == 1
    assert ours.cells[0].type == ref.cells[0].type
    assert np.array_equal(ours.cells[0].data, ref.cells[0].data)
    for k in ("u", "v", "w", "det_j"):
        assert np.array_equal(ours.point_data[k], ref.point_data[k]), k
    for k in ("body", "scaled_jacobian"):
        assert k in ref.cell_data, sorted(ref.cell_data)
        assert np.array_equal(np.asarray(ours.cell_data[k][0]), np.asarray(ref.cell_data[k][0]))
    # meshio round trip of our own mesh: the VTU meshio writes reads back the same
    ours.write(tmp_path / "ours.vtu")
    back = meshio.read(tmp_path / "ours.vtu")
    assert np.array_equal(back.cells[0].data, ref.cells[0].data)


def test_hex8_cells_positive_in_vtk_order():
    """VTK's hexahedron: corners 1, 3, 4 on the positive sides of corner 0."""
    vm = coons.load(example("thick-cylinder.json")).volume_mesh(resolution=(3, 4, 2))
    (cells,) = vm.cells.values()
    p = vm.points[cells]
    det = np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 3] - p[:, 0], p[:, 4] - p[:, 0]))
    assert len(cells) == 24 and np.all(det > 0)


@pytest.mark.parametrize("ext", ["vtu", "msh", "inp", "vtk"])
def test_volume_write_equals_cli_bytes(ext, tmp_path):
    a, b = tmp_path / "a" / ("x." + ext), tmp_path / "b" / ("x." + ext)
    os.makedirs(a.parent)
    os.makedirs(b.parent)
    run_cli(example("spool.json"), "--element", "hex20", "--resolution", "4,5,3", "-o", a)
    coons.load(example("spool.json")).write(b, element="hex20", resolution=(4, 5, 3))
    assert filecmp.cmp(a, b, shallow=False)
