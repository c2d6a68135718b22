#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Rewrites C sources written for libcoons 0.1 to the 0.2 names.

    tools/migrate-0.2.py FILE...      rewrites the files in place
    tools/migrate-0.2.py --check FILE...  lists what it would change, exit 1 if any

Only names are rewritten; the calls whose arguments changed in 0.2 are listed
with their line so that you can adapt them by hand (libcoons(3), HISTORY):
  coons_patch_bilinear, coons_body_body0   corners are one flat array of doubles
  coons_patch_coons, coons_patch_hermite_coons, coons_body_body1,
  coons_body_body2                         arrays of handles are coons_X *const *
  coons_body_bspline                       three knot pointers instead of an array
  coons_model_load, coons_model_load_buffer  take an options pointer (NULL: defaults)
The 0.1 names compiled in 0.2 as deprecated wrappers; 0.3 removed them. For
0.3, run tools/migrate-0.3.py afterwards (the 0.2 names 0.3 changed). Lines from one that says "migrate-0.2: off" to
one that says "migrate-0.2: on" are left as they are.
"""
import re
import sys

# 0.1 name -> 0.2 name. Functions first, then macros.
RENAMES = {
    "coons_curve_line": "coons_curve_new_line",
    "coons_curve_polyline": "coons_curve_new_polyline",
    "coons_curve_bezier": "coons_curve_new_bezier",
    "coons_curve_hermite": "coons_curve_new_hermite",
    "coons_curve_coons_cubic": "coons_curve_new_coons_cubic",
    "coons_curve_clamped_cubic": "coons_curve_new_clamped_cubic",
    "coons_curve_bspline": "coons_curve_new_bspline",
    "coons_cubic_open_to_clamped": "coons_curve_convert_open_to_clamped",
    "coons_patch_bilinear": "coons_patch_new_bilinear",
    "coons_patch_ruled": "coons_patch_new_ruled",
    "coons_patch_coons": "coons_patch_new_coons",
    "coons_patch_hermite_coons": "coons_patch_new_hermite_coons",
    "coons_patch_bezier": "coons_patch_new_bezier",
    "coons_patch_bspline": "coons_patch_new_bspline",
    "coons_body_body0": "coons_body_new_body0",
    "coons_body_body1": "coons_body_new_body1",
    "coons_body_body2": "coons_body_new_body2",
    "coons_body_bezier": "coons_body_new_bezier",
    "coons_body_bspline": "coons_body_new_bspline",
    "coons_model_load_opts": "coons_model_load_file",
    "coons_model_load_buffer_opts": "coons_model_load_memory",
    "coons_model_mesh": "coons_model_sample",
    "coons_model_solid": "coons_model_solidify",
    "coons_mesh_self_intersections": "coons_mesh_count_self_intersections",
    "coons_mesh_self_intersections_float": "coons_mesh_count_self_intersections_float",
    "coons_csg_available": "coons_csg_is_available",
    "COONS_T0": "COONS_SIDE_T0",
    "COONS_T1": "COONS_SIDE_T1",
    "COONS_S0": "COONS_SIDE_S0",
    "COONS_S1": "COONS_SIDE_S1",
    "COONS_MAX_CURVE_POINTS": "COONS_CURVE_MAX_POINTS",
    "COONS_MAX_PATCH_POINTS": "COONS_PATCH_MAX_POINTS",
    "COONS_MAX_BODY_POINTS": "COONS_BODY_MAX_POINTS",
    "COONS_MAX_DEGREE": "COONS_SPLINE_MAX_DEGREE",
    "COONS_DEFAULT_MAX_TRIANGLES": "COONS_MESH_MAX_TRIANGLES",
    "COONS_DEFAULT_MAX_ASPECT": "COONS_SAMPLE_DEFAULT_MAX_ASPECT",
}
# Calls whose arguments changed: renamed, and reported for a look by hand.
CHANGED = {
    "coons_patch_bilinear", "coons_body_body0", "coons_patch_coons",
    "coons_patch_hermite_coons", "coons_body_body1", "coons_body_body2",
    "coons_body_bspline", "coons_model_load", "coons_model_load_buffer",
}
PATTERN = re.compile(r"\b(" + "|".join(sorted(set(RENAMES) | CHANGED, key=len, reverse=True))
                     + r")\b")


def unclosed_paren(line):
    """Column of the innermost '(' still open at the end of line, or None."""
    stack = []
    for i, ch in enumerate(line):
        if ch == "(":
            stack.append(i)
        elif ch == ")" and stack:
            stack.pop()
    return stack[-1] if stack else None


def migrate(text):
    """Returns (new text, [(line, old name)] of calls whose arguments changed).
    Continuation lines aligned under the '(' of a renamed call move with it."""
    notes = []
    out = []
    shift = None  # (old indent, new indent) of continuation lines, while open
    skip = False  # between lines saying "migrate-0.2: off" and "migrate-0.2: on"
    for n, line in enumerate(text.splitlines(keepends=True), 1):
        if "migrate-0.2: off" in line or skip:
            skip = "migrate-0.2: on" not in line
            out.append(line)
            continue
        if shift is not None:
            body = line.lstrip(" ")
            indent = len(line) - len(body)
            if indent == shift[0] and body.strip():
                line = " " * shift[1] + body
            else:
                shift = None

        def sub(m):
            old = m.group(1)
            if old in CHANGED:
                notes.append((n, old))
            if old == "coons_model_load":
                return "coons_model_load_file"
            if old == "coons_model_load_buffer":
                return "coons_model_load_memory"
            return RENAMES[old]
        new = PATTERN.sub(sub, line)
        if new != line:
            a, b = unclosed_paren(line), unclosed_paren(new)
            if a is not None and b is not None and a != b:
                shift = (a + 1, b + 1)
        elif shift is not None and unclosed_paren(line) is None and line.count(")") > line.count("("):
            pass
        out.append(new)
    return "".join(out), notes


def main(argv):
    check = "--check" in argv
    files = [a for a in argv if a != "--check"]
    if not files:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    changed = 0
    for path in files:
        with open(path, encoding="utf-8", errors="surrogateescape") as f:
            text = f.read()
        new, notes = migrate(text)
        for n, old in notes:
            print(f"{path}:{n}: {old}: its arguments changed in 0.2, see libcoons(3)")
        if new != text:
            changed += 1
            if check:
                print(f"{path}: would be rewritten")
            else:
                with open(path, "w", encoding="utf-8", errors="surrogateescape") as f:
                    f.write(new)
    return 1 if check and changed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
