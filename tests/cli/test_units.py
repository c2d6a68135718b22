#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Units (coons2stl(1), "Units"; the output contract, "Honest output").

- A model in inches written to a format whose readers take millimetres
  (binary and ASCII STL, OFF, SCAD) warns once, naming the unit, also for
  --frames (once for all frames); not with -q, not for a model in mm, not
  with --scale-to mm.
- --scale-to mm multiplies every coordinate by 25.4 (the OFF's doubles are
  exactly the unscaled ones times 25.4, computed here), labels the output
  mm (the .inp heading), and scales volume-mesh nodes alike; --scale-to cm
  from inches is 2.54.
- Refusals: an unknown target (exit 2), a model unit that is not a length
  (exit 1), --eval and --info without a volume output (exit 2), nothing
  written.

Usage: test_units.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import os
import shutil
import sys
import tempfile
import xml.etree.ElementTree as ET
import zipfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
TMP = tempfile.mkdtemp(prefix="coons-units-")


def model(units, name="box.json", morph=False):
    box = {"type": "body0", "name": "box",
           "corners": [[0, 0, 0], [0, 0, 1], [0, 1, 0], [0, 1, 1],
                       [1, 0, 0], [1, 0, 1], [1, 1, 0], [1, 1, 1.5]]}
    if morph:
        big = dict(box, corners=[[2 * c for c in p] for p in box["corners"]])
        box = {"type": "morph", "name": "box", "keys": [box, big], "t": 0.5}
    path = os.path.join(TMP, name)
    with open(path, "w") as fh:
        json.dump({"coons": 1, "units": units, "bodies": [box]}, fh)
    return path


def off_vertices(path):
    if not os.path.exists(path):
        return []
    with open(path) as fh:
        lines = [ln for ln in fh.read().split("\n") if ln and not ln.startswith("#")]
    nv = int(lines[1].split()[0])
    return [tuple(float(x) for x in ln.split()) for ln in lines[2:2 + nv]]


def inp_nodes(path):
    if not os.path.exists(path):
        return "", []
    with open(path) as fh:
        text = fh.read()
    body = text.split("*NODE, NSET=NALL\n")[1].split("*")[0]
    return text, [tuple(float(x) for x in ln.split(",")[1:]) for ln in body.strip().split("\n")]


inch = model("in")
mm = model("mm", "mm.json")
WARN = "warning: the model's units are 'in'"

for ext in ("stl", "off", "scad"):
    out = os.path.join(TMP, "a." + ext)
    rc, _, err = T.run(["-o", out, inch])
    T.check(f"inches to .{ext}: exit 0, one warning naming 'in' and --scale-to mm",
            rc == 0 and err.count(WARN) == 1 and "--scale-to mm" in err
            and err.count("\n") == 1, err)
rc, _, err = T.run(["-f", "stl-ascii", "-o", os.path.join(TMP, "a.txt"), inch])
T.check("inches to ASCII STL: the warning", rc == 0 and err.count(WARN) == 1, err)
rc, _, err = T.run(["-q", "-o", os.path.join(TMP, "q.stl"), inch])
T.check("-q: no warning", rc == 0 and err == "", err)
rc, _, err = T.run(["-o", os.path.join(TMP, "m.stl"), mm])
T.check("a model in mm: no warning", rc == 0 and err == "", err)
rc, _, err = T.run(["--resolution", "2", "-o", os.path.join(TMP, "v.vtu"), inch])
T.check("a volume mesh (.vtu): no warning (not a format for slicers)", rc == 0 and err == "", err)

# --frames: one warning for all frames
fr = model("in", "morph.json", morph=True)
rc, _, err = T.run(["--frames", "3", "-o", os.path.join(TMP, "f%d.stl"), fr])
T.check("--frames 3 of a model in inches: one warning, not one per frame",
        rc == 0 and err.count(WARN) == 1, err)

# --scale-to: the numbers, computed here from the unscaled output
plain, scaled, cm = (os.path.join(TMP, n) for n in ("p.off", "s.off", "c.off"))
rc1, _, _ = T.run(["-q", "-o", plain, inch])
rc2, _, err2 = T.run(["--scale-to", "mm", "-o", scaled, inch])
rc3, _, _ = T.run(["--scale-to", "CM", "-o", cm, inch])
p, s, c = off_vertices(plain), off_vertices(scaled), off_vertices(cm)
T.check("--scale-to mm: no warning", rc2 == 0 and err2 == "", err2)
T.check("--scale-to mm: the same vertices, each coordinate times 25.4",
        rc1 == rc2 == 0 and len(p) == len(s) > 8
        and all(sv[k] == pv[k] * 25.4 for pv, sv in zip(p, s) for k in range(3)),
        f"{p[:2]} {s[:2]}")
