# SPDX-License-Identifier: GPL-3.0-or-later
"""coons2stl's .inp volume meshes solved by the real CalculiX (ccx) against
two closed forms of linear elasticity (issue 10):

(a) examples/cantilever.json, a box L x h x b (100 x 10 x 10) meshed with
    `--element hex20 --resolution 20,2,2`: the face set BEAM_U0 clamped,
    a shear load P on the face u1 (the consistent nodal loads of a uniform
    traction on the C3D20 faces of BEAM_U1_S, *CLOAD), a static step; the
    deflection of the tip's centre against Timoshenko's beam,
    P L^3 / (3 E I) + P L / (k G A) with k = 10 (1 + nu) / (12 + 11 nu),
    within 2%;
(b) examples/thick-cylinder.json, a quarter of a thick-walled tube (radii
    a = 10, b = 20, height 5) as an exact NURBS volume, and
    thick-cylinder-distorted.json, the same shape with an uneven interior
    (radial degree 2 with its middle control points at r = 12, angular
    weights 1, 1.6 sqrt(1/2), 2.56), each meshed with `--element hex20
    --resolution 4,8,1`: pressure p on the inner face (*DSLOAD on
    TUBE_U0_S), symmetry on the cut planes (uy = 0 on TUBE_V0, ux = 0 on
    TUBE_V1), plane strain (uz = 0 on TUBE_W0 and TUBE_W1); the radial
    displacement of every node against Lame's plane-strain solution
    u(r) = (1 + nu) a^2 p / (E (b^2 - a^2)) ((1 - 2 nu) r + b^2 / r),
    within 0.5%.

(c) the same cantilever as a control lattice of 4 x 1 x 2 body 0 cells
    sharing faces, each at --resolution 5,2,1 (the same 20 x 2 x 2 mesh):
    the tip deflection equals the single body's to 1e-6 relative;
(d) examples/lattice-l-bracket.json (two arms meeting only along an edge),
    hex20: one arm's end clamped, a force on the other's end: ccx solves
    it, the reaction balances the force, the element volumes add up to the
    bodies' (--info) within 1e-3.

The decks are coons2stl's output, *INCLUDEd unchanged; only the sets it
writes carry the boundary conditions and loads.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner  # noqa: E402
from test_volume_ccx import read_dat, read_inp  # noqa: E402

E, NU = 210000.0, 0.3
HEADER = ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{E}, {NU}",
          "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL"]
# C3D20 face S4 (2-6-7-3): its corners and its edge nodes, 1-based
S4_CORNERS, S4_EDGES = (2, 6, 7, 3), (18, 14, 19, 10)


def mesh(r, d, model, out, resolution):
    path = os.path.join(d, out)
    st, _, err = r.run([os.path.join(r.src, "examples", model), "-o", path,
                        "--element", "hex20", "--resolution", resolution])
    ok = r.check(f"{os.path.basename(model)}: coons2stl writes {out} (hex20, --resolution {resolution})",
                 st == 0 and os.path.exists(path), err)
    return read_inp(path) if ok else None


def ccx(r, d, what, lines):
    with open(os.path.join(d, "job.inp"), "w") as f:
        f.write("\n".join(lines + [""]))
    p = subprocess.run(["ccx", "-i", "job"], cwd=d, capture_output=True, text=True,
                       timeout=600)
    ok = p.returncode == 0 and "*ERROR" not in p.stdout
    if not r.check(f"{what}: ccx solves it", ok, (p.stdout + p.stderr)[-2000:]):
        return None
    return read_dat(os.path.join(d, "job.dat"))


def tip_deflection(r, d, label, model, resolution, clamp, tips, L, h, b, P):
    """Meshes `model` (hex20), clamps the node sets `clamp`, puts a shear
    load P on the surfaces `tips` (the consistent nodal loads of a uniform
    traction on their C3D20 S4 faces) and returns ccx's y displacement of
    the tip's centre (L, h/2, b/2)."""
    deck = mesh(r, d, model, "box.inp", resolution)
    if not deck:
        return None
    nodes, elems, nsets, elsets, surfs = deck
    # consistent loads of a uniform traction P / (h b) along y on the S4
    # faces of the tip surfaces: -1/12 of a face's force at each corner,
    # 1/3 at each edge node
    load = {}
    faces = [(e, lab) for t in tips for s, lab in surfs[t] for e in elsets[s]]
    area = 0.0
    for e, lab in faces:
        conn = elems[e][1]
        c = [nodes[conn[i - 1]] for i in S4_CORNERS]
        d1 = [c[2][k] - c[0][k] for k in range(3)]
        d2 = [c[3][k] - c[1][k] for k in range(3)]
        cr = [d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2],
              d1[0] * d2[1] - d1[1] * d2[0]]
        a = 0.5 * math.sqrt(sum(x * x for x in cr))
        area += a
        for i in S4_CORNERS:
            load[conn[i - 1]] = load.get(conn[i - 1], 0.0) - a / 12
        for i in S4_EDGES:
            load[conn[i - 1]] = load.get(conn[i - 1], 0.0) + a / 3
    r.check(f"{label}: the tip surfaces {' '.join(tips)} are the whole end face "
            f"({len(faces)} faces, area {area:.12g})", all(lab == "S4" for _, lab in faces) and
            abs(area - h * b) < 1e-9 * h * b)
    lines = ["*INCLUDE, INPUT=box.inp"] + HEADER + ["*BOUNDARY"] + \
        [f"{c}, 1, 3" for c in clamp] + ["*STEP", "*STATIC", "*CLOAD"]
    for n, w in sorted(load.items()):
        lines.append(f"{n}, 2, {P * w / area:.12e}")
    lines += ["*NODE PRINT, NSET=NALL", "U", "*END STEP"]
    dat = ccx(r, d, label, lines)
    if dat is None:
        return None
    tip = [n for n, x in nodes.items()
           if abs(x[0] - L) < 1e-9 and abs(x[1] - h / 2) < 1e-9 and abs(x[2] - b / 2) < 1e-9]
    uy = {int(row[0]): row[2] for row in dat.get("displacements", [])}
    if not r.check(f"{label}: the tip's centre is a node", len(tip) == 1 and tip[0] in uy):
        return None
    return uy[tip[0]]


