# SPDX-License-Identifier: GPL-3.0-or-later
"""Bodies built from numpy equal the same JSON models bitwise; Model(...)
and Model.to_json() give files coons2stl reads as the same model."""
import json

import numpy as np
import pytest

import coons
from conftest import example, run_cli
from test_eval import cli_eval, points


def _json_body(path, i=0):
    with open(path) as f:
        return json.load(f)["bodies"][i]


def test_body0_equals_json_and_trilinear():
    rng = np.random.default_rng(1)
    c = np.array([[[[i, j, k] for k in (0, 1)] for j in (0, 1)] for i in (0, 1)], float)
    c = c * [3, 2, 1] + 0.2 * rng.random((2, 2, 2, 3))
    b = coons.body0(c)
    text = json.dumps({"coons": 1, "bodies": [{"type": "body0",
                                               "corners": c.reshape(8, 3).tolist()}]})
    ref = coons.loads(text).bodies[0]
    q = points(3)
    assert np.array_equal(b.eval(q), ref.eval(q))
    # seed 000, body 0: T(P_ijk; u, v, w), trilinear in the corners [i][j][k]
    u, v, w = q[:, 0:1], q[:, 1:2], q[:, 2:3]
    tri = sum(c[i, j, k] * (u if i else 1 - u) * (v if j else 1 - v) * (w if k else 1 - w)
              for i in (0, 1) for j in (0, 1) for k in (0, 1))
    assert np.allclose(b.eval(q), tri, rtol=0, atol=1e-13)
    assert b.type == "body0"


def test_bezier_volume_equals_example():
    path = example("volume-bezier.json")
    spec = _json_body(path)
    b = coons.bezier_volume(np.array(spec["points"], float))
    ref = coons.load(path).bodies[0]
    q = points(4)
    assert np.array_equal(b.eval(q), ref.eval(q))
    assert np.array_equal(b.jacobian(q), ref.jacobian(q))


@pytest.mark.parametrize("name", ["volume-nurbs.json", "volume-bspline.json"])
def test_bspline_volume_equals_example(name):
    path = example(name)
    spec = _json_body(path)
    pts = np.array(spec["points"], float)
    if "knots" in spec:
        ku, kv, kw = spec["knots"]
    else:  # the format's default: clamped uniform
        ku, kv, kw = [[0.0] * p + list(np.linspace(0, 1, n - p + 1)) + [1.0] * p
                      for n, p in zip(pts.shape[:3], spec["degree"])]
    b = coons.bspline_volume(pts, ku, kv, kw, weights=spec.get("weights"))
    ref = coons.load(path).bodies[0]
    q = points(5)
    assert np.array_equal(b.eval(q), ref.eval(q))
    assert list(b.to_dict()["degree"]) == list(spec["degree"])


def test_model_to_json_round_trips_through_cli(tmp_path):
    rng = np.random.default_rng(2)
    c = np.array([[[[i, j, k] for k in (0, 1)] for j in (0, 1)] for i in (0, 1)], float)
    a = coons.body0(c + 0.1 * rng.random((2, 2, 2, 3)), name="a")
    pts = np.stack(np.meshgrid(*[np.linspace(0, 1, 3)] * 3, indexing="ij"), -1) * [2, 2, 2]
    bz = coons.bezier_volume(pts + [3, 0, 0] + 0.05 * rng.random(pts.shape), name="bz")
    m = coons.Model([a, bz], units="in", tolerance=0.002, operation="none")
    f = tmp_path / "m.json"
    f.write_text(m.to_json())
    for i, b in enumerate((a, bz)):
        q = points(6 + i)
        assert np.array_equal(cli_eval(str(f), b.name, q), b.eval(q))
        assert np.array_equal(m.body(b.name).eval(q), b.eval(q))
    back = coons.loads(m.to_json())
    assert back.units == "in" and back.tolerance == 0.002 and back.operation == "none"
    assert [b.name for b in back.bodies] == ["a", "bz"]
    # a loaded model's to_json is a model the CLI reads as the same
    src = coons.load(example("fig13.json"))
    g = tmp_path / "fig13.json"
    g.write_text(src.to_json())
    q = points(9)
    assert np.array_equal(cli_eval(str(g), 0, q), src.bodies[0].eval(q))


def test_generic_body_builder():
    spec = _json_body(example("nail.json"))
    spec.pop("name", None)
    t = spec.pop("type")
    b = coons.body(t, name="n", **spec)
    ref = coons.load(example("nail.json")).bodies[0]
    q = points(7)
    assert np.array_equal(b.eval(q), ref.eval(q))
    assert coons.Model([b]).body("n").name == "n"
