#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""References of the model format (coons-model(5), "Definitions and
references") through coons2stl:

- a model written with "define"/"ref" (identity transforms) gives the same
  --eval output, byte for byte, and the same STL bytes as the model
  written inline; body1 edges, body2 faces and Coons patch boundaries
  through references, a definition referencing a definition;
- a mirrored instance (det M < 0) is left-handed, and its boundary is
  still written outward: --info "mesh" oriented and closed, mesh volume
  positive and equal to the original's;
- every reference error: exit status 1, `coons2stl: FILE:LINE:COL: PATH:
  message` with the line, column and JSON pointer counted here, the words
  of the message, and for an error inside a definition both paths;
- a model whose references expand beyond max_values is refused quickly
  with the limit named (exit status 1), and so is a chain of references
  nested too deep.

Usage: test_refs.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
TMP = tempfile.mkdtemp(prefix="coons-refs-")
ID = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]
CUBE = [[0, 0, 0], [0, 0, 1], [0, 1, 0], [0, 1, 1], [1, 0, 0], [1, 0, 1], [1, 1, 0], [1, 1, 1]]


def write(name, text):
    p = os.path.join(TMP, name)
    with open(p, "w") as f:
        f.write(text if isinstance(text, str) else json.dumps(text, indent=1))
    return p


def line(a, b):
    return {"type": "line", "points": [a, b]}


def arc(r, z):
    return {"type": "bspline", "degree": 2, "points": [[r, 0, z], [r, r, z], [0, r, z]],
            "weights": [1, 0.7071067811865476, 1]}


def quarter_tube_edges(e):
    """The 12 edges of a body1 quarter tube (r 1..2, z 0..1), e(name, curve)
    may replace any of them."""
    edges = {
        "u00": arc(2, 0), "u01": arc(2, 1), "u10": arc(1, 0), "u11": arc(1, 1),
        "v00": line([2, 0, 0], [1, 0, 0]), "v01": line([2, 0, 1], [1, 0, 1]),
        "v10": line([0, 2, 0], [0, 1, 0]), "v11": line([0, 2, 1], [0, 1, 1]),
        "w00": line([2, 0, 0], [2, 0, 1]), "w01": line([1, 0, 0], [1, 0, 1]),
        "w10": line([0, 2, 0], [0, 2, 1]), "w11": line([0, 1, 0], [0, 1, 1])}
    return {k: e(k, v) for k, v in edges.items()}


def coons_face(c):
    return {"type": "coons", "boundary": {"t0": line(c[0], c[1]), "t1": line(c[2], c[3]),
                                          "s0": line(c[0], c[2]), "s1": line(c[1], c[3])}}


def body2_faces(P):
    """Six Coons faces of the body with corners P[4i+2j+k]."""
    def q(a, b, c, d):
        return coons_face([P[a], P[b], P[c], P[d]])
    return {"u0": q(0, 2, 1, 3), "u1": q(4, 6, 5, 7), "v0": q(0, 4, 1, 5),
            "v1": q(2, 6, 3, 7), "w0": q(0, 4, 2, 6), "w1": q(1, 5, 3, 7)}


LATTICE = "".join(f"{i / 4} {j / 4} {k / 4}\n" for i in range(5) for j in range(5) for k in range(5))


def eval_out(path, body):
    rc, out, err = T.run([path, "--eval", "--jacobian", "--body", body], stdin=LATTICE)
    return rc, out, err


def stl(path):
    out = path + ".stl"
    rc, _, err = T.run([path, "-o", out])
    with open(out, "rb") as f:
        data = f.read()
    return rc, data, err


# ---- references against inline ---------------------------------------------------

P2 = [[0, 0, 0], [0, 0, 1], [0, 1, 0], [0, 1.2, 1], [1, 0, 0], [1, 0, 1.1], [1, 1, 0], [1.5, 1.2, 1]]
faces = body2_faces(P2)
inline = {"coons": 1, "operation": "none", "bodies": [
    {"type": "body1", "name": "tube", "edges": quarter_tube_edges(lambda k, v: v)},
    {"type": "body2", "name": "cell", "faces": faces}]}

