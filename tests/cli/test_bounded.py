# SPDX-License-Identifier: GPL-3.0-or-later
"""Bounded work of the sampler (issue 15): a tolerance predicted to need far
more triangles (or volume cells) than the limit is refused on the first,
coarse lattice, naming the limit, the prediction and what to try; and the
prediction never refuses a mesh that fits: for every single-body example
at a quarter of its tolerance, --max-triangles set to exactly the triangles the
sampler's lattice makes (4 (nu nv + nv nw + nu nw), from --info's
"lattice") is accepted, and one less is refused by the exact check."""
import json
import os
import shutil
import tempfile

from clitest import Runner


def lattice_of(T, model, tol):
    rc, out, err = T.run(["-q", "--info", "--no-solid", "-t", repr(tol), model])
    if rc != 0:
        return None, err
    info = json.loads(out)
    if info["body_count"] != 1 or "mesh" not in info["bodies"][0]:
        return None, "not one sampled body"
    return info["bodies"][0]["mesh"], ""


def main():
    T = Runner(__doc__)
    root = tempfile.mkdtemp(prefix="coons_bounded_")
    spool = os.path.join(T.src, "examples", "spool.json")
    try:
        out = os.path.join(root, "out.stl")
        # ---- refused at once, on the first lattice ---------------------------
        rc, _, err = T.run(["-t", "1e-6", "-o", out, spool])
        words = ["tolerance 1e-06", "more than 20000000 triangles", "the limit",
                 "predicted", "on the 4 x 4 x 4 lattice", "--max-triangles",
                 "loosen the tolerance"]
        missing = [w for w in words if w not in err]
        T.check("spool -t 1e-6: exit 3, refused on the starting lattice with the prediction",
                rc == 3 and not missing, f"status {rc}, missing {missing}: {err!r}")
        T.check("spool -t 1e-6: nothing written", not os.path.exists(out))
        rc, _, err = T.run(["-q", "--info", "--no-solid", "--volume-mesh", "-t", "1e-4", spool])
        words = ["more than 4194304 volume cells", "predicted", "on the 4 x 4 x 4 lattice"]
        missing = [w for w in words if w not in err]
        T.check("spool --volume-mesh -t 1e-4: exit 3, cells predicted on the starting lattice",
                rc == 3 and not missing, f"status {rc}, missing {missing}: {err!r}")

        # ---- never refuses what fits ---------------------------------------------
        tried = 0
        # Every example in release; under a sanitizer or valgrind the
        # representative subset (every kind of curve, patch and body).
        for model in T.examples():
            name = os.path.basename(model)
            rc, info, _ = T.run(["-q", "--info", "--no-solid", model])
            if rc != 0:
                continue
            base = json.loads(info)["tolerance"]
            for tol in (base / 4,):
                mesh, why = lattice_of(T, model, tol)
                if mesh is None:
                    break
                n = mesh["lattice"]
                need = 4 * (n[0] * n[1] + n[1] * n[2] + n[0] * n[2])
                rc, _, err = T.run(["-q", "-t", repr(tol), "--max-triangles", str(need),
                                    "-o", out, model])
                T.check(f"{name} -t {tol:.3g}: --max-triangles {need} (exactly the lattice's) "
                        "fits", rc == 0, err)
                rc, _, err = T.run(["-q", "-t", repr(tol), "--max-triangles", str(need - 1),
                                    "-o", out, model])
                T.check(f"{name} -t {tol:.3g}: --max-triangles {need - 1} refused (exit 3)",
                        rc == 3 and "--max-triangles" in err, f"status {rc}: {err!r}")
                tried += 1
        least = 8 if len(T.examples()) < 30 else 35
        T.check(f"{tried} single-body cases tried", tried >= least)
    finally:
        shutil.rmtree(root, ignore_errors=True)
    T.finish()


if __name__ == "__main__":
    main()
