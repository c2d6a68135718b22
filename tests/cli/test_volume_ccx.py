# SPDX-License-Identifier: GPL-3.0-or-later
"""The .inp writer against the real CalculiX (ccx): a linear-elasticity
patch test on decks written by build/tests/vm_sample.

Each deck is *INCLUDEd, unchanged, into an analysis deck that adds a
material, a section on EALL, a hydrostatic pressure p on the faces of the
*SURFACEs the writer wrote (*DSLOAD) and, on the remaining boundary, the
displacement of the exact solution, which for any closed body is the
constant stress sigma = -p I and u = -p (1 - 2 nu) / E x. ccx must then
reproduce it at every node and every integration point:

- a wrong node order inverts elements (ccx: "nonpositive jacobian") or
  gives another volume (the sum of ccx's element volumes EVOL must be the
  volume of the mapped cube: exactly 0.992 for the quadratic map, whose
  hex20 interpolation is exact; that of the trilinear cells, computed here
  from the map, for hex8; 1/2 for the apex; 1/3 for the pyramid);
- a wrong face label puts the pressure on another face (an interior one
  or the opposite side), so that the field is no longer constant;
- wedges (C3D6, at the apex) and pyramids (degenerate C3D8) must be
  accepted by ccx and be exact too;
- every example but the two whose bodies overlap (chair, union-three-
  bodies, refused), hex8 at --resolution 4 and the control lattices also
  hex20 at 2: every node held at the exact displacement, ccx accepts every
  element and gives the stress -p I at every integration point, and the
  element volumes add up to the bodies' (--info) within 40%.

The maps are vm_sample's (tests/tools/vm_sample.c). Its face sets of the
cells at a collapsed face (the "lo" part of the apex and pyramid samples)
are taken from a node that several lattice points share, so they are not
the true boundary there: the exact displacement is prescribed on that
part's lateral boundary instead (found from the coordinates), and the
pressure goes on the other surfaces.
"""
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner  # noqa: E402

E, NU, P = 1000.0, 0.3, 1.0
EPS = -P * (1 - 2 * NU) / E  # the exact strain, the same in x, y and z


# ---- an .inp reader, from the Abaqus keyword descriptions ------------------

def read_inp(path):
    """Returns nodes {id: (x, y, z)}, elements {id: (type, [nodes])},
    nsets, elsets {name: [ids]} and surfaces {name: [(elset or id, label)]}.
    Continuation lines of *ELEMENT end with a comma."""
    nodes, elems, nsets, elsets, surfs = {}, {}, {}, {}, {}
    kw, opts, pending = None, {}, None
    with open(path) as f:
        lines = f.read().split("\n")
    for raw in lines:
        line = raw.strip()
        if not line or line.startswith("**"):
            continue
        if line.startswith("*"):
            parts = [p.strip() for p in line.split(",")]
            kw = parts[0].upper()
            opts = {}
            for p in parts[1:]:
                k, _, v = p.partition("=")
                opts[k.strip().upper()] = v.strip()
            if kw == "*NSET":
                nsets.setdefault(opts["NSET"], [])
            elif kw == "*ELSET":
                elsets.setdefault(opts["ELSET"], [])
            elif kw == "*SURFACE":
                surfs.setdefault(opts["NAME"], [])
            continue
        fields = [x.strip() for x in line.split(",")]
        if kw == "*NODE":
            nodes[int(fields[0])] = tuple(float(x) for x in fields[1:4])
            if "NSET" in opts:
                nsets.setdefault(opts["NSET"], []).append(int(fields[0]))
        elif kw == "*ELEMENT":
            if pending is None:
                pending = [int(x) for x in fields if x]
            else:
                pending += [int(x) for x in fields if x]
            if line.endswith(","):
                continue
            elems[pending[0]] = (opts["TYPE"], pending[1:])
            if "ELSET" in opts:
                elsets.setdefault(opts["ELSET"], []).append(pending[0])
            pending = None
        elif kw == "*NSET":
            nsets[opts["NSET"]] += [int(x) for x in fields if x]
        elif kw == "*ELSET":
            elsets[opts["ELSET"]] += [int(x) for x in fields if x]
        elif kw == "*SURFACE":
            surfs[opts["NAME"]].append((fields[0], fields[1]))
    return nodes, elems, nsets, elsets, surfs


# ---- the maps of vm_sample and the exact volumes ---------------------------

def vm_map(which, r, s, t):
    if which == "apex":
        return (r, r * s, t)
    if which == "pyramid":
        return (r * (s - 0.5), r * (t - 0.5), r)
    return (r + 0.2 * s * s, s + 0.1 * r * t, t + 0.15 * r * r)


def det3(a, b, c):
    return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]))


