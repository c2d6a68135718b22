# SPDX-License-Identifier: GPL-3.0-or-later
"""The one harness of the command-line tests, tests/cli/test_<concept>.py
(not a test itself).

- Runner: parses --bin/--src/--build, runs the binary, counts checks;
  need() fails (never skips) when a client program is missing.
- examples(): every example, or under a sanitizer or valgrind
  (COONS_TEST_REPRESENTATIVE=1 or COONS_TEST_UNDER_VALGRIND=1) the
  representative subset of tests/data/representative-examples.txt;
  model_kinds() is what that subset must cover.
- An independent reference of the model format (coons-model(5)) written
  from the format's definitions, not from libcoons: every curve type at any
  t (Cox-de Boor, Bernstein, Coons polynomials of seed 002, cubic Hermite),
  and the 8 corners of every body type.
"""
import argparse
import glob
import json
import os
import shutil
import subprocess
import sys

# Under a sanitizer or valgrind: tests that repeat the same work over every
# example take the representative subset (release and core take all).
REPRESENTATIVE = bool(os.environ.get("COONS_TEST_REPRESENTATIVE")
                      or os.environ.get("COONS_TEST_UNDER_VALGRIND"))


class Runner:
    def __init__(self, doc=""):
        ap = argparse.ArgumentParser(description=doc)
        ap.add_argument("--bin", default="")  # empty for test_man, test_install
        ap.add_argument("--src", required=True)
        ap.add_argument("--build", default="")
        a = ap.parse_args()
        self.bin, self.src, self.build = a.bin, a.src, a.build
        self.data = os.path.join(self.src, "tests", "data")
        self.passed = self.failed = 0
        # A hung run fails instead of stalling CI; valgrind (tools/memcheck.sh)
        # slows coons2stl 50-fold.
        self.timeout = 900 if os.environ.get("COONS_TEST_UNDER_VALGRIND") else 120

    def need(self, program):
        """A client program the test runs: missing, it is a failed check,
        never a skip (tools/setup.sh installs every one)."""
        return self.check(f"{program} is installed (tools/setup.sh installs it)",
                          shutil.which(program) is not None)

    def has_cgal(self):
        """Whether this build has the Boolean (CGAL) layer, from its CMake
        cache: only without it may a union be refused (exit 3, naming CGAL)."""
        try:
            with open(os.path.join(self.build, "CMakeCache.txt")) as f:
                return "COONS_WITH_CGAL:BOOL=ON" in f.read()
        except OSError:
            return True  # unknown: nothing is excused

    def examples(self):
        """The example models to run (see examples())."""
        return examples(self.src)

    def check(self, name, ok, detail=""):
        if ok:
            self.passed += 1
            print(f"ok   {name}")
        else:
            self.failed += 1
            print(f"FAIL {name}" + (f"\n     {detail}" if detail else ""))
        return ok

    def run(self, args, stdin=None, cwd=None, binary=False):
        """Runs coons2stl; returns (status, stdout, stderr)."""
        p = subprocess.run([self.bin] + list(args), input=stdin, cwd=cwd,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           text=not binary, timeout=self.timeout)
        return p.returncode, p.stdout, p.stderr

    def finish(self):
        print(f"{self.passed} passed, {self.failed} failed")
        sys.exit(1 if self.failed or not self.passed else 0)


# ---- which examples ------------------------------------------------------------

def representative_names(src):
    """The names listed in tests/data/representative-examples.txt."""
    with open(os.path.join(src, "tests", "data", "representative-examples.txt")) as f:
        return [ln.strip() for ln in f if ln.strip() and not ln.startswith("#")]


def examples(src, every=False):
    """Paths of examples/*.json, sorted; the representative subset instead
    under a sanitizer or valgrind unless every is set."""
    if REPRESENTATIVE and not every:
        return [os.path.join(src, "examples", n) for n in representative_names(src)]
    return sorted(glob.glob(os.path.join(src, "examples", "*.json")))


def model_kinds(node, key=None, out=None):
    """What a model file exercises: every "type" value (curve, patch, body,
    ...), every key, and the values of the keys that choose a method
    (twist, blend, path, operation, closed)."""
    if out is None:
        out = set()
    if isinstance(node, dict):
        for k, v in node.items():
            out.add(("key", k))
            model_kinds(v, k, out)
        if isinstance(node.get("type"), str):
            out.add(("type", node["type"]))
    elif isinstance(node, list):
        for v in node:
            model_kinds(v, key, out)
    elif key in ("twist", "blend", "path", "operation", "closed") and \
            isinstance(node, (str, bool)):  # a method's name, not a number
        out.add(("value", key, json.dumps(node)))
    return out


# ---- small vector helpers ---------------------------------------------------

