#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Every example's STL read and sliced by the real PrusaSlicer (2.5) CLI.

For each examples/*.json, coons2stl -o x.stl, then:
- `prusa-slicer --info` (one run for all files): the model is `manifold =
  yes`, nothing was repaired (PrusaSlicer prints degenerate_facets,
  edges_fixed, facets_removed, facets_reversed, backwards_edges or
  open_edges only when it found some: none of them may appear), it has as
  many facets as the file holds, its volume is the volume of the file's
  triangles (computed here; relative 1e-4, PrusaSlicer sums in float), and
  its size is the file's bounding box;
- `prusa-slicer --export-gcode` with the default printer and print profile
  (layer height 0.3 mm, first layer 0.35 mm; seam position "rear", since 2.5's default seam
  placer spends 1 s per model on visibility rays): exit 0, no error (such
  as "There is an object with no extrusions in the first layer", what a
  model standing on a point gives), a G-code file whose extrusion moves
  start at the first layer's height (the model stands on the bed) and
  reach its top: above height - 2 mm (the nail's tip, thinner than an
  extrusion near its point, prints nothing there) and at most half a layer
  above it (layers are cut at their middle); heights as the G-code's own
  configuration comments give them.
The slicer runs two at a time. In a build without CGAL, models whose union
needs it are left out (coons2stl refuses them).

Usage: test_prusaslicer.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import concurrent.futures
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

REPAIRS = ("degenerate_facets", "edges_fixed", "facets_removed", "facets_added",
           "facets_reversed", "backwards_edges", "open_edges")
SLICE = ["--seam-position", "rear"]


def read_stl(path):
    """Triangles of a binary STL, as 9-tuples of floats."""
    with open(path, "rb") as f:
        data = f.read()
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


def bbox(tris):
    lo = [min(t[k] for t in tris for k in range(i, 9, 3)) for i in range(3)]
    hi = [max(t[k] for t in tris for k in range(i, 9, 3)) for i in range(3)]
    return lo, hi


def parse_info(text):
    """PrusaSlicer's --info: {file base name: {key: value}}."""
    out, cur = {}, None
    for line in text.splitlines():
        m = re.match(r"^\[(.+)\]$", line.strip())
        if m:
            cur = out.setdefault(os.path.basename(m.group(1)), {})
            continue
        m = re.match(r"^(\w+)\s*=\s*(.*?)\s*$", line)
        if m and cur is not None:
            cur[m.group(1)] = m.group(2)
    return out


def slice_one(stl):
    gcode = stl[:-4] + ".gcode"
    p = subprocess.run(["prusa-slicer", "--export-gcode", "--loglevel", "1"] + SLICE +
                       ["-o", gcode, stl], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, timeout=600)
    zs, conf = [], {}
    if os.path.exists(gcode):
        z = None
        with open(gcode) as f:
            for line in f:
                m = re.match(r"^; (first_layer_height|layer_height) = ([0-9.]+)$", line)
                if m:
                    conf[m.group(1)] = float(m.group(2))
                if not line.startswith("G1"):
                    continue
                w = line.split(";")[0].split()
                for tok in w[1:]:
                    if tok[0] == "Z":
                        z = float(tok[1:])
                # An extrusion: moves in X or Y with E > 0.
                if z is not None and any(t[0] in "XY" for t in w[1:]) and \
                        any(t[0] == "E" and float(t[1:]) > 0 for t in w[1:]):
                    zs.append(z)
    return p.returncode, p.stdout, zs, conf


def have_cgal(build):
    """Whether this build has the Boolean (CGAL) layer, from its CMake cache.
    Without it, models whose bodies overlap cannot be united (coons2stl exits
    3 and names CGAL): those are left out, and only then."""
    try:
        with open(os.path.join(build, "CMakeCache.txt")) as f:
            return "COONS_WITH_CGAL:BOOL=ON" in f.read()
    except OSError:
        return True  # unknown: nothing is excused


def main():
    r = Runner(__doc__)
    # A real client of the output: missing, it fails, never skips.
    if not r.need("prusa-slicer"):
        r.finish()
    tmp = tempfile.mkdtemp(prefix="coons-prusaslicer-")
    try:
        r.check("examples found", len(clitest.examples(r.src, every=True)) > 10)
        examples = r.examples()
        stls = {}
        cgal = have_cgal(r.build)
        for ex in examples:
            name = os.path.splitext(os.path.basename(ex))[0]
            stl = os.path.join(tmp, name + ".stl")
            st, _, err = r.run(["-q", "-o", stl, ex])
            if st == 3 and "CGAL" in err and not cgal:
                print(f"n/a  {name}: its union needs CGAL, not in this build")
                continue
            if r.check(f"{name}: coons2stl -o {name}.stl", st == 0, err):
                stls[name] = stl
        names = sorted(stls)

        # --info, one run for every file.
        p = subprocess.run(["prusa-slicer", "--info", "--loglevel", "1"] +
                           [stls[n] for n in names], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True, timeout=600)
        info = parse_info(p.stdout)
        r.check("prusa-slicer --info exits 0", p.returncode == 0, p.stderr[-2000:])
        for name in names:
            tris = read_stl(stls[name])
            i = info.get(name + ".stl")
            if not r.check(f"{name}: --info reports it", i is not None, p.stdout[-2000:]):
                continue
            r.check(f"{name}: manifold = yes", i.get("manifold") == "yes", f"{i}")
            fixed = {k: i[k] for k in REPAIRS if k in i}
            r.check(f"{name}: nothing repaired", not fixed, f"{fixed}")
            r.check(f"{name}: {len(tris)} facets", i.get("number_of_facets") == str(len(tris)),
                    f"{i.get('number_of_facets')}")
            v = volume(tris)
            try:
                pv = float(i.get("volume", "nan"))
            except ValueError:
                pv = float("nan")
            r.check(f"{name}: volume {pv:.7g} = the file's {v:.7g}",
                    v > 0 and abs(pv - v) <= 1e-4 * v, f"{i}")
            lo, hi = bbox(tris)
            got = [float(i.get(k, "nan")) for k in ("min_x", "min_y", "min_z",
                                                     "max_x", "max_y", "max_z")]
            r.check(f"{name}: bounding box", all(abs(a - b) <= 1e-4 * (1 + abs(b)) for a, b in
                                                 zip(got, lo + hi)), f"{got} vs {lo} {hi}")

        # Slicing, two at a time.
        with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
            results = dict(zip(names, pool.map(slice_one, [stls[n] for n in names])))
        for name in names:
            rc, log, zs, conf = results[name]
            said = [ln for ln in log.splitlines() if re.search(r"error|no extrusions", ln, re.I)]
            r.check(f"{name}: prusa-slicer --export-gcode exits 0, no error",
                    rc == 0 and not said, f"exit {rc}: {said or log[-1500:]}")
            if not r.check(f"{name}: the G-code extrudes and gives its layer heights",
                           len(zs) > 0 and len(conf) == 2, f"{conf}"):
                continue
            first, layer = conf["first_layer_height"], conf["layer_height"]
            lo, hi = bbox(read_stl(stls[name]))
            height = hi[2] - lo[2]
            r.check(f"{name}: extrusion from the first layer (z {min(zs):.3g}) to the top "
                    f"(z {max(zs):.3g} of {height:.4g})",
                    abs(min(zs) - first) < 1e-6 and height - 2.0 <= max(zs)
                    <= height + layer / 2 + 1e-6, f"{min(zs)} {max(zs)}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    r.finish()


if __name__ == "__main__":
    main()
