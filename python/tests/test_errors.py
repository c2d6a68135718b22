# SPDX-License-Identifier: GPL-3.0-or-later
"""Every error class is raised by a real bad input and carries the
library's message; misuse raises instead of crashing."""
import json
import os

import numpy as np
import pytest

import coons
from conftest import example

CUBE = [[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)]


def test_load_error_locates_the_value(tmp_path):
    text = '{"coons": 1,\n "bodies": [\n  {"type": "body0", "corners": [[0, 0, 0]]}]}'
    with pytest.raises(coons.LoadError) as e:
        coons.loads(text, name="bad.json")
    assert e.value.file == "bad.json" and e.value.line == 3 and e.value.column > 1
    assert e.value.path == "/bodies/0/corners"
    assert "bad.json:3:" in str(e.value) and e.value.code == -2
    f = tmp_path / "bad.json"
    f.write_text('{"coons": 1, "bodies": [}')
    with pytest.raises(coons.LoadError) as e:
        coons.load(f)
    assert e.value.file == str(f) and e.value.line == 1 and e.value.code == -5
    with pytest.raises(coons.LoadError) as e:
        coons.load(tmp_path / "missing.json")
    assert e.value.code == -4 and e.value.line == 0


def test_load_limit_error():
    text = json.dumps({"coons": 1, "bodies": [{"type": "body0", "corners": CUBE}]})
    with pytest.raises(coons.LimitError) as e:
        coons.loads(text, max_values=10)
    assert isinstance(e.value, coons.LoadError) and "max_values" in str(e.value)


def test_limit_error_triangle_budget():
    with pytest.raises(coons.LimitError):
        coons.load(example("nail.json")).mesh(resolution=40, max_triangles=100)


def test_geometry_error_body1_edges_do_not_meet():
    text = open(example("body1-bspline-edges.json")).read()
    doc = json.loads(text)
    edges = doc["bodies"][0]["edges"]
    key = sorted(edges)[0]
    e0 = edges[key]
    e0["points"][0] = [p + 0.5 for p in e0["points"][0]]
    with pytest.raises(coons.GeometryError) as e:
        coons.loads(json.dumps(doc))
    assert isinstance(e.value, coons.LoadError) and e.value.code == -10


def test_geometry_error_inverted_volume_mesh(tmp_path):
    """A body whose corner 7 is pulled through the opposite corner folds;
    coons2stl refuses its volume mesh, and so does Model.write."""
    c = np.array(CUBE, float).reshape(2, 2, 2, 3)
    c[1, 1, 1] = [-0.8, -0.8, -0.8]
    m = coons.Model([coons.body0(c)])
    with pytest.raises(coons.GeometryError) as e:
        m.write(tmp_path / "x.vtu", resolution=4)
    assert "inverted" in str(e.value)
    assert not (tmp_path / "x.vtu").exists()
    m.write(tmp_path / "x.vtu", resolution=4, allow_inverted=True)


def test_unsupported_or_union(tmp_path):
    m = coons.load(example("union-three-bodies.json"))
    if coons.features()["cgal"]:
        assert len(m.mesh().triangles) > 0
    else:
        with pytest.raises(coons.UnsupportedError) as e:
            m.mesh()
        assert "CGAL" in str(e.value)


def test_argument_errors():
    b = coons.load(example("nail.json")).bodies[0]
    with pytest.raises(coons.DomainError):
        b.eval([0.5, 0.5, 1.5])
    with pytest.raises(coons.InvalidError):
        b.eval([0.5, np.nan, 0.5])
    with pytest.raises(coons.InvalidError):
        b.eval(np.zeros((4, 2)))
    with pytest.raises(coons.InvalidError):
        b.eval("abc")
    with pytest.raises(coons.InvalidError):
        b.eval([[object(), 1, 2]])
    with pytest.raises(coons.LimitError):
        b.grid(np.zeros(1000), np.zeros(1000), np.zeros(1000))
    with pytest.raises(coons.InvalidError):
        b.jacobian(np.zeros((2, 3, 3)))
    with pytest.raises(coons.DomainError):
        b.eval([0.5, 0.5, 0.5], time=2)
    # integer and float32 input is accepted and converted
    assert np.array_equal(b.eval(np.array([0, 1, 1], np.int32)), b.eval([0.0, 1.0, 1.0]))
    assert np.array_equal(b.eval(np.zeros((0, 3))), np.zeros((0, 3)))
    m = coons.load(example("nail.json"))
    with pytest.raises(KeyError):
        m.body("no such body")
    with pytest.raises(coons.InvalidError):
        m.volume_mesh("tet4")
    with pytest.raises(coons.InvalidError):
        m.mesh(tolerance=-1)
    with pytest.raises(coons.InvalidError):
        m.write("x.unknown")
    with pytest.raises(coons.InvalidError):
        coons.body0(np.zeros((2, 2, 3)))
    with pytest.raises(coons.InvalidError):
        coons.bspline_volume(np.zeros((3, 3, 3, 3)), [0, 1], [0, 0, 1, 1], [0, 0, 1, 1])


def test_file_error(tmp_path):
    with pytest.raises(coons.FileError) as e:
        coons.load(example("nail.json")).write(tmp_path / "no" / "dir" / "x.stl")
    assert "x.stl" in str(e.value)


def test_model_file_is_never_overwritten(tmp_path):
    f = tmp_path / "m.off"
    f.write_text(open(example("nail.json")).read())
    m = coons.load(f)
    with pytest.raises(coons.InvalidError):
        m.write(f)
    assert f.read_text() == open(example("nail.json")).read()


def test_features_as_built():
    """tools/test.sh says which build it installed (COONS_EXPECT_CGAL): the
    full library in one environment, the C core in another."""
    f = coons.features()
    want = os.environ.get("COONS_EXPECT_CGAL")
    if want is not None:
        assert f["cgal"] == (want == "1"), f
        assert f["occt"] == (want == "1"), f  # the full build has Open CASCADE too
    assert f["openmesh"] or not f["cgal"]
