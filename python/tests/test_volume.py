# SPDX-License-Identifier: GPL-3.0-or-later
"""Model.volume_mesh() equals the CLI's .vtu after meshio reads both
(points, the blocks of cells by type in VTK order, point and cell data),
for each element and every example, including bodies that collapse
(nail.json: its tip's hex8 cells are pyramids in both, by
coons_volume_mesh_cell_shape()); Model.write() of volume formats writes
the CLI's bytes."""
import filecmp
import os

import meshio
import numpy as np
import pytest

import coons
from conftest import EXAMPLE_FILES, example, ids, run_cli


def _same_as_cli(path, element, tmp_path):
    vtu = tmp_path / "cli.vtu"
    run_cli(path, "--element", element, "-o", vtu)
    ref = meshio.read(vtu)
    vm = coons.load(path).volume_mesh(element)
    ours = vm.to_meshio()
    assert np.array_equal(ours.points, ref.points)
    assert [(c.type, len(c.data)) for c in ours.cells] == \
        [(c.type, len(c.data)) for c in ref.cells]
    for a, b in zip(ours.cells, ref.cells):
        assert np.array_equal(a.data, b.data), a.type
    # VolumeMesh.cells: one array per type, the blocks of that type in order
    for t in {c.type for c in ref.cells}:
        want = np.concatenate([c.data for c in ref.cells if c.type == t])
        assert np.array_equal(vm.cells[t], want), t
    assert sorted(vm.cells) == sorted({c.type for c in ref.cells})
    for k in ("u", "v", "w", "det_j"):
        assert np.array_equal(ours.point_data[k], ref.point_data[k]), k
    for k in ("body", "scaled_jacobian"):
        assert k in ref.cell_data, sorted(ref.cell_data)
        assert len(ours.cell_data[k]) == len(ref.cell_data[k])
        for a, b in zip(ours.cell_data[k], ref.cell_data[k]):
            assert np.array_equal(np.asarray(a), np.asarray(b)), k
    # meshio round trip of our own mesh: the VTU meshio writes reads back the same
    ours.write(tmp_path / "ours.vtu")
    back = meshio.read(tmp_path / "ours.vtu")
    assert [c.type for c in back.cells] == [c.type for c in ref.cells]
    for a, b in zip(back.cells, ref.cells):
        assert np.array_equal(a.data, b.data)
    return vm


@pytest.mark.parametrize("element", ["hex8", "hex20", "hex27"])
@pytest.mark.parametrize("path", EXAMPLE_FILES, ids=ids(EXAMPLE_FILES))
def test_volume_mesh_equals_cli_vtu(path, element, tmp_path):
    """Every example: the same mesh as the CLI's, or, for the models the
    CLI refuses to volume-mesh (bodies that overlap), the same refusal."""
    if run_cli(path, "--element", element, "-o", tmp_path / "probe.vtu",
               check=False).returncode != 0:
        with pytest.raises(coons.errors.Error):
            coons.load(path).volume_mesh(element)
        return
    _same_as_cli(path, element, tmp_path)


@pytest.mark.parametrize("name", ["nail.json", "nail-density.json"])
def test_collapsed_tip_is_pyramids(name, tmp_path):
    """The nail's tip is a point: its hex8 cells there are pyramids. The
    CLI's .inp keeps them as C3D8 with repeated nodes (CalculiX has no
    pyramid): the cells with 5 distinct nodes there are exactly the
    pyramids' node sets, and each pyramid is positive in VTK's order."""
    vm = _same_as_cli(example(name), "hex8", tmp_path)
    assert sorted(vm.cells) == ["hexahedron", "pyramid"]
    inp = tmp_path / "cli.inp"
    run_cli(example(name), "--element", "hex8", "-o", inp)
    raw = np.concatenate([c.data for c in meshio.read(inp).cells if c.type == "hexahedron"])
    five = sorted(tuple(sorted(set(r))) for r in raw.tolist() if len(set(r)) == 5)
    ours = sorted(tuple(sorted(r)) for r in vm.cells["pyramid"].tolist())
    assert len(ours) > 0 and ours == five
    p = vm.points[vm.cells["pyramid"]]
    det = np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]),
                    p[:, 4] - p[:, 0])
    assert np.all(det > 0)


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