def pt3(p):
    """[x, y] means z = 0."""
    return [float(p[0]), float(p[1]), float(p[2]) if len(p) > 2 else 0.0]


def add(a, b):
    return [a[i] + b[i] for i in range(3)]


def scale(a, s):
    return [a[i] * s for i in range(3)]


def dist(a, b):
    return sum((a[i] - b[i]) ** 2 for i in range(3)) ** 0.5


def lincomb(ws, ps):
    out = [0.0, 0.0, 0.0]
    for w, p in zip(ws, ps):
        for i in range(3):
            out[i] += w * p[i]
    return out


# ---- bases ---------------------------------------------------------------------

def bernstein(n, t):
    from math import comb
    return [comb(n, i) * t ** i * (1 - t) ** (n - i) for i in range(n + 1)]


def clamped_knots(p, ncp):
    """p+1 zeros, 1..ncp-p-1, p+1 times ncp-p."""
    return [0.0] * (p + 1) + [float(i) for i in range(1, ncp - p)] + [float(ncp - p)] * (p + 1)


def bspline_basis(knots, p, ncp, t):
    """All ncp basis values at t in [0,1] mapped onto [k_p, k_ncp]; the
    right end belongs to the last non-empty span (Cox-de Boor recursion)."""
    a, b = knots[p], knots[ncp]
    x = a + t * (b - a)
    # span: k_i <= x < k_i+1, p <= i <= ncp-1; at the right end the last
    # non-empty span
    span = None
    for i in range(p, ncp):
        if knots[i] <= x < knots[i + 1]:
            span = i
    if span is None:
        for i in range(ncp - 1, p - 1, -1):
            if knots[i] < knots[i + 1]:
                span = i
                break
    m = len(knots) - 1
    N = [1.0 if i == span else 0.0 for i in range(m)]
    for d in range(1, p + 1):
        M = [0.0] * (m - d)
        for i in range(m - d):
            v = 0.0
            den = knots[i + d] - knots[i]
            if den > 0:
                v += (x - knots[i]) / den * N[i]
            den = knots[i + d + 1] - knots[i + 1]
            if den > 0:
                v += (knots[i + d + 1] - x) / den * N[i + 1]
            M[i] = v
        N = M
    return N[:ncp]


def coons_basis(t):
    return [(1 - t) ** 3 / 6, (3 * t ** 3 - 6 * t ** 2 + 4) / 6,
            (-3 * t ** 3 + 3 * t ** 2 + 3 * t + 1) / 6, t ** 3 / 6]


# ---- curves ---------------------------------------------------------------------

def curve_eval(c, t):
    typ = c["type"]
    P = [pt3(p) for p in c["points"]]
    if typ in ("line", "polyline"):
        n = len(P) - 1
        s = min(int(t * n), n - 1)
        return add(scale(P[s], 1 - (t * n - s)), scale(P[s + 1], t * n - s))
    if typ == "bezier":
        return lincomb(bernstein(len(P) - 1, t), P)
    if typ == "hermite":
        T = [pt3(v) for v in c["tangents"]]
        h = [1 - 3 * t * t + 2 * t ** 3, t - 2 * t * t + t ** 3, -t * t + t ** 3, 3 * t * t - 2 * t ** 3]
        return lincomb(h, [P[0], T[0], T[1], P[1]])
    if typ == "coons-cubic":
        if c.get("closed", False):
            P = P + P[:3]
        nseg = len(P) - 3
        x = t * nseg
        s = min(int(x), nseg - 1)
        return lincomb(coons_basis(x - s), P[s:s + 4])
    if typ == "clamped-cubic":
        return lincomb(bspline_basis(clamped_knots(3, len(P)), 3, len(P), t), P)
    if typ == "bspline":
        p = int(c["degree"])
        k = [float(v) for v in c["knots"]] if "knots" in c else clamped_knots(p, len(P))
        N = bspline_basis(k, p, len(P), t)
        if "weights" in c:
            w = [float(v) for v in c["weights"]]
            W = sum(N[i] * w[i] for i in range(len(P)))
            return lincomb([N[i] * w[i] / W for i in range(len(P))], P)
        return lincomb(N, P)
    raise ValueError("unknown curve type " + typ)


# ---- tensor products ---------------------------------------------------------

