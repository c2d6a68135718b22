#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""One model per error class in tests/data/bad/<class>.json. For each:
exit status 1; stderr is `coons2stl: FILE:LINE:COL: /json/path: message`
with the line, column (UTF-8 code points) and JSON pointer counted by hand
in the file (see the comments); the message says what was expected; and a
file that already exists at -o is left byte-for-byte unchanged, with no
other file created next to it. The same through standard input names
<stdin>.

Usage: test_errors.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
BAD = os.path.join(T.data, "bad")

# class: (line, column, JSON pointer, words the message must contain)
# Columns: count from 1 along the line; e.g. "      \"colour\"" has its quote
# at column 7 after six spaces.
CASES = {
    # line 6 is the inserted `      "colour": "red",`: the key at column 7
    "unknown-key": (6, 7, "/bodies/0/colour", ["unknown key", "colour", "expected one of"]),
    # the second `      "type": "body0",` on line 6
    "repeated-key": (6, 7, "/bodies/0/type", ["twice", "line 5, column 7"]),
    # `      "corners": "box"`: 6 spaces + `"corners": ` (11) -> value at 18
    "wrong-type": (6, 18, "/bodies/0/corners", ["expected an array", "found a string"]),
    # line 7: 18 spaces, then `[1, 0, 0, 5]` at 19, the 5th corner (index 4)
    "point-arity": (7, 19, "/bodies/0/corners/4", ["2 or 3 numbers", "found 4"]),
    # line 7: `[1, 0, 0], ` (11) after 18 spaces puts `[1, 0, 1e400]` at 30, 1e400 at 37
    "number-overflow": (7, 37, "/bodies/0/corners/5/2", ["1e400", "finite"]),
    # the body object `    {` on line 4 lacks "corners"
    "missing-key": (4, 5, "/bodies/0", ["missing key", "corners"]),
    # `      "name": "caf` + byte 0xE9: 6 spaces, "name" 7-12, ':' 13, ' ' 14, '"' 15, caf 16-18
    "invalid-utf8": (6, 19, "/bodies/0/name", ["UTF-8"]),
    # `x` alone on line 11 after the 10-line document
    "trailing-garbage": (11, 1, "", ["after the end"]),
    # `      "name": "a"` has no comma: the next key's quote at line 7, column 7
    "syntax-missing-comma": (7, 7, "/bodies/0/name", ["expected ','"]),
    # `  "tolerance": 0,`: 2 + `"tolerance": ` (13) -> 16
    "tolerance-nonpositive": (3, 16, "/tolerance", ["> 0"]),
    # `  "coons": 2,`: 2 + `"coons": ` (9) -> 12
    "version-wrong": (2, 12, "/coons", ["version 2", "version 1"]),
    # `  "bodies": [` -> '[' at 13
    "bodies-empty": (3, 13, "/bodies", ["at least one body"]),
    # line 6 `    {"type": "body0", "name": "part",`: '{' 5, `{"type": "body0", ` (18)
    # puts "name" at 23 and its value at 31; the first is on line 4, column 31
    "duplicate-body-name": (6, 31, "/bodies/1/name", ["part", "body 0", "line 4, column 31"]),
    # `     "blend": "cubic",`: the key after 5 spaces
    "blend-not-allowed": (5, 6, "/bodies/0/blend", ["body0, body1 and body2 only"]),
    # line 4 holds 70 '[': the bodies array is level 2, so '[' number 63 at column 63 is level 65
    "depth-limit": (4, 63, "/bodies" + "/0" * 63, ["limit", "64"]),
    # line 10 `        "u11": {...}`: 8 spaces + `"u11": ` (7) -> '{' at 16; u11 and
    # w11 disagree at P111 and u11 comes first
    "body1-edges-apart": (10, 16, "/bodies/0/edges/u11", ["u11", "w11", "P111", "0.5 apart"]),
    # line 8 `                "points": [...]`: 16 spaces + `"points": ` (10) -> 27
    "too-few-points": (8, 27, "/bodies/0/edges/u00/points", ["at least 4 points", "found 3"]),
    # line 9 `                "knots": [0, 0, 0, 1, 1]}`: 16 + `"knots": ` (9) -> 26
    "knots-length": (9, 26, "/bodies/0/edges/u00/knots", ["expected 6 knots", "found 5"]),
    # `[0, 0, 0, 1, 0.5, 1]` from 26: 0.5 is knot 4 at 26 + 13 = 39
    "knots-decreasing": (9, 39, "/bodies/0/edges/u00/knots/4", ["non-decreasing"]),
    # `[0, 0, 0, 0, 1, 1]`: the 4th zero (knot 3) at 26 + 10 = 36; degree 2 allows 3
    "knots-multiplicity": (9, 36, "/bodies/0/edges/u00/knots/3", ["more than degree + 1 = 3"]),
    # `[0, 0, 1, 1, 1, 2]`: knots[2] = knots[3] = 1
    "knots-empty-domain": (9, 26, "/bodies/0/edges/u00/knots", ["empty"]),
    # `                "weights": [1, 0, 1]}`: 16 + `"weights": ` (11) -> '[' 28, weight 1 at 32
    "weight-nonpositive": (9, 32, "/bodies/0/edges/u00/weights/1", ["> 0"]),
    "weight-nonfinite": (9, 32, "/bodies/0/edges/u00/weights/1", ["1e999", "finite"]),
    # line 7 `        "u00": {"type": "bspline", "degree": 2.5,`: '{' at 16,
    # `{"type": "bspline", ` (20) -> "degree" at 36, value at 46
    "degree-not-integer": (7, 46, "/bodies/0/edges/u00/degree", ["integer", "2.5"]),
    # line 9: 27 spaces, the 4th point (index 3) repeats the first
    "closed-coons-cubic-repeat": (9, 28, "/bodies/0/edges/u00/points/3", ["repeat", "3 distinct"]),
    # faces u0 u1 v0 v1 on lines 7-10: `        "v1": ` -> '{' at 15; v1 and w1 disagree
    # along edge u11, v1 is named first
    # ... and the rule and how to meet it (issue 24)
    "body2-faces-disagree": (10, 15, "/bodies/0/faces/v1",
                             ["v1", "w1", "u11", "0.5 apart",
                              "must be the same curve there at the same parameter",
                              "the same knots and equal control points along the edge",
                              "build the faces from the edge curves"]),
    # line 8 `                 "t0": {...}`: 17 spaces + `"t0": ` (6) -> 24; t0(1) and s1(0)
    # (corner X10) are 0.25 apart, t0 comes first
    "patch-corners-apart": (8, 24, "/bodies/0/faces/u0/boundary/t0", ["t0", "s1", "X10", "0.25 apart"]),
    # cross.t0(0) = (0,0,2) but s0'(0) = (0,0,1); boundary s0 (line 10, column 24)
    # comes before cross on the format's page
    "hermite-cross-inconsistent": (10, 24, "/bodies/0/faces/u0/boundary/s0", ["cross", "t0", "s0'(0)"]),
}

