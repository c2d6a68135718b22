# SPDX-License-Identifier: GPL-3.0-or-later
"""Lifetime torture: use after close, objects outliving their model,
threads closing a model while others evaluate its bodies. Runs in this
process, and again in a child process under valgrind memcheck (the
package's libcoons is not sanitized; valgrind sees every invalid read of
freed C memory and makes the child fail). valgrind cannot run CGAL (its
interval arithmetic checks the rounding modes valgrind does not emulate
when the library is loaded), so the valgrind run needs a C-core build:
tools/test.sh runs it in its second, C-core environment."""
import gc
import os
import shutil
import subprocess
import sys
import threading

import numpy as np
import pytest

import coons
from conftest import example

HERE = os.path.dirname(os.path.abspath(__file__))


def torture(rounds=3):
    for _ in range(rounds):
        m = coons.load(example("union-three-bodies.json"))
        b = m.bodies[1]
        m.close()
        with pytest.raises(coons.ClosedError):
            b.eval([0.5, 0.5, 0.5])
        with pytest.raises(coons.ClosedError):
            m.mesh()
        m.close()  # twice: harmless

        # a body outlives every Python reference to its model
        b = coons.load(example("nail.json")).bodies[0]
        gc.collect()
        x = b.eval([0.5, 0.5, 0.5])
        assert np.all(np.isfinite(x)) and b.model is not None

        # meshes and volume meshes own their data
        m = coons.load(example("nail.json"))
        mesh = m.mesh(resolution=4)
        vm = m.volume_mesh(resolution=2)
        m.close()
        assert mesh.vertices.shape[1] == 3 and len(vm.points) > 0
        mesh.close()
        with pytest.raises(coons.ClosedError):
            mesh.write("unused.off")
        vm.close()

        # standalone builder bodies
        c = np.array([[[[i, j, k] for k in (0, 1)] for j in (0, 1)] for i in (0, 1)], float)
        s = coons.body0(c)
        s.close()
        with pytest.raises(coons.ClosedError):
            s.eval([0, 0, 0])

        # curves and patches: a patch outlives its curves (constructors copy)
        ends = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0.5]], float)
        sides = {"t0": coons.line(ends[[0, 1]]), "t1": coons.line(ends[[2, 3]]),
                 "s0": coons.line(ends[[0, 2]]), "s1": coons.line(ends[[1, 3]])}
        p = coons.coons(sides)
        for c in sides.values():
            c.close()
        with pytest.raises(coons.ClosedError):
            coons.ruled([sides["t0"], sides["t1"]])
        assert np.allclose(p.eval([1, 1]), ends[3])
        p.close()
        with pytest.raises(coons.ClosedError):
            p.grid([0, 1], [0, 1])

        # threads: evaluating while another thread closes the model
        m = coons.load(example("volume-nurbs.json"))
        body = m.bodies[0]
        q = np.random.default_rng(0).random((2000, 3))
        errors, results = [], []

        def work():
            try:
                for _ in range(5):
                    results.append(body.eval(q))
            except coons.ClosedError:
                pass
            except Exception as e:  # pragma: no cover - reported below
                errors.append(e)

        ts = [threading.Thread(target=work) for _ in range(4)]
        for t in ts:
            t.start()
        m.close()
        for t in ts:
            t.join()
        assert not errors, errors
        for r in results:
            assert r.shape == (2000, 3) and np.all(np.isfinite(r))


def test_torture_in_process():
    torture()


def test_torture_under_valgrind():
    valgrind = shutil.which("valgrind")
    assert valgrind, "valgrind is needed (tools/setup.sh installs it)"
    assert not coons.features()["cgal"], (
        "this build has CGAL, which valgrind cannot run: run this test against a C-core "
        "build (pip wheel ./python with -DCOONS_WITH_CGAL=OFF; tools/test.sh does)")
    env = dict(os.environ, PYTHONMALLOC="malloc")
    code = ("import sys; sys.path.insert(0, %r); import test_lifetime; "
            "test_lifetime.torture(1); print('torture ok')" % HERE)
    p = subprocess.run([valgrind, "--error-exitcode=99", "--leak-check=no", "-q",
                        "--suppressions=" + os.path.join(HERE, "python.supp"),
                        sys.executable, "-c", code], capture_output=True, text=True, env=env,
                       cwd=HERE)
    assert p.returncode == 0 and "torture ok" in p.stdout, p.stderr[-4000:]