def trilinear_volume(which, n=2):
    """Volume of the trilinear cells through the map's lattice points
    (2-point Gauss is exact: det J is of degree 2 in each variable)."""
    g = [0.5 - 0.5 / math.sqrt(3), 0.5 + 0.5 / math.sqrt(3)]
    vol = 0.0
    for i in range(n):
        for j in range(n):
            for k in range(n):
                c = {}
                for a in (0, 1):
                    for b in (0, 1):
                        for d in (0, 1):
                            c[a, b, d] = vm_map(which, (i + a) / n, (j + b) / n, (k + d) / n)
                for x in g:
                    for y in g:
                        for z in g:
                            w = {(a, b, d): ((x if a else 1 - x), (y if b else 1 - y),
                                             (z if d else 1 - z))
                                 for a in (0, 1) for b in (0, 1) for d in (0, 1)}
                            jac = []
                            for axis in range(3):
                                col = [0.0, 0.0, 0.0]
                                for key, p in c.items():
                                    f = (1 if key[axis] else -1)
                                    for o in range(3):
                                        if o != axis:
                                            f *= w[key][o]
                                    for q in range(3):
                                        col[q] += f * p[q]
                                jac.append(col)
                            vol += det3(*jac) / 8.0
    return vol


# ---- ccx --------------------------------------------------------------------

def read_dat(path):
    """The blocks of a ccx .dat file: {"displacements": rows, ...}, each row
    a list of numbers."""
    blocks, cur = {}, None
    with open(path) as f:
        for line in f:
            s = line.strip()
            if not s:
                continue
            m = re.match(r"^(displacements|stresses|volume)\b", s)
            if m:
                cur = blocks.setdefault(m.group(1), [])
                continue
            try:
                cur.append([float(x) for x in s.split()])
            except (ValueError, AttributeError):
                cur = None
    return blocks


def analysis(mesh, prescribed, surfaces, nodes):
    out = ["*INCLUDE, INPUT=" + mesh,
           "*MATERIAL, NAME=STEEL", "*ELASTIC", f"{E}, {NU}",
           "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL",
           "*STEP", "*STATIC", "*BOUNDARY"]
    for n in sorted(prescribed):
        for dof in (1, 2, 3):
            out.append(f"{n}, {dof}, {dof}, {EPS * nodes[n][dof - 1]:.13e}")
    out.append("*DSLOAD")
    for s in surfaces:
        out.append(f"{s}, P, {P}")
    out += ["*NODE PRINT, NSET=NALL", "U", "*EL PRINT, ELSET=EALL", "S",
            "*EL PRINT, ELSET=EALL", "EVOL", "*END STEP", ""]
    return "\n".join(out)


def patch_test(r, tmp, element, which):
    tag = f"{element} {which}"
    d = os.path.join(tmp, f"{element}_{which}")
    os.makedirs(d)
    mesh = os.path.join(d, "mesh.inp")
    vm = os.path.join(r.build, "tests", "vm_sample")
    p = subprocess.run([vm, mesh, element, which], capture_output=True, text=True)
    if not r.check(f"{tag}: vm_sample writes the deck", p.returncode == 0, p.stderr):
        return
    nodes, elems, nsets, elsets, surfs = read_inp(mesh)
    if which == "quad":
        # the r = 0 face is the curved face x = 0.2 s^2: held at the exact
        # displacement; pressure on every other face
        prescribed = set(nsets["LO_U0"])
        surfaces = [s for s in surfs if s != "LO_U0_S" and surfs[s]]
    else:
        # the lo part's lateral boundary, from the coordinates
        def lateral(x):
            if which == "apex":
                return x[0] <= 0.5 + 1e-12 and (abs(x[1]) < 1e-12 or abs(x[1] - x[0]) < 1e-12)
            h = x[2] / 2
            return x[2] <= 0.5 + 1e-12 and (abs(abs(x[0]) - h) < 1e-12
                                             or abs(abs(x[1]) - h) < 1e-12)
        prescribed = {n for n, x in nodes.items() if lateral(x)}
        surfaces = [s for s in surfs if surfs[s] and
                    (s.startswith("HI_") or (which == "apex" and s in ("LO_W0_S", "LO_W1_S")))]
    free = [n for n in nodes if n not in prescribed]
    types = sorted({t for t, _ in elems.values()})
    job = os.path.join(d, "job.inp")
    with open(job, "w") as f:
        f.write(analysis("mesh.inp", prescribed, surfaces, nodes))
    p = subprocess.run(["ccx", "-i", "job"], cwd=d, capture_output=True, text=True, timeout=300)
    ok = p.returncode == 0 and "*ERROR" not in p.stdout
    if not r.check(f"{tag}: ccx runs the deck ({', '.join(types)}; {len(free)} free nodes, "
                   f"{len(surfaces)} loaded surfaces)", ok, (p.stdout + p.stderr)[-2000:]):
        return
    dat = read_dat(os.path.join(d, "job.dat"))
    disp = dat.get("displacements", [])
    scale = max(abs(EPS * c) for x in nodes.values() for c in x)
    err = max((abs(row[1 + k] - EPS * nodes[int(row[0])][k]) for row in disp for k in range(3)),
              default=math.inf)
    r.check(f"{tag}: every node moves by -p(1-2nu)/E x (max error {err / scale:.1e} of the largest)",
            len(disp) == len(nodes) and err <= 2e-6 * scale, f"{len(disp)} rows")
    st = dat.get("stresses", [])
    serr = max((max(max(abs(row[2 + k] + P) for k in range(3)),
                    max(abs(row[5 + k]) for k in range(3))) for row in st), default=math.inf)
    r.check(f"{tag}: the stress is -p I at all {len(st)} integration points "
            f"(max error {serr / P:.1e} p)",
            st and {int(x[0]) for x in st} == set(elems) and serr <= 2e-6 * P)
    vol = sum(row[1] for row in dat.get("volume", []))
    want = {"apex": 0.5, "pyramid": 1.0 / 3.0}.get(which)
    if want is None:
        want = 0.992 if element == "hex20" else trilinear_volume("quad")
    r.check(f"{tag}: the element volumes add up to the body's ({vol!r} vs {want!r})",
            abs(vol - want) <= 2e-6 * want)
    return elems