defs = {"arc2": arc(2, 0),
        "arc2up": {"ref": "arc2", "transform": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 1]]},
        "s0": faces["u0"]["boundary"]["s0"],
        "face_u0": {"type": "coons", "boundary": dict(faces["u0"]["boundary"], s0={"ref": "s0"})},
        "face_w1": faces["w1"],
        "unused": line([0, 0], [1, 0])}
ref_faces = dict(faces, u0={"ref": "face_u0"}, w1={"ref": "face_w1", "transform": ID})
defs["cell"] = {"type": "body2", "faces": ref_faces}
withref = {"coons": 1, "operation": "none", "define": defs, "bodies": [
    {"type": "body1", "name": "tube", "edges": quarter_tube_edges(
        lambda k, v: {"ref": "arc2"} if k == "u00" else {"ref": "arc2up", "transform": ID}
        if k == "u01" else v)},
    {"ref": "cell", "transform": ID}]}
pi, pr = write("inline.json", inline), write("ref.json", withref)
for body in ("tube", "cell"):
    a, b = eval_out(pi, body), eval_out(pr, body)
    T.check(f"--eval of {body}: references give the inline output byte for byte",
            a[0] == 0 and a == b and len(a[1].splitlines()) == 125, f"{a[2]} {b[2]}")
a, b = stl(pi), stl(pr)
T.check("the STL of the model with references is the inline model's, byte for byte",
        a[0] == 0 and a == b and len(a[1]) > 84, f"{a[2]} {b[2]}")

# ---- a mirrored instance ----------------------------------------------------------

mir = {"coons": 1, "operation": "none", "define": {"cell": {"type": "body2", "faces": faces}},
       "bodies": [{"ref": "cell"},
                  {"ref": "cell", "name": "mirror", "transform": [[-1, 0, 0, -1], [0, 1, 0, 0], [0, 0, 1, 0]]}]}
pm = write("mirror.json", mir)
rc, out, err = T.run([pm, "--info", "--no-solid"])
ok = rc == 0
if ok:
    info = json.loads(out)
    b0, b1 = info["bodies"]
    m0, m1 = b0["mesh"], b1["mesh"]
    T.check("mirrored instance: left-handed (min det J < 0, signed volume < 0)",
            b1["min_det_jacobian"] < 0 and b1["volume"] < 0 and b0["volume"] > 0, out)
    T.check("mirrored instance: boundary mesh closed, manifold and oriented",
            m1["closed"] and m1["manifold"] and m1["oriented"], json.dumps(m1))
    T.check("mirrored instance: mesh volume positive (outward) and equal to the original's",
            m1["volume"] > 0 and abs(m1["volume"] - m0["volume"]) <= 1e-12 * m0["volume"],
            f"{m0['volume']} {m1['volume']}")
    T.check("mirrored instance: bbox mirrored (x in [-2.5, -1])",
            abs(b1["bbox"]["min"][0] + 2.5) < 1e-12 and abs(b1["bbox"]["max"][0] + 1) < 1e-12,
            json.dumps(b1["bbox"]))
else:
    T.check("mirrored model loads", False, err)

# ---- errors ---------------------------------------------------------------------

