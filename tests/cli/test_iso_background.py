#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""coons2stl --iso ... --with-boundary: in OpenSCAD each body's boundary,
and nothing else, is called with the background modifier `%`.

The boundary parts are found from the file itself: the parts
(`// part i: NAME`) whose NAME is a body name of the model file (read from
the JSON here), while the surfaces are named BODY.u=V. For every body, for
one body (--body), and without --with-boundary (no `%` at all), the model
module calls exactly the boundary modules with `%` (coons_write_options.
background, 0.3; the mesh carried the mark before).

Usage: test_iso_background.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner  # noqa: E402


def calls(text):
    """{part name: called with %} from the part comments and the model module."""
    parts = dict(re.findall(r"^// part (\d+): (\S+) \(", text, re.M))
    mods = re.findall(r"^module (\w+)\(\) \{$", text, re.M)
    model = mods[-1]
    body = text.split(f"module {model}() {{\n", 1)[1].split("}\n", 1)[0]
    called = re.findall(r"^  (%?)(\w+)\(\);$", body, re.M)
    # The i-th call is part i (the writer calls the parts in order).
    return {parts[str(i)]: pct == "%" for i, (pct, _) in enumerate(called)}


def main():
    r = Runner(__doc__)
    model = os.path.join(r.src, "examples", "union-three-bodies.json")
    with open(model) as f:
        names = [b["name"] for b in json.load(f)["bodies"]]
    r.check("the model has three named bodies", len(names) == 3, str(names))
    tmp = tempfile.mkdtemp(prefix="coons-iso-bg-")
    out = os.path.join(tmp, "x.scad")
    for extra, bodies, boundary in (([], names, True), (["--body", "1"], names[1:2], True),
                                    ([], names, False)):
        args = [model, "--iso", "u=0.25,0.5"] + extra + (["--with-boundary"] if boundary else [])
        rc, _, err = r.run(args + ["-o", out])
        tag = " ".join(extra + (["--with-boundary"] if boundary else []))
        if not r.check(f"{tag or 'no options'}: written", rc == 0, err):
            continue
        with open(out) as f:
            got = calls(f.read())
        want = {n: True for n in bodies} if boundary else {}
        want.update({f"{n}.u={v}": False for n in bodies for v in ("0.25", "0.5")})
        r.check(f"{tag or 'no options'}: exactly the boundaries of {bodies} called with %"
                if boundary else "without --with-boundary: no part called with %",
                got == want, f"got {got}\nwant {want}")
    r.finish()


if __name__ == "__main__":
    main()
