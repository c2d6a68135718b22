#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""coons2stl -o FILE.3mf / -f 3mf, read by the programs that use 3MF.

With lib3mf built in (COONS_WITH_LIB3MF in the build's CMakeCache.txt):
- PrusaSlicer's `--info` reads the spool (examples/spool.json): manifold,
  nothing repaired, 12 mm across (examples/README.md) and 10 mm high, the
  same volume as the binary STL of the same run (read here);
- the `operation: none` example with three bodies gives three objects
  (PrusaSlicer lists three), the first the body0 box of corners
  0..10 x 0..10 with heights 13, 7, 7, 13, whose volume is exactly 1000
  (the cubic blend's two halves average the heights to 10);
- the same model with "units": "in" is read by PrusaSlicer 25.4 times as
  large (the unit attribute, which the package holds as unit="inch");
- the package is a zip with 3D/3dmodel.model (Python's zipfile and XML
  parser): one <object type="model"> per body named after it, one
  <item> per object;
- `-f 3mf` on standard output gives the same bytes as `-o spool.3mf`;
- refusals leave nothing: a model whose units 3MF has no name for (exit 3,
  an existing output unchanged), an unwritable directory (exit 3, nothing
  created), `--iso` to .3mf (usage error 2).
Without lib3mf: every 3MF write exits 3 saying so, writing nothing.

Usage: test_3mf.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
import zipfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner  # noqa: E402

NS = "{http://schemas.microsoft.com/3dmanufacturing/core/2015/02}"


def built_with_lib3mf(build):
    with open(os.path.join(build, "CMakeCache.txt")) as f:
        return re.search(r"^COONS_WITH_LIB3MF:BOOL=(ON|1|TRUE)$", f.read(), re.M) is not None


def stl_box_volume(path):
    with open(path, "rb") as f:
        data = f.read()
    (n,) = struct.unpack_from("<I", data, 80)
    lo, hi, vol = [1e300] * 3, [-1e300] * 3, 0.0
    for i in range(n):
        v = struct.unpack_from("<12f", data, 84 + 50 * i)[3:]
        a, b, c = v[0:3], v[3:6], v[6:9]
        for p in (a, b, c):
            lo = [min(lo[k], p[k]) for k in range(3)]
            hi = [max(hi[k], p[k]) for k in range(3)]
        vol += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0
    return [hi[k] - lo[k] for k in range(3)], vol


def prusa_info(path):
    """The [file] blocks of `prusa-slicer --info` as dicts (one per object)."""
    p = subprocess.run(["prusa-slicer", "--info", path], capture_output=True, text=True,
                       timeout=300)
    blocks, cur = [], None
    for line in p.stdout.splitlines():
        if line == f"[{os.path.basename(path)}]":
            cur = {}
            blocks.append(cur)
        elif cur is not None and re.match(r"^\w+ = ", line):
            k, v = line.split(" = ", 1)
            cur[k.strip()] = v.strip()
    return p.returncode, blocks, p.stdout + p.stderr


REPAIRS = ("needed_repair", "number_of_errors", "degenerate_facets", "edges_fixed",
           "facets_removed", "facets_added", "facets_reversed", "backwards_edges")


def clean(block):
    return block.get("manifold") == "yes" and not any(
        float(block.get(k, "0")) != 0 for k in REPAIRS)


def near(a, b, tol):
    return abs(float(a) - b) <= tol


def main():
    r = Runner(__doc__)
    ex = os.path.join(r.src, "examples")
    spool = os.path.join(ex, "spool.json")
    blend = os.path.join(ex, "body-blend-cubic.json")
    with tempfile.TemporaryDirectory() as tmp:
        if not built_with_lib3mf(r.build):
            out = os.path.join(tmp, "spool.3mf")
            st, _, err = r.run([spool, "-o", out])
            r.check("without lib3mf: -o .3mf exits 3 saying why", st == 3 and
                    "without lib3mf" in err, err)
            r.check("without lib3mf: nothing written", os.listdir(tmp) == [], os.listdir(tmp))
            st, out_b, err = r.run([spool, "-f", "3mf"], binary=True)
            r.check("without lib3mf: -f 3mf to stdout exits 3, no bytes", st == 3 and
                    out_b == b"", err)
            r.finish()
            return
        r.check("prusa-slicer is installed", shutil.which("prusa-slicer") is not None)

        # The spool, against PrusaSlicer and the STL of the same model.
        p3 = os.path.join(tmp, "spool.3mf")
        ps = os.path.join(tmp, "spool.stl")
        st, _, err = r.run([spool, "-o", p3])
        r.check("spool -o .3mf", st == 0, err)
        st, _, err = r.run([spool, "-o", ps])
        r.check("spool -o .stl", st == 0, err)
        size, vol = stl_box_volume(ps)
        rc, blocks, text = prusa_info(p3)
        b = blocks[0] if blocks else {}
        r.check("PrusaSlicer reads the spool: one object, manifold, nothing repaired",
                rc == 0 and len(blocks) == 1 and clean(b), text[-1500:])
        r.check("spool is 12 mm across and 10 mm high",
                b and near(b["size_x"], 12, 0.02) and near(b["size_y"], 12, 0.02) and
                near(b["size_z"], 10, 1e-4), str(b))
        r.check(f"spool volume = the STL's {vol:.4f}", b and near(b["volume"], vol, 1e-5 * vol),
                str(b) + f" STL size {size}")

        # Standard output: the same bytes.
        st, data, err = r.run([spool, "-f", "3mf"], binary=True)
        with open(p3, "rb") as f:
            r.check("-f 3mf on stdout = -o spool.3mf, byte for byte", st == 0 and
                    data == f.read(), err)

        # operation "none": one object per body.
        with open(blend) as f:
            model = json.load(f)
        names = [bd["name"] for bd in model["bodies"]]
        pb = os.path.join(tmp, "blend.3mf")
        st, _, err = r.run([blend, "-o", pb])
        r.check("body-blend-cubic -o .3mf", st == 0, err)
        with zipfile.ZipFile(pb) as z:
            r.check("the package is a zip that tests clean", z.testzip() is None)
            root = ET.fromstring(z.read("3D/3dmodel.model"))
        objs = root.findall(f"{NS}resources/{NS}object")
        items = root.findall(f"{NS}build/{NS}item")
        r.check("unit=\"millimeter\" for \"mm\"", root.get("unit") == "millimeter", root.attrib)
        r.check("one object of type model per body, named after it",
                [o.get("name") for o in objs] == names and
                all(o.get("type") == "model" for o in objs), [o.attrib for o in objs])
        r.check("one build item per object",
                [i.get("objectid") for i in items] == [o.get("id") for o in objs])
        rc, blocks, text = prusa_info(pb)
        r.check("PrusaSlicer lists three clean objects",
                rc == 0 and len(blocks) == 3 and all(clean(x) for x in blocks), text[-2000:])
        b0 = blocks[0] if blocks else {}
        r.check("the box body: 10 x 10 x 13, volume 1000",
                b0 and near(b0["size_x"], 10, 1e-4) and near(b0["size_y"], 10, 1e-4) and
                near(b0["size_z"], 13, 1e-4) and near(b0["volume"], 1000, 0.01), str(b0))

        # Units "in": PrusaSlicer scales by 25.4.
        model["units"] = "in"
        mi = os.path.join(tmp, "inch.json")
        with open(mi, "w") as f:
            json.dump(model, f)
        pi = os.path.join(tmp, "inch.3mf")
        st, _, err = r.run([mi, "-o", pi])
        r.check("inch model -o .3mf", st == 0, err)
        with zipfile.ZipFile(pi) as z:
            unit = ET.fromstring(z.read("3D/3dmodel.model")).get("unit")
        r.check("unit=\"inch\" for \"in\"", unit == "inch", unit)
        rc, blocks, text = prusa_info(pi)
        bi = blocks[0] if blocks else {}
        r.check("PrusaSlicer reads the inch box 25.4 times as large",
                rc == 0 and bi and near(bi["size_x"], 254, 1e-3) and
                near(bi["size_z"], 330.2, 1e-3) and
                near(bi["volume"], 1000 * 25.4 ** 3, 2e-6 * 1000 * 25.4 ** 3),
                str(bi))

        # Refusals: nothing written, nothing changed.
        model["units"] = "furlong"
        mf = os.path.join(tmp, "furlong.json")
        with open(mf, "w") as f:
            json.dump(model, f)
        keep = os.path.join(tmp, "keep.3mf")
        with open(keep, "wb") as f:
            f.write(b"previous\n")
        before = sorted(os.listdir(tmp))
        st, _, err = r.run([mf, "-o", keep])
        with open(keep, "rb") as f:
            r.check("units 3MF cannot name: exit 3, the message names them, output unchanged",
                    st == 3 and "'furlong'" in err and f.read() == b"previous\n", err)
        r.check("... and no temporary file is left", sorted(os.listdir(tmp)) == before)
        ro = os.path.join(tmp, "ro")
        os.mkdir(ro)
        os.chmod(ro, 0o555)
        if os.geteuid() == 0:
            ro = os.path.join(tmp, "missing")  # root ignores permissions
        st, _, err = r.run([spool, "-o", os.path.join(ro, "x.3mf")])
        r.check("unwritable directory: exit 3, nothing created",
                st == 3 and (not os.path.isdir(ro) or os.listdir(ro) == []), err)
        os.chmod(os.path.join(tmp, "ro"), 0o755)
        st, _, err = r.run([spool, "--iso", "u=0.5", "-o", os.path.join(tmp, "iso.3mf")])
        r.check("--iso to .3mf: usage error 2, nothing written",
                st == 2 and not os.path.exists(os.path.join(tmp, "iso.3mf")), err)
    r.finish()


if __name__ == "__main__":
    main()