def cantilever(r, tmp, results):
    L, h, b, P = 100.0, 10.0, 10.0, 100.0
    d = os.path.join(tmp, "cantilever")
    os.makedirs(d)
    got = tip_deflection(r, d, "cantilever", "cantilever.json", "20,2,2", ["BEAM_U0"],
                         ["BEAM_U1_S"], L, h, b, P)
    if got is None:
        return
    I, A, G = b * h ** 3 / 12, b * h, E / (2 * (1 + NU))
    k = 10 * (1 + NU) / (12 + 11 * NU)
    want = P * L ** 3 / (3 * E * I) + P * L / (k * G * A)
    rel = (got - want) / want
    results.append(("cantilever 100x10x10, hex20 20x2x2, tip deflection", got, want, rel))
    r.check(f"cantilever: tip deflection {got:.6g} vs Timoshenko {want:.6g} "
            f"({100 * rel:+.2f}%)", abs(rel) <= 0.02)
    lattice_cantilever(r, tmp, results, got, L, h, b, P)


def lattice_cantilever(r, tmp, results, single, L, h, b, P):
    """The same beam as a control lattice of 4 x 1 x 2 body 0 cells (cells
    c<i><k>, 25 x 10 x 5, sharing faces), each meshed at 5,2,1: the same
    20 x 2 x 2 hex20 mesh in total, so ccx must give the same tip
    deflection as the single body's, to 1e-6 relative."""
    d = os.path.join(tmp, "lattice-cantilever")
    os.makedirs(d)
    bodies = []
    for i in range(4):
        for k in range(2):
            x0, x1, z0, z1 = 25.0 * i, 25.0 * (i + 1), 5.0 * k, 5.0 * (k + 1)
            c = [[x1 if n & 4 else x0, h if n & 2 else 0.0, z1 if n & 1 else z0]
                 for n in range(8)]
            bodies.append({"type": "body0", "name": f"c{i}{k}", "corners": c})
    with open(os.path.join(r.src, "examples", "cantilever.json")) as f:
        units = json.load(f).get("units", "mm")
    model = os.path.join(d, "lattice-cantilever.json")
    with open(model, "w") as f:
        json.dump({"coons": 1, "units": units, "bodies": bodies}, f)
    got = tip_deflection(r, d, "4 x 1 x 2 lattice cantilever", model, "5,2,1",
                         ["C00_U0", "C01_U0"], ["C30_U1_S", "C31_U1_S"], L, h, b, P)
    if got is None:
        return
    rel = (got - single) / single
    results.append(("cantilever as 4x1x2 cells, hex20 5x2x1 each, tip deflection", got, single,
                    rel))
    r.check(f"4 x 1 x 2 lattice cantilever: tip deflection {got:.9g} = the single body's "
            f"{single:.9g} (relative {rel:+.1e})", abs(rel) <= 1e-6)


