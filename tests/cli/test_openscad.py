#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Every example's OpenSCAD output, rendered by the real `openscad` binary.

For each examples/*.json: `coons2stl -o x.scad` and `coons2stl -o x.stl`;
`openscad -o r.stl x.scad` must exit 0 with no WARNING/ERROR and no
'not manifold' / 'may not be a valid 2-manifold' / 'not closed' on stderr;
the volume of OpenSCAD's STL (computed here, from its own ASCII or binary
STL) must match the volume of our binary STL (relative 1e-5: both are
float32). OpenSCAD renders a multi-body "none" model as the union of the
shells: that is compared with coons2stl's own union of the same model when
this libcoons has CGAL, else with the sum of the shells when those turn out
disjoint (equal volumes), and the volume check is skipped otherwise.
Models whose union needs CGAL are left out in a build without it, and only there.
Also: `use <x.scad>` renders nothing by itself and gives a module per
body, `include` renders the model. Two generated files `include`d into one
design (the spool, and the nail moved beside it by a transform: both files'
parts have the same name, "union") both render: every module name carries its
file's name, the design's volume is the sum of the two files' separate
renders and its bounding box covers both of theirs (when the names
clashed, OpenSCAD silently rendered the nail twice and no spool).

Usage: test_openscad.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402
from clitest import Runner  # noqa: E402

BAD = ("WARNING", "ERROR", "not manifold", "2-manifold", "not closed")


def read_stl(path):
    """Triangles of an ASCII or binary STL, as 9-tuples of floats."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:5] == b"solid" and b"facet" in data[:1024]:
        tris, cur = [], []
        for line in data.decode("ascii").splitlines():
            w = line.split()
            if w and w[0] == "vertex":
                cur.extend(float(x) for x in w[1:4])
                if len(cur) == 9:
                    tris.append(tuple(cur))
                    cur = []
        return tris
    (n,) = struct.unpack_from("<I", data, 80)
    if len(data) != 84 + 50 * n:
        raise ValueError(f"{path}: {len(data)} bytes for {n} triangles")
    return [struct.unpack_from("<12f", data, 84 + 50 * i)[3:] for i in range(n)]


def volume(tris):
    v = 0.0
    for t in tris:
        ax, ay, az, bx, by, bz, cx, cy, cz = t
        v += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)
    return v / 6.0


def openscad(scad, out, cwd):
    p = subprocess.run(["openscad", "-o", out, scad], cwd=cwd, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True, timeout=600)
    return p.returncode, p.stdout + p.stderr


def bbox(tris):
    pts = [(t[3 * j], t[3 * j + 1], t[3 * j + 2]) for t in tris for j in range(3)]
    lo = [min(p[i] for p in pts) for i in range(3)]
    hi = [max(p[i] for p in pts) for i in range(3)]
    return lo, hi


def render_design(r, tmp, name, text):
    """Renders a .scad design of `text`; returns (triangles or None, log)."""
    path = os.path.join(tmp, name + ".scad")
    with open(path, "w") as f:
        f.write(text)
    out = os.path.join(tmp, name + ".stl")
    rc, log = openscad(path, out, tmp)
    said = [b for b in BAD if b in log]
    if not r.check(f"{name}: openscad renders it silently", rc == 0 and not said,
                   f"exit {rc}, {said}:\n{log}"):
        return None
    return read_stl(out)


def two_includes(r, tmp):
    """include <spool.scad> and include <nail.scad> in one design."""
    src = os.path.join(r.src, "examples")
    with open(os.path.join(src, "nail.json")) as f:
        nail = json.load(f)
    # The nail as a definition, placed 20 mm beside the spool (|x| <= 6).
    moved = {k: v for k, v in nail.items() if k != "bodies"}
    moved["define"] = {f"b{i}": b for i, b in enumerate(nail["bodies"])}
    # Named like the spool's body: without a union (no CGAL) each file's part
    # is named after its body, and the clash is then spool_spool / nail_spool.
    moved["bodies"] = [{"ref": f"b{i}", "name": "spool" if i == 0 else f"b{i}",
                        "transform": [[1, 0, 0, 20], [0, 1, 0, 0], [0, 0, 1, 0]]}
                       for i, b in enumerate(nail["bodies"])]
    inc = os.path.join(tmp, "inc")
    os.makedirs(inc)
    nj = os.path.join(inc, "nail-moved.json")
    with open(nj, "w") as f:
        json.dump(moved, f)
    mods = {}
    for name, model in (("spool", os.path.join(src, "spool.json")), ("nail", nj)):
        st, _, err = r.run(["-o", os.path.join(inc, name + ".scad"), model])
        if not r.check(f"two includes: coons2stl -o {name}.scad", st == 0, err):
            return
        with open(os.path.join(inc, name + ".scad")) as f:
            mods[name] = re.findall(r"^module (\w+)\(\)", f.read(), re.M)
        r.check(f"two includes: every module of {name}.scad carries its name",
                mods[name] and all(m == name or m.startswith(name + "_") for m in mods[name]),
                f"{mods[name]}")
    # The case of the bug report: the same part name in both files ("union"
    # for united models, "spool" without CGAL).
    parts = [{m[len(n) + 1:] for m in mods[n] if m != n} for n in ("spool", "nail")]
    r.check("two includes: both files have a part of the same name",
            parts[0] & parts[1], f"{mods}")
    r.check("two includes: no module name in both files",
            not set(mods["spool"]) & set(mods["nail"]), f"{mods}")
    alone = {}
    for name in ("spool", "nail"):
        alone[name] = render_design(r, inc, f"{name}-alone", f"include <{name}.scad>\n")
    both = render_design(r, inc, "both", "include <spool.scad>\ninclude <nail.scad>\n")
    if both is None or None in alone.values():
        return
    vs, vn, vb = volume(alone["spool"]), volume(alone["nail"]), volume(both)
    r.check(f"two includes: volume {vb:.7g} = spool's {vs:.7g} + nail's {vn:.7g}",
            vs > 0 and vn > 0 and abs(vb - (vs + vn)) <= 1e-5 * (vs + vn))
    (ls, hs), (ln, hn), (lb, hb) = bbox(alone["spool"]), bbox(alone["nail"]), bbox(both)
    want_lo = [min(ls[i], ln[i]) for i in range(3)]
    want_hi = [max(hs[i], hn[i]) for i in range(3)]
    r.check("two includes: the bounding box covers both parts' (the nail 20 mm beside)",
            all(abs(lb[i] - want_lo[i]) <= 1e-4 and abs(hb[i] - want_hi[i]) <= 1e-4
                for i in range(3)) and ln[0] > hs[0],
            f"{lb} {hb} vs {want_lo} {want_hi}")


def main():
    r = Runner(__doc__)
    # A real client of the output: missing, it fails, never skips.
    if not r.need("openscad"):
        r.finish()
    tmp = tempfile.mkdtemp(prefix="coons-openscad-")
    try:
        r.check("examples found", len(clitest.examples(r.src, every=True)) > 10)
        examples = r.examples()
        for ex in examples:
            name = os.path.splitext(os.path.basename(ex))[0]
            scad = os.path.join(tmp, name + ".scad")
            ours = os.path.join(tmp, name + ".stl")
            st, _, err = r.run(["-o", scad, ex])
            if st == 3 and "CGAL" in err and not r.has_cgal():
                print(f"n/a  {name}: its union needs CGAL, not in this build")
                continue
            if not r.check(f"{name}: coons2stl -o .scad", st == 0, err):
                continue
            extra = []
            with open(scad) as f:  # a morph's animation renders t = $t = 0 on its lattice
                lat = re.search(r"one lattice of (\d+) intervals", f.read())
            if lat:
                extra = ["--time", "0", "--resolution", lat.group(1)]
            st, _, err = r.run(["-o", ours, ex] + extra)
            r.check(f"{name}: coons2stl -o .stl", st == 0, err)
            rendered = os.path.join(tmp, name + ".openscad.stl")
            rc, log = openscad(scad, rendered, tmp)
            said = [b for b in BAD if b in log]
            if not r.check(f"{name}: openscad renders it silently", rc == 0 and not said,
                           f"exit {rc}, {said}:\n{log}"):
                continue
            v_os = volume(read_stl(rendered))
            v_ours = volume(read_stl(ours))
            with open(ex) as f:
                model = json.load(f)
            multi_none = model.get("operation", "union") == "none" and len(model["bodies"]) > 1
            want, what = v_ours, "our STL"
            if multi_none:
                # OpenSCAD unites the shells; ask coons2stl for the union.
                u = dict(model, operation="union")
                uj = os.path.join(tmp, name + "-union.json")
                with open(uj, "w") as f:
                    json.dump(u, f)
                us = os.path.join(tmp, name + "-union.stl")
                st, _, err = r.run(["-o", us, uj])
                if st == 0:
                    want, what = volume(read_stl(us)), "coons2stl's union"
                elif abs(v_os - v_ours) > 1e-5 * abs(v_ours):
                    # only a build without CGAL may fail to unite them
                    r.check(f"{name}: coons2stl unites the overlapping shells", not r.has_cgal(), err)
                    continue
                else:
                    what = "the sum of its (disjoint) shells"
            r.check(f"{name}: OpenSCAD's volume {v_os:.7g} = {what} {want:.7g}",
                    abs(v_os - want) <= 1e-5 * abs(want) and want > 0)

        # use <> / include <> on a two-body "none" model.
        ex = os.path.join(r.src, "examples", "body-blend-cubic.json")
        with open(ex) as f:
            model = json.load(f)
        scad = os.path.join(tmp, "model.scad")
        st, _, err = r.run(["-o", scad, ex])
        r.check("body-blend-cubic to scad", st == 0, err)
        with open(scad) as f:
            text = f.read()
        modules = re.findall(r"^module (\w+)\(\)", text, re.M)
        r.check("one module per body plus the model's",
                len(modules) == len(model["bodies"]) + 1, f"{modules}")
        r.check("the model module is named after the file", modules[-1] == "model", modules[-1])
        r.check("a top-level call renders the model", text.rstrip().endswith(modules[-1] + "();"))
        user = os.path.join(tmp, "user.scad")
        with open(user, "w") as f:
            f.write(f"use <model.scad>\n{modules[0]}();\n")
        rc, log = openscad(user, os.path.join(tmp, "one.stl"), tmp)
        r.check("use <>: the first body's module renders alone", rc == 0 and
                not [b for b in BAD if b in log], log)
        ours_one = os.path.join(tmp, "one-ours.stl")
        st, _, err = r.run(["--body", "0", "-o", ours_one, ex])
        if st == 0 and rc == 0:
            a, b = volume(read_stl(os.path.join(tmp, "one.stl"))), volume(read_stl(ours_one))
            r.check(f"use <>: volume {a:.7g} = body 0's {b:.7g}", abs(a - b) <= 1e-5 * abs(b))
        with open(user, "w") as f:
            f.write("use <model.scad>\n")
        rc, log = openscad(user, os.path.join(tmp, "nothing.stl"), tmp)
        r.check("use <> alone renders nothing", rc != 0 or "Current top level object is empty"
                in log or "top level object is empty" in log.lower(), log)
        two_includes(r, tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    r.finish()


if __name__ == "__main__":
    main()
