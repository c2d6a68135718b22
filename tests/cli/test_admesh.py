#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Every example's STL checked and repaired by the real `admesh`.

admesh (0.98) reads an STL, matches facet edges, and fixes what it finds:
disconnected facets, degenerate facets, reversed facets, holes, and facet
normals that disagree with the facet's vertices ("Normals fixed": the
stored normal differs from the one admesh computes from the stored float32
vertices). A printable file needs none of it. For the STL of every
examples/*.json (binary and ASCII) at the model's tolerance, and for the
chair and the union of three bodies at -t 0.001 (binary; the union in ASCII
too), where thin triangles of the union once gave 85 and 2 fixed normals
(normals computed from the double vertices), admesh's report must say: as many facets as the
file holds (its own count), after as before; no disconnected facet; every
repair counter (degenerate facets, edges fixed, facets removed, added,
reversed, backwards edges, normals fixed) 0; a positive volume (outward
facets). In a build without CGAL, models whose union needs it are left
out (coons2stl refuses them).

Usage: test_admesh.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
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

COUNTERS = ("Degenerate facets", "Edges fixed", "Facets removed", "Facets added",
            "Facets reversed", "Backwards edges", "Normals fixed")
# Examples meshed again at -t 0.001 (issue 16: the thin triangles of the union).
FINE = ("chair", "union-three-bodies")


def stl_facets(path):
    """The facet count of a binary or ASCII STL, read from the file."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:5] == b"solid" and b"facet" in data[:1024]:
        return len(re.findall(rb"^\s*facet normal", data, re.M))
    (n,) = struct.unpack_from("<I", data, 80)
    if len(data) != 84 + 50 * n:
        raise ValueError(f"{path}: {len(data)} bytes for {n} triangles")
    return n


def parse_admesh(text):
    """admesh's report as {label: (original, final)} or {label: value}."""
    out = {}
    for line in text.splitlines():
        m = re.match(r"^(Number of facets|Facets with [123] disconnected edges?|"
                     r"Total disconnected facets)\s*:\s*(\d+)\s+(\d+)\s*$", line)
        if m:
            out[m.group(1)] = (int(m.group(2)), int(m.group(3)))
            continue
        m = re.match(r"^(Number of parts)\s*:\s*(\d+)\s+Volume\s*:\s*(\S+)", line)
        if m:
            out["Number of parts"] = int(m.group(2))
            out["Volume"] = float(m.group(3))
            continue
        m = re.match(r"^(" + "|".join(COUNTERS) + r")\s*:\s*(\d+)\s*$", line)
        if m:
            out[m.group(1)] = int(m.group(2))
    return out


def check_one(r, label, stl):
    p = subprocess.run(["admesh", stl], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, timeout=300)
    rep = parse_admesh(p.stdout)
    missing = [k for k in ("Number of facets", "Total disconnected facets", "Volume")
               + COUNTERS if k not in rep]
    if not r.check(f"{label}: admesh exits 0 and reports every counter",
                   p.returncode == 0 and not missing, f"missing {missing}:\n{p.stdout}"):
        return
    n = stl_facets(stl)
    r.check(f"{label}: admesh reads {n} facets, {n} after its fixes",
            rep["Number of facets"] == (n, n), f"{rep['Number of facets']}")
    bad = {k: v for k, v in rep.items()
           if (k.startswith("Facets with") or k == "Total disconnected facets") and v != (0, 0)}
    bad.update({k: rep[k] for k in COUNTERS if rep[k] != 0})
    r.check(f"{label}: nothing disconnected, nothing repaired (normals fixed "
            f"{rep['Normals fixed']})", not bad, f"{bad}\n{p.stdout}")
    r.check(f"{label}: positive volume {rep['Volume']:.6g} (outward)", rep["Volume"] > 0)


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
    if not r.need("admesh"):
        r.finish()
    tmp = tempfile.mkdtemp(prefix="coons-admesh-")
    try:
        r.check("examples found", len(clitest.examples(r.src, every=True)) > 10)
        every = clitest.examples(r.src, every=True)
        names = [os.path.splitext(os.path.basename(e))[0] for e in every]
        for name in FINE:
            r.check(f"example {name} exists", name in names)
        # the representative examples under a sanitizer, and always FINE's
        some = r.examples()
        examples = [e for e, n in zip(every, names) if e in some or n in FINE]
        names = [os.path.splitext(os.path.basename(e))[0] for e in examples]
        cgal = have_cgal(r.build)
        runs = []
        for ex, name in zip(examples, names):
            runs.append((name, ex, [], "stl"))
            runs.append((name, ex, ["-f", "stl-ascii"], "ascii"))
            if name in FINE:
                runs.append((name, ex, ["-t", "0.001"], "stl at -t 0.001"))
            if name == FINE[1]:
                # ASCII at -t 0.001 too (the chair's would take 3 s more).
                runs.append((name, ex, ["-t", "0.001", "-f", "stl-ascii"], "ascii at -t 0.001"))
        for i, (name, ex, args, what) in enumerate(runs):
            stl = os.path.join(tmp, f"{i}-{name}.stl")
            st, _, err = r.run(["-q"] + args + ["-o", stl, ex])
            if st == 3 and "CGAL" in err and not cgal:
                print(f"n/a  {name} ({what}): its union needs CGAL, not in this build")
                continue
            if r.check(f"{name} ({what}): coons2stl writes it", st == 0, err):
                check_one(r, f"{name} ({what})", stl)
            os.remove(stl) if os.path.exists(stl) else None
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    r.finish()


if __name__ == "__main__":
    main()