def l_bracket(r, tmp):
    """examples/lattice-l-bracket.json (a corner cell and two arms; the arms
    meet along one edge only) as hex20 on its sampled lattice: arm-x's end
    face (node set ARM_X_U1, at the largest x) clamped, a force F along -z
    spread evenly over the nodes of arm-y's end face (ARM_Y_V1, at the
    largest y): ccx solves it, the reactions add up to F (equilibrium),
    and ccx's element volumes add up to the three bodies' volumes
    (--info) within 1e-3."""
    d = os.path.join(tmp, "l-bracket")
    os.makedirs(d)
    model = os.path.join(r.src, "examples", "lattice-l-bracket.json")
    path = os.path.join(d, "lb.inp")
    st, _, err = r.run([model, "-o", path, "--element", "hex20"])
    if not r.check("lattice-l-bracket.json: coons2stl writes lb.inp (hex20)",
                   st == 0 and os.path.exists(path), err):
        return
    nodes, elems, nsets, elsets, surfs = read_inp(path)
    xmax = max(x[0] for x in nodes.values())
    ymax = max(x[1] for x in nodes.values())
    clamp, tip = nsets.get("ARM_X_U1", []), nsets.get("ARM_Y_V1", [])
    # (the arms' ends are rounded: from x = 40 to 41.275)
    r.check("ARM_X_U1 is the end face at the largest x, ARM_Y_V1 the one at the largest y",
            clamp and tip and all(nodes[n][0] >= 40 - 1e-9 for n in clamp) and
            all(nodes[n][1] >= 40 - 1e-9 for n in tip) and
            any(abs(nodes[n][0] - xmax) < 1e-9 for n in clamp) and
            any(abs(nodes[n][1] - ymax) < 1e-9 for n in tip))
    F = 1000.0
    lines = ["*INCLUDE, INPUT=lb.inp"] + HEADER + ["*BOUNDARY", "ARM_X_U1, 1, 3", "*STEP",
                                                     "*STATIC", "*CLOAD"]
    lines += [f"{n}, 3, {-F / len(tip):.12e}" for n in sorted(tip)]
    lines += ["*NODE PRINT, NSET=ARM_X_U1, TOTALS=ONLY", "RF", "*EL PRINT, ELSET=EALL", "EVOL",
              "*NODE PRINT, NSET=NALL", "U", "*END STEP"]
    dat = ccx(r, d, "lattice-l-bracket", lines)
    if dat is None:
        return
    with open(os.path.join(d, "job.dat")) as f:
        text = f.read()
    # " total force (fx,fy,fz) for set ARM_X_U1 ...", a blank line, the values
    lines = text.splitlines()
    at = [i for i, line in enumerate(lines) if line.strip().startswith("total force")]
    try:
        rz = float(lines[at[-1] + 2].split()[2])
    except (IndexError, ValueError):
        rz = math.nan
    r.check(f"lattice-l-bracket: the clamp's reaction {rz:.9g} balances the load {F:g}",
            abs(rz - F) <= 1e-6 * F, text[-800:])
    st, out, err = r.run(["--info", "--no-solid", model])
    want = sum(abs(bd["volume"]) for bd in json.loads(out)["bodies"]) if st == 0 else math.nan
    vol = sum(row[1] for row in dat.get("volume", []))
    r.check(f"lattice-l-bracket: ccx's element volumes {vol:.8g} = the bodies' {want:.8g} "
            "within 1e-3", abs(vol - want) <= 1e-3 * want)
    uz = [row[3] for row in dat.get("displacements", [])]
    r.check(f"lattice-l-bracket: every node has a displacement ({len(uz)} of {len(nodes)}), "
            f"the tip moves down ({min(uz) if uz else math.nan:.4g})",
            len(uz) == len(nodes) and min(uz) < 0)


