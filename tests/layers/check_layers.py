#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The layer rule of src/ (docs/ARCHITECTURE.md), read from the sources.

Every quoted include of a file in src/<stage>/ must name a header of its own
stage or of a stage before it, by its bare name (no path: the build gives
each source only those stages' folders, so a path would be the only way
round the rule). Header names are unique across src/, so a bare name means
one file. Public headers (<coons.h>, "coons/...") are always allowed.

Usage: check_layers.py SRC_DIR STAGE...   (the stages in pipeline order)
Exit 0 when every include keeps the rule; else each breach on a line
"file:line: ..." and exit 1."""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def main(argv):
    src, stages = argv[1], argv[2:]
    rank = {s: i for i, s in enumerate(stages)}
    owner = {}  # header name -> stage
    problems = []
    files = []
    for stage in stages:
        for root, _dirs, names in os.walk(os.path.join(src, stage)):
            for name in sorted(names):
                path = os.path.join(root, name)
                files.append((stage, path))
                if name.endswith((".h", ".hpp")):
                    if name in owner:
                        problems.append(f"{path}: header name '{name}' also in stage "
                                        f"'{owner[name]}' (names must be unique)")
                    owner[name] = stage
    for stage in sorted(set(os.listdir(src)) - set(stages)):
        if os.path.isdir(os.path.join(src, stage)):
            problems.append(f"{os.path.join(src, stage)}: folder is not a stage")
    for stage, path in files:
        if not path.endswith((".c", ".cpp", ".h", ".hpp")):
            continue
        with open(path, encoding="utf-8") as f:
            for no, line in enumerate(f, 1):
                m = INCLUDE.match(line)
                if not m:
                    continue
                inc = m.group(1)
                where = f"{path}:{no}"
                if inc == "coons.h" or inc.startswith("coons/"):
                    continue
                if "/" in inc:
                    problems.append(f"{where}: include \"{inc}\" has a path; "
                                    "name the header alone")
                    continue
                if inc not in owner:
                    problems.append(f"{where}: include \"{inc}\" is no header of src/")
                    continue
                if rank[owner[inc]] > rank[stage]:
                    problems.append(f"{where}: stage '{stage}' includes \"{inc}\" of "
                                    f"the later stage '{owner[inc]}'")
    for p in problems:
        print(p)
    print(f"check_layers: {len(files)} files, {len(stages)} stages, "
          f"{len(problems)} breaches")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