# Each case: the file's lines, then (line, column, path, words). The model
# text is written line by line so that positions can be counted here.
HEAD = '{"coons": 1,\n'
CUBE_S = json.dumps({"type": "body0", "corners": CUBE})
CASES = {
    # line 2 `"bodies": [{"ref": "nope"}]}`: '"nope"' after `"bodies": [{"ref": ` (19) -> 20
    "unknown-name": (HEAD + '"bodies": [{"ref": "nope"}]}\n',
                     2, 20, "/bodies/0/ref", ["unknown definition", "nope"]),
    # line 3 `"bodies": [{"ref": "l"}]}`: '"l"' at 20
    "wrong-kind": (HEAD + '"define": {"l": {"type": "line", "points": [[0, 0], [1, 0]]}},\n'
                   '"bodies": [{"ref": "l"}]}\n',
                   3, 20, "/bodies/0/ref",
                   ['"l" is a curve', "line 2, column 17", "a body stands here"]),
    # line 3 `"b": {"ref": "a"}},`: the cycle closes at b's "ref" value, column 14
    "cycle": (HEAD + '"define": {"a": {"ref": "b"},\n'
              '"b": {"ref": "a"}},\n'
              '"bodies": [{"ref": "a"}]}\n',
              3, 14, "/define/b/ref", ["a cycle of references: a -> b -> a",
                                   'in definition "b" referenced at /define/a',
                                   'in "a" referenced at /bodies/0']),
    # an unused definition that references itself: line 2 `"define": {"a": {"ref": "a"}},`, "a" at 25
    "self-cycle": (HEAD + '"define": {"a": {"ref": "a"}},\n'
                   '"bodies": [{"type": "body0", "corners": ' + json.dumps(CUBE) + '}]}\n',
                   2, 25, "/define/a/ref", ["a cycle of references: a -> a"]),
    # line 4 `"transform": [[1, 0, 0, 0], [0, 1, 0, 0], [2, 2, 0, 0]]}]}`: '[' at 14
    "singular": (HEAD + '"define": {"c": ' + CUBE_S + '},\n'
                 '"bodies": [{"ref": "c",\n'
                 '"transform": [[1, 0, 0, 0], [0, 1, 0, 0], [2, 2, 0, 0]]}]}\n',
                 4, 14, "/bodies/0/transform", ["singular", "determinant is 0"]),
    # line 4 `"transform": [[1, 0, 0], ...`: the row at 15
    "transform-row": (HEAD + '"define": {"c": ' + CUBE_S + '},\n'
                      '"bodies": [{"ref": "c",\n'
                      '"transform": [[1, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}]}\n',
                      4, 15, "/bodies/0/transform/0", ["4 numbers", "found 3"]),
    # line 3 `"bodies": [{"ref": "c", "mirror": true}]}`: key at 25
    "unknown-modifier": (HEAD + '"define": {"c": ' + CUBE_S + '},\n'
                         '"bodies": [{"ref": "c", "mirror": true}]}\n',
                         3, 25, "/bodies/0/mirror",
                         ['unknown key "mirror"', "body reference", "ref, transform, name"]),
    # the same place for "swap", a patch modifier
    "modifier-kind": (HEAD + '"define": {"c": ' + CUBE_S + '},\n'
                      '"bodies": [{"ref": "c", "swap": true}]}\n',
                      3, 25, "/bodies/0/swap",
                      ['"swap" modifies a reference to a patch, not to a body']),
    # line 3 `"reverse": 1}}]}` after 21 `"bodies": [{"ref": "r",` ... see below
    "modifier-type": (HEAD + '"define": {"c": ' + CUBE_S + '},\n'
                      '"bodies": [{"ref": "c", "name": 7}]}\n',
                      3, 33, "/bodies/0/name", ["expected a string", "found a number"]),
    # line 2 `"define": {"c": {"type": "body0", "corners": [[0, 0, 0]]}},`:
    # the corners array at 46; the reference on line 3 at /bodies/0
    "inside-definition": (HEAD + '"define": {"c": {"type": "body0", "corners": [[0, 0, 0]]}},\n'
                          '"bodies": [{"ref": "c"}]}\n',
                          2, 46, "/define/c/corners",
                          ["8 corners", 'in definition "c" referenced at /bodies/0']),
    # line 4 the second `{"ref": "c"}` at 2; the first at line 3 column 13 ("c")
    "duplicate-instance": (HEAD + '"define": {"c": ' + CUBE_S + '},\n'
                           '"bodies": [{"ref": "c"},\n'
                           '{"ref": "c"}]}\n',
                           4, 9, "/bodies/1/ref",
                           ['body name "c" is already used by body 0', "line 3, column 20",
                            'give it a "name"']),
    # an explicit name that repeats: line 4 `{"ref": "c", "name": "x"}]}` value at 22
    "duplicate-name": (HEAD + '"define": {"c": ' + CUBE_S + '},\n'
                       '"bodies": [{"ref": "c", "name": "x"},\n'
                       '{"ref": "c", "name": "x"}]}\n',
                       4, 22, "/bodies/1/name", ['body name "x" is already used by body 0']),
    # line 2 `"define": {"a": {"type": "foo"}},`: "foo" at 26
    "definition-type": (HEAD + '"define": {"a": {"type": "foo"}},\n'
                        '"bodies": [{"type": "body0", "corners": ' + json.dumps(CUBE) + '}]}\n',
                        2, 26, "/define/a/type", ['unknown type "foo" for a definition']),
    # an unused definition is checked: line 2 `"define": {"x": {"type": "line", "points": [[0, 0]]}},`
    # `"points": ` ends at 43: the array at 44
    "unused-definition": (HEAD + '"define": {"x": {"type": "line", "points": [[0, 0]]}},\n'
                          '"bodies": [{"type": "body0", "corners": ' + json.dumps(CUBE) + '}]}\n',
                          2, 44, "/define/x/points", ["2 points"]),
    # line 3: the second "a" key at 1
    "definition-twice": (HEAD + '"define": {"a": ' + CUBE_S + ',\n'
                         '"a": ' + CUBE_S + '},\n'
                         '"bodies": [{"ref": "a"}]}\n',
                         3, 1, "/define/a", ['definition "a" is already defined at line 2, column 12']),
}
for name, (text, ln, col, path, words) in sorted(CASES.items()):
    p = write(name + ".json", text)
    rc, out, err = T.run([p, "--info", "--no-solid"])
    want = f"coons2stl: {p}:{ln}:{col}: {path}: "
    first = err.splitlines()[0] if err else ""
    T.check(f"{name}: exit 1, {ln}:{col} {path}",
            rc == 1 and first.startswith(want), f"rc={rc} {first!r}, want {want!r}")
    missing = [w for w in words if w not in first]
    T.check(f"{name}: the message says {words}", not missing, f"{first!r} lacks {missing}")