def tube(r, tmp, model, results, radii):
    a, b, p = 10.0, 20.0, 10.0
    d = os.path.join(tmp, model)
    os.makedirs(d)
    deck = mesh(r, d, model, "tube.inp", "4,8,1")
    if not deck:
        return
    nodes = deck[0]
    radii[model] = sorted({round(math.hypot(x[0], x[1]), 9) for x in nodes.values()})
    lines = ["*INCLUDE, INPUT=tube.inp"] + HEADER + [
        "*BOUNDARY", "TUBE_V0, 2, 2", "TUBE_V1, 1, 1", "TUBE_W0, 3, 3", "TUBE_W1, 3, 3",
        "*STEP", "*STATIC", "*DSLOAD", f"TUBE_U0_S, P, {p}",
        "*NODE PRINT, NSET=NALL", "U", "*END STEP"]
    dat = ccx(r, d, model, lines)
    if dat is None:
        return
    disp = dat.get("displacements", [])
    c = (1 + NU) * a * a * p / (E * (b * b - a * a))
    worst, worst_t, at = 0.0, 0.0, None
    for row in disp:
        x = nodes[int(row[0])]
        rad = math.hypot(x[0], x[1])
        ur = (row[1] * x[0] + row[2] * x[1]) / rad
        ut = (-row[1] * x[1] + row[2] * x[0]) / rad
        want = c * ((1 - 2 * NU) * rad + b * b / rad)
        if abs(ur - want) / want > worst:
            worst, at = abs(ur - want) / want, (rad, ur, want)
        worst_t = max(worst_t, abs(ut) / want)
    uin = c * ((1 - 2 * NU) * a + b * b / a)
    inner = [(row[1] * nodes[int(row[0])][0] + row[2] * nodes[int(row[0])][1]) / a
             for row in disp if abs(math.hypot(*nodes[int(row[0])][:2]) - a) < 1e-9]
    results.append((f"{model}, hex20 4x8x1, u_r at r = a (mean of {len(inner)} nodes)",
                    sum(inner) / max(1, len(inner)), uin,
                    (sum(inner) / max(1, len(inner)) - uin) / uin))
    results.append((f"{model}, worst node (r = {at[0]:.4g}), |error|" if at else model,
                    at[1] if at else math.nan, at[2] if at else math.nan, worst))
    r.check(f"{model}: radial displacement of all {len(disp)} nodes within 0.5% of Lame "
            f"(worst {100 * worst:.3f}% at r = {at[0] if at else math.nan:.4g}; "
            f"tangential at most {100 * worst_t:.2g}%)",
            len(disp) == len(nodes) and worst <= 0.005 and worst_t <= 0.005)


def main():
    r = Runner(__doc__)
    if not r.check("ccx is installed", shutil.which("ccx") is not None):
        r.finish()
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        cantilever(r, tmp, results)
        l_bracket(r, tmp)
        radii = {}
        for model in ("thick-cylinder.json", "thick-cylinder-distorted.json"):
            tube(r, tmp, model, results, radii)
        even, uneven = radii.get("thick-cylinder.json"), radii.get("thick-cylinder-distorted.json")
        r.check("the distorted tube's nodes lie at other radii (uneven: "
                f"{uneven[:5] if uneven else None} ...)",
                even and uneven and len(even) == len(uneven) == 9 and even != uneven)
    print("| case | ccx | closed form | relative error |")
    print("|---|---|---|---|")
    for what, got, want, rel in results:
        print(f"| {what} | {got:.6g} | {want:.6g} | {100 * rel:+.3f}% |")
    r.finish()


if __name__ == "__main__":
    main()