def tensor_eval(obj, params):
    """Bezier or B-spline/NURBS surface (2 params) or volume (3 params)."""
    pts = obj["points"]
    dims = len(params)
    shape = []
    a = pts
    for _ in range(dims):
        shape.append(len(a))
        a = a[0]
    bases = []
    for d in range(dims):
        n = shape[d]
        if obj["type"].startswith("bezier"):
            bases.append(bernstein(n - 1, params[d]))
        else:
            p = int(obj["degree"][d])
            k = [float(v) for v in obj["knots"][d]] if "knots" in obj else clamped_knots(p, n)
            bases.append(bspline_basis(k, p, n, params[d]))
    num, den = [0.0, 0.0, 0.0], 0.0
    w = obj.get("weights")

    def walk(node, wnode, d, coef):
        nonlocal den
        if d == dims:
            ww = float(wnode) if w is not None else 1.0
            for i in range(3):
                num[i] += coef * ww * pt3(node)[i]
            den += coef * ww
            return
        for i in range(shape[d]):
            if bases[d][i] != 0.0:
                walk(node[i], wnode[i] if w is not None else None, d + 1, coef * bases[d][i])
    walk(pts, w, 0, 1.0)
    return scale(num, 1.0 / den)


# ---- patches and bodies at corners -----------------------------------------------

def patch_eval_corner(p, s, t):
    """A patch at a corner (s, t in {0, 1})."""
    typ = p["type"]
    if typ == "bilinear":
        return pt3(p["corners"][int(s) + 2 * int(t)])
    if typ == "ruled":
        return curve_eval(p["curves"][int(t)], s)
    if typ in ("coons", "hermite-coons"):
        b = p["boundary"]
        # x(s, t) at a corner: t0/t1 give x(s, 0)/x(s, 1); s0/s1 agree with them
        return curve_eval(b["t1" if t else "t0"], s)
    if typ == "network":
        # row 0 is x(s, 0), the last row x(s, 1)
        return curve_eval(p["rows"][-1 if t else 0], s)
    return tensor_eval(p, [s, t])


def morph_weights(b):
    """The weights of a morph's keys at its "t" (coons-model(5) "morph"): on
    the interval of t, 1 - s and s (linear, or two keys), else the cubic
    Hermite with the Catmull-Rom tangents (K_k+1 - K_k-1) / (at_k+1 - at_k-1),
    one-sided at the ends, written as weights of the keys."""
    n = len(b["keys"])
    at = b.get("at") or [k / (n - 1) for k in range(n)]
    t = min(max(b.get("t", 0), 0), 1)
    i = 0
    while i + 2 < n and t >= at[i + 1]:
        i += 1
    h = at[i + 1] - at[i]
    s = min((t - at[i]) / h, 1)
    w = [0.0] * n
    if b.get("path", "linear") == "linear" or n == 2:
        w[i], w[i + 1] = 1 - s, s
        return w
    h00, h10 = 2 * s ** 3 - 3 * s ** 2 + 1, s ** 3 - 2 * s ** 2 + s
    h01, h11 = -2 * s ** 3 + 3 * s ** 2, s ** 3 - s ** 2
    w[i] += h00
    w[i + 1] += h01
    for k, c in ((i, h * h10), (i + 1, h * h11)):
        lo, hi = max(k - 1, 0), min(k + 1, n - 1)
        w[hi] += c / (at[hi] - at[lo])
        w[lo] -= c / (at[hi] - at[lo])
    return w


def body_corners(b):
    """The 8 corners P_ijk (index 4i + 2j + k) of a body."""
    typ = b["type"]
    if typ == "morph":
        keys = [body_corners(k) for k in b["keys"]]
        w = morph_weights(b)
        return [[sum(w[k] * keys[k][n][d] for k in range(len(keys))) for d in range(3)]
                for n in range(8)]
    out = []
    for n in range(8):
        i, j, k = n >> 2, (n >> 1) & 1, n & 1
        if typ == "body0":
            out.append(pt3(b["corners"][n]))
        elif typ == "body1":
            e = b["edges"]
            out.append(curve_eval(e["u%d%d" % (j, k)], i))
        elif typ == "body2":
            f = b["faces"]
            # u_I(s, t) = C(I, v=s, w=t)
            out.append(patch_eval_corner(f["u%d" % i], j, k))
        elif typ == "shell":
            # the offset needs the surface's normal: examples/coons_ref.py
            out.append(list(_coons_ref().body_corner(b, i, j, k)))
        else:
            out.append(tensor_eval(b, [i, j, k]))
    return out


def _coons_ref():
    """examples/coons_ref.py, the format's reference evaluator (no libcoons)."""
    here = os.path.dirname(os.path.abspath(__file__))
    sys.path.insert(0, os.path.join(here, "..", "..", "examples"))
    import coons_ref
    return coons_ref


def model_scale(model):
    """Diagonal of the box of the model's corner points (for tolerances)."""
    lo, hi = [1e300] * 3, [-1e300] * 3
    for b in model["bodies"]:
        if "ref" in b:  # a reference: its definition (a transform keeps the scale
            b = model["define"][b["ref"]]  # up to its norm; good enough for tolerances)
        for p in body_corners(b):
            for i in range(3):
                lo[i], hi[i] = min(lo[i], p[i]), max(hi[i], p[i])
    return max(dist(lo, hi), 1e-300)
