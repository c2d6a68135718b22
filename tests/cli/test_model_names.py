#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The names of the model format agree everywhere they appear.

- The core's names (coons_curve_type_name(), coons_patch_type_name(),
  coons_body_type_name(), coons_body_edge_name(), coons_body_face_name(),
  coons_patch_side_name(), read through ctypes from the built libcoons) are
  exactly the types and keys the loader accepts: every type the core names
  has a loader row and the loader has no type the core does not name.
- What the loader accepts is asked of coons2stl itself: a model with an
  unknown type or key is refused with "expected one of: ..." listing what it
  takes, for the top level, every body, patch and curve type, and the
  edges, faces and sides objects.
- tests/fuzz/model.dict holds every type name and every key the loader
  accepts, quoted as in a model.

Usage: test_model_names.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import ctypes
import glob
import json
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
UNKNOWN = "zzz-unknown"


def core_names(lib, fn):
    f = getattr(lib, fn)
    f.restype = ctypes.c_char_p
    f.argtypes = [ctypes.c_int]
    out = []
    while len(out) < 100:
        n = f(len(out))
        if n is None:
            break
        out.append(n.decode())
    return out


def load_lib():
    found = sorted(glob.glob(os.path.join(T.build, "src", "libcoons.so*")))
    if not found:
        found = sorted(glob.glob(os.path.join(T.build, "**", "libcoons.so*"), recursive=True))
    return ctypes.CDLL(found[0]) if found else None


def expected_list(model, what):
    """Runs coons2stl on model (a dict) and returns the list after
    'expected one of: ' in its error, or None."""
    st, _, err = T.run(["--info", "--no-solid", "-"], stdin=json.dumps(model))
    m = re.search(r"expected one of: (.*)$", err.strip())
    if st != 1 or not m:
        T.check(f"{what}: refused with a list of what is accepted", False,
                f"status {st}, stderr {err.strip()!r}")
        return None
    return m.group(1).split(", ")


def doc(*bodies):
    return {"coons": 1, "bodies": list(bodies)}


LINE = {"type": "line", "points": [[0, 0], [1, 0]]}


def in_curve(curve):
    """A body1 whose first edge (u00, read first) is curve."""
    edges = {e: LINE for e in EDGES}
    edges[EDGES[0]] = curve
    return doc({"type": "body1", "edges": edges})


def in_patch(patch):
    """A body2 whose first face (u0, read first) is patch."""
    faces = {f: {} for f in FACES}
    faces[FACES[0]] = patch
    return doc({"type": "body2", "faces": faces})


lib = load_lib()
if not T.check("libcoons found in the build directory", lib is not None, T.build):
    T.finish()

CURVE_TYPES = core_names(lib, "coons_curve_type_name")
PATCH_TYPES = core_names(lib, "coons_patch_type_name")
BODY_TYPES = core_names(lib, "coons_body_type_name")
EDGES = core_names(lib, "coons_body_edge_name")
FACES = core_names(lib, "coons_body_face_name")
SIDES = core_names(lib, "coons_patch_side_name")
T.check("the core names 7 curve, 6 patch and 5 body types, 12 edges, 6 faces, 4 sides",
        [len(CURVE_TYPES), len(PATCH_TYPES), len(BODY_TYPES), len(EDGES), len(FACES),
         len(SIDES)] == [7, 6, 5, 12, 6, 4])

accepted = set()  # every type name and key the loader accepts


def same(what, loader, core):
    if loader is None:
        return
    T.check(f"{what}: the loader's list is the core's", loader == core,
            f"loader {loader}, core {core}")
    accepted.update(loader)


# Types: one row per core name, and no other.
same("body types", expected_list(doc({"type": UNKNOWN}), "body type"), BODY_TYPES)
same("patch types", expected_list(in_patch({"type": UNKNOWN}), "patch type"), PATCH_TYPES)
same("curve types", expected_list(in_curve({"type": UNKNOWN}), "curve type"), CURVE_TYPES)

# Edge, face and side keys.
same("body1 edges", expected_list(doc({"type": "body1", "edges": {UNKNOWN: 1}}), "edges"),
     EDGES)
same("body2 faces", expected_list(doc({"type": "body2", "faces": {UNKNOWN: 1}}), "faces"),
     FACES)
same("patch boundary sides",
     expected_list(in_patch({"type": "coons", "boundary": {UNKNOWN: 1}}), "boundary"), SIDES)
same("hermite cross sides",
     expected_list(in_patch({"type": "hermite-coons",
                             "boundary": {s: LINE for s in SIDES},
                             "cross": {UNKNOWN: 1}}), "cross"), SIDES)


# Keys of the top level and of every type.
def keys(what, model):
    got = expected_list(model, what)
    if got is not None:
        if what != "the model":
            T.check(f"{what}: takes \"type\"", "type" in got, str(got))
        else:
            T.check(f"{what}: takes \"coons\" and \"bodies\"",
                    "coons" in got and "bodies" in got, str(got))
        accepted.update(got)


keys("the model", {"coons": 1, UNKNOWN: 1})
for t in BODY_TYPES:
    keys(f"body {t}", doc({"type": t, UNKNOWN: 1}))
for t in PATCH_TYPES:
    keys(f"patch {t}", in_patch({"type": t, UNKNOWN: 1}))
for t in CURVE_TYPES:
    keys(f"curve {t}", in_curve({"type": t, UNKNOWN: 1}))


# The fuzz dictionary: lines "..." in libFuzzer's escaping.
def dict_entries(path):
    out = set()
    with open(path, encoding="utf-8") as f:
        for line in f:
            line = line.strip()
            if line.startswith('"') and line.endswith('"') and len(line) >= 2:
                out.add(re.sub(r'\\(.)', r'\1', line[1:-1]))
    return out


DICT = os.path.join(T.src, "tests", "fuzz", "model.dict")
entries = dict_entries(DICT)
T.check("the loader accepts at least 40 distinct names", len(accepted) >= 40, str(accepted))
for name in sorted(accepted):
    T.check(f"model.dict has \"{name}\"", f'"{name}"' in entries,
            f"add the line \"\\\"{name}\\\"\" to tests/fuzz/model.dict")

T.finish()