present = sorted(f[:-5] for f in os.listdir(BAD) if f.endswith(".json"))
T.check("every file in tests/data/bad has an expected position, and back",
        sorted(CASES) == present, f"files {present}\ncases {sorted(CASES)}")

work = tempfile.mkdtemp(prefix="coons_err_")
SENTINEL = b"solid old\nthis file must survive a failed run\n\x00\xff"
for name in sorted(CASES):
    line, col, path, words = CASES[name]
    src = os.path.join(BAD, name + ".json")
    if not os.path.exists(src):
        T.check(f"{name}: file exists", False, src)
        continue
    shutil.copy(src, os.path.join(work, name + ".json"))
    out = os.path.join(work, "out.stl")
    with open(out, "wb") as f:
        f.write(SENTINEL)
    before = sorted(os.listdir(work))
    rc, _, err = T.run([name + ".json", "-o", "out.stl"], cwd=work)
    shown = path if path else "(root)"
    head = f"coons2stl: {name}.json:{line}:{col}: {shown}: "
    T.check(f"{name}: exit 1", rc == 1, f"status {rc}: {err}")
    T.check(f"{name}: {head.strip()}", err.startswith(head) and err.count("\n") == 1,
            f"got {err!r}")
    missing = [w for w in words if w not in err]
    T.check(f"{name}: message says {words}", not missing, f"missing {missing} in {err!r}")
    with open(out, "rb") as f:
        same = f.read() == SENTINEL
    T.check(f"{name}: existing output unchanged, nothing created",
            same and sorted(os.listdir(work)) == before, str(sorted(os.listdir(work))))
    os.remove(os.path.join(work, name + ".json"))

# Through standard input the file is called <stdin>.
with open(os.path.join(BAD, "unknown-key.json"), "rb") as f:
    text = f.read()
rc, _, err = T.run(["-", "-o", os.path.join(work, "out.stl")], stdin=text, binary=True)
T.check("stdin: coons2stl: <stdin>:6:7: /bodies/0/colour:",
        rc == 1 and err.decode().startswith("coons2stl: <stdin>:6:7: /bodies/0/colour: "), repr(err))

# A file that cannot be read: the system's reason, exit 1, output untouched.
rc, _, err = T.run([os.path.join(work, "missing.json"), "-o", os.path.join(work, "out.stl")])
T.check("unreadable model: exit 1 with the system's reason",
        rc == 1 and "missing.json: cannot open the model: No such file or directory" in err, err)
with open(os.path.join(work, "out.stl"), "rb") as f:
    T.check("unreadable model: output unchanged", f.read() == SENTINEL)

# An error in --info and --eval mode is the same error.
for mode in (["--info"], ["--eval"]):
    rc, out, err = T.run(mode + [os.path.join(BAD, "knots-decreasing.json")], stdin="0 0 0\n")
    T.check(f"{mode[0]}: the model error, exit 1, nothing on stdout",
            rc == 1 and "knots-decreasing.json:9:39: /bodies/0/edges/u00/knots/4: " in err and out == "",
            f"{rc} {err!r} {out!r}")

shutil.rmtree(work)
T.finish()