# ---- limits -----------------------------------------------------------------------

# One large curve, referenced 4 times by a patch, the patch 6 times by a
# body, the body 400 times: 20001 * 4 * 6 * 400 points from a 1 MB file.
n = 20001
big = {"type": "bspline", "degree": 1, "points": [[i / (n - 1), 0, 0] for i in range(n)]}
patch = {"type": "coons", "boundary": {k: {"ref": "big"} for k in ("t0", "t1", "s0", "s1")}}
body = {"type": "body2", "faces": {k: {"ref": "p"} for k in ("u0", "u1", "v0", "v1", "w0", "w1")}}
model = {"coons": 1, "define": {"big": big, "p": patch, "b": body},
         "bodies": [{"ref": "b", "name": f"b{i}"} for i in range(400)]}
p = write("blowup.json", json.dumps(model))
# The work is bounded by the count of values read (not by a clock: the
# tests time nothing, and this one also runs under valgrind).
rc, out, err = T.run([p, "--info", "--no-solid"])
T.check("references that expand beyond max_values: refused with the limit named",
        rc == 1 and "expand the model to more than 8388608 JSON values" in err
        and "--max-values" in err, f"rc={rc} {err}")
rc, out, err = T.run([p, "--info", "--no-solid", "--max-values", "1000000"])
T.check("... the limit follows --max-values",
        rc == 1 and "more than 1000000 JSON values" in err, err)

chain = {"a0": {"type": "line", "points": [[0, 0], [1, 0]]}}
for i in range(1, 40):
    chain[f"a{i}"] = {"ref": f"a{i - 1}", "transform": [[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0]]}
edges = quarter_tube_edges(lambda k, v: {"ref": "a39"} if k == "u00" else v)
p = write("deep.json", {"coons": 1, "define": chain, "bodies": [{"type": "body1", "edges": edges}]})
rc, out, err = T.run([p, "--info", "--no-solid"])
T.check("references nested 40 deep: refused (limit 32)",
        rc == 1 and "nest more than 32 deep" in err, err)

shutil.rmtree(TMP, ignore_errors=True)
T.finish()
