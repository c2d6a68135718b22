# SPDX-License-Identifier: GPL-3.0-or-later
"""Model.mesh() is the solid coons2stl -o writes (compared with the CLI's
OFF, which carries every double exactly); Model.write() writes the CLI's
bytes in every surface format; a model the CLI cannot mesh (a union
without CGAL) raises."""
import filecmp
import os

import numpy as np
import pytest

import coons
from conftest import example, run_cli


def read_off(path):
    with open(path) as f:
        toks = [ln.split("#")[0].split() for ln in f]
    toks = [t for t in toks if t]
    assert toks[0] == ["OFF"]
    nv, nt = int(toks[1][0]), int(toks[1][1])
    v = np.array([[float(x) for x in t] for t in toks[2:2 + nv]]).reshape(nv, 3)
    t = np.array([[int(x) for x in t[1:]] for t in toks[2 + nv:2 + nv + nt]],
                 dtype=np.int64).reshape(nt, 3)
    return v, t


def test_mesh_equals_cli(example_file, tmp_path):
    off = tmp_path / "cli.off"
    p = run_cli(example_file, "-o", off, check=False)
    m = coons.load(example_file)
    if p.returncode != 0:
        with pytest.raises(coons.Error):
            m.mesh()
        assert not coons.features()["cgal"]
        return
    mesh = m.mesh()
    v, t = read_off(off)
    assert mesh.vertices.dtype == np.float64 and mesh.triangles.dtype == np.int64
    assert np.array_equal(mesh.vertices, v)
    assert np.array_equal(mesh.triangles, t)
    if m.operation == "union" and len(m.bodies) == 1 and m.bodies[0].det_j([.5, .5, .5]) > 0:
        assert mesh.volume() > 0  # outward


@pytest.mark.parametrize("ext", ["stl", "off", "scad"])
@pytest.mark.parametrize("name", ["nail.json", "spool.json", "morph-three-keys.json",
                                  "hood-shell.json"])
def test_write_equals_cli_bytes(name, ext, tmp_path):
    """Same file name in two folders (the model name in the file is the
    output's base name)."""
    a, b = tmp_path / "cli" / ("x." + ext), tmp_path / "py" / ("x." + ext)
    os.makedirs(a.parent)
    os.makedirs(b.parent)
    run_cli(example(name), "-o", a)
    coons.load(example(name)).write(b)
    assert filecmp.cmp(a, b, shallow=False)


def test_write_options_equal_cli(tmp_path):
    path = example("union-three-bodies.json")
    a, b = tmp_path / "a" / "x.off", tmp_path / "b" / "x.off"
    os.makedirs(a.parent)
    os.makedirs(b.parent)
    run_cli(path, "--body", "1", "--resolution", "6", "-o", a)
    coons.load(path).write(b, body=1, resolution=6)
    assert filecmp.cmp(a, b, shallow=False)
    # ASCII STL through -f
    run_cli(path, "--body", "0", "-t", "0.05", "-f", "stl-ascii", "-o", a)
    coons.load(path).write(b, body=0, tolerance=0.05, format="stl-ascii")
    assert filecmp.cmp(a, b, shallow=False)


def test_body_mesh_and_mesh_write(tmp_path):
    path = example("union-three-bodies.json")
    m = coons.load(path)
    body = m.bodies[2]
    a = tmp_path / "x.off"
    run_cli(path, "--body", body.name, "-o", a)
    mesh = body.mesh()
    v, t = read_off(a)
    assert np.array_equal(mesh.vertices, v) and np.array_equal(mesh.triangles, t)
    b = tmp_path / "y" / "x.off"
    os.makedirs(b.parent)
    mesh.write(b, units=m.units)
    assert filecmp.cmp(a, b, shallow=False)


def test_progress_callback_is_called():
    seen = []
    coons.load(example("spool.json")).mesh(progress=lambda stage, f: seen.append((stage, f)))
    assert all(isinstance(s, str) and 0 <= f <= 1 for s, f in seen)


@pytest.mark.parametrize("ext", ["step", "igs", "brep"])
@pytest.mark.parametrize("name", ["spool.json", "union-three-bodies.json"])
def test_write_solid_equals_cli_bytes(name, ext, tmp_path):
    """Exact solids (Open CASCADE): the bytes coons2stl writes; without the
    layer, refused naming it, nothing written."""
    a, b = tmp_path / "cli" / ("x." + ext), tmp_path / "py" / ("x." + ext)
    os.makedirs(a.parent)
    os.makedirs(b.parent)
    m = coons.load(example(name))
    if not coons.features()["occt"]:
        with pytest.raises(coons.UnsupportedError) as e:
            m.write(b)
        assert "Open CASCADE" in str(e.value) and not b.exists()
        return
    run_cli(example(name), "-o", a)
    m.write(b)
    assert filecmp.cmp(a, b, shallow=False)
    assert a.stat().st_size > 1000