T.check("--scale-to CM (any case): times 2.54", rc3 == 0 and len(c) == len(p)
        and all(abs(cv[k] - pv[k] * 2.54) <= 1e-15 * max(1, abs(pv[k]))
                for pv, cv in zip(p, c) for k in range(3)), f"{c[:2]}")
units, units0 = ([ln for ln in open(f).read().split("\n") if ln.startswith("# units")]
                 if os.path.exists(f) else [] for f in (scaled, plain))
T.check("the OFF's units comment: 'in' as the model, 'mm' with --scale-to mm",
        units0 == ["# units: in"] and units == ["# units: mm"], f"{units0} {units}")

for extra in ([], ["--scale-to", "mm"]):
    out = os.path.join(TMP, "v%d.inp" % len(extra))
    rc, _, err = T.run(["-q", "--resolution", "2"] + extra + ["-o", out, inch])
    T.check(f".inp {extra}: exit 0", rc == 0, err)
vin_text, vin = inp_nodes(os.path.join(TMP, "v0.inp"))
vmm_text, vmm = inp_nodes(os.path.join(TMP, "v2.inp"))
T.check("volume mesh: the .inp heading says units=in, and units=mm with --scale-to mm",
        "units=in" in vin_text and "units=mm" in vmm_text, vmm_text[:200])
T.check("volume mesh --scale-to mm: every node times 25.4 (to the 17 digits printed)",
        len(vin) == len(vmm) > 8 and all(abs(b[k] - a[k] * 25.4) <= 1e-14 * max(1, abs(b[k]))
                                          for a, b in zip(vin, vmm) for k in range(3)),
        f"{vin[:2]} {vmm[:2]}")

# 3MF carries units: 'inch' as the model says, no warning; with --scale-to mm the
# coordinates times 25.4 and 'millimeter' (when the library has lib3mf)
def read_3mf(path):
    with zipfile.ZipFile(path) as z:
        name = [n for n in z.namelist() if n.endswith(".model")][0]
        root = ET.fromstring(z.read(name))
    xs = [float(v.get("x")) for v in root.iter() if v.tag.endswith("vertex")]
    return root.get("unit"), xs


t_in, t_mm = os.path.join(TMP, "in.3mf"), os.path.join(TMP, "mm.3mf")
rc, _, err = T.run(["-o", t_in, inch])
if rc == 0:
    rc2, _, err2 = T.run(["--scale-to", "mm", "-o", t_mm, inch])
    (u_in, x_in), (u_mm, x_mm) = read_3mf(t_in), read_3mf(t_mm) if rc2 == 0 else (None, [])
    T.check("3MF of a model in inches: unit 'inch', no warning (3MF carries units)",
            u_in == "inch" and err == "", f"{u_in} {err}")
    T.check("3MF --scale-to mm: unit 'millimeter', the same vertices times 25.4 (6 decimals)",
            u_mm == "millimeter" and len(x_in) == len(x_mm) > 8
            and all(abs(b - a * 25.4) <= 1e-5 * max(1, abs(b)) for a, b in zip(x_in, x_mm)),
            f"{u_mm} {x_in[:3]} {x_mm[:3]}")
else:
    T.check("3MF without lib3mf: refused as before", rc == 3 and "3MF" in err, err)

# refusals: nothing written
def refused(name, args, status, words):
    out = os.path.join(TMP, "never.off")
    rc, so, err = T.run(args)
    T.check(f"{name}: exit {status}, says {words}, nothing written",
            rc == status and all(w in err for w in words) and not os.path.exists(out), err)


refused("unknown target", ["--scale-to", "furlong", "-o", os.path.join(TMP, "never.off"), inch],
        2, ["--scale-to", "furlong"])
odd = model("parsec", "odd.json")
refused("a model unit that is not a length", ["--scale-to", "mm", "-o",
        os.path.join(TMP, "never.off"), odd], 1, ["parsec", "nothing was written"])
refused("--eval", ["--eval", "--scale-to", "mm", inch], 2, ["--scale-to"])
refused("--info", ["--info", "--scale-to", "mm", inch], 2, ["--scale-to"])

shutil.rmtree(TMP)
T.finish()