OVERLAPPING = ("chair.json", "union-three-bodies.json")
LATTICES = ("lattice-ffd.json", "chair-lattice.json", "lattice-l-bracket.json",
            "lattice-ring.json", "lattice-instanced.json")


def examples(r, tmp):
    """Every example but the two whose bodies overlap, as coons2stl's .inp
    (hex8 at --resolution 4; the control lattices also hex20 at 2), read by
    ccx: every node held at the exact displacement of the uniform strain
    -p(1-2nu)/E, ccx must accept every element (no nonpositive Jacobian at
    its integration points) and give the stress -p I at all of them; the
    element volumes add up to the bodies' (--info) within 40% (a coarse
    lattice: no body lost or counted twice)."""
    exdir = os.path.join(r.src, "examples")
    for name in sorted(os.listdir(exdir)):
        if not name.endswith(".json"):
            continue
        model = os.path.join(exdir, name)
        runs = [("hex8", "4")] + ([("hex20", "2")] if name in LATTICES else [])
        for element, res in runs:
            d = os.path.join(tmp, f"ex-{name}-{element}")
            os.makedirs(d)
            mesh = os.path.join(d, "mesh.inp")
            st, _, err = r.run([model, "-o", mesh, "--element", element, "--resolution", res])
            label = f"{name} {element} --resolution {res}"
            if name in OVERLAPPING:
                r.check(f"{label}: refused as not conformal (its bodies overlap)",
                        st == 3 and "conformal" in err, err)
                break
            if not r.check(f"{label}: coons2stl writes the deck", st == 0, err):
                continue
            nodes, elems = read_inp(mesh)[:2]
            with open(os.path.join(d, "job.inp"), "w") as f:
                f.write(analysis("mesh.inp", set(nodes), [], nodes))
            p = subprocess.run(["ccx", "-i", "job"], cwd=d, capture_output=True, text=True,
                               timeout=300)
            if not r.check(f"{label}: ccx accepts all {len(elems)} elements",
                           p.returncode == 0 and "*ERROR" not in p.stdout,
                           (p.stdout + p.stderr)[-1500:]):
                continue
            dat = read_dat(os.path.join(d, "job.dat"))
            st_ = dat.get("stresses", [])
            serr = max((max(max(abs(row[2 + k] + P) for k in range(3)),
                            max(abs(row[5 + k]) for k in range(3))) for row in st_),
                       default=math.inf)
            vol = sum(row[1] for row in dat.get("volume", []))
            rc, out, e2 = r.run(["--info", "--no-solid", model])
            want = sum(abs(b["volume"]) for b in json.loads(out)["bodies"]) if rc == 0 \
                else math.nan
            r.check(f"{label}: stress -p I at every integration point (max error "
                    f"{serr / P:.1e} p), volume {vol:.6g} vs the bodies' {want:.6g}",
                    serr <= 1e-6 * P and abs(vol - want) <= 0.4 * want, e2)
            shutil.rmtree(d, ignore_errors=True)


def main():
    r = Runner(__doc__)
    if not r.check("ccx is installed", shutil.which("ccx") is not None):
        r.finish()
    with tempfile.TemporaryDirectory() as tmp:
        for element in ("hex8", "hex20"):
            for which in ("quad", "apex", "pyramid"):
                elems = patch_test(r, tmp, element, which)
                if elems and element == "hex8" and which == "apex":
                    n6 = sum(t == "C3D6" for t, _ in elems.values())
                    r.check("hex8 apex: the 4 cells at the collapsed face are C3D6", n6 == 4)
                if elems and element == "hex20":
                    r.check(f"hex20 {which}: every element is C3D20 with 20 nodes",
                            all(t == "C3D20" and len(v) == 20 for t, v in elems.values()))
        examples(r, tmp)
    r.finish()


if __name__ == "__main__":
    main()
