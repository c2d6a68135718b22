#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Rewrites sources written for libcoons 0.2 to the 0.3 names.

    tools/migrate-0.3.py PATH...          rewrites the files in place
    tools/migrate-0.3.py --check PATH...  lists what it would change, exit 1 if any

A PATH that is a directory is walked for C, C++, Python, man page and
Markdown files (.c .h .cpp .hpp .cc .cxx .in .py .md .1 .3 .5 .txt). The
table is tools/abi-0.3-renames.txt ("old new" a line): every old name is
replaced, as a whole word, by its new one, and every use of a name 0.3
removed ("old -") is listed with its line and what to use instead. No new
name is an old one, so running the tool again over migrated (or partly
migrated) code changes nothing more. Lines from one that says
"migrate-0.3: off" to one that says "migrate-0.3: on" are left as they are.
Code still on the 0.1 names: run tools/migrate-0.2.py first.
"""
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TABLE = os.path.join(HERE, "abi-0.3-renames.txt")
SUFFIXES = (".c", ".h", ".cpp", ".hpp", ".cc", ".cxx", ".in", ".py", ".md", ".1", ".3", ".5",
            ".txt")


def load_table(path=TABLE):
    """(renames {old: new}, removed {old: note}) from the table."""
    renames, removed = {}, {}
    with open(path, encoding="utf-8") as f:
        for n, raw in enumerate(f, 1):
            line = raw.strip()
            if not line or line.startswith("#"):
                continue
            head, _, note = line.partition("#")
            words = head.split()
            if len(words) != 2:
                raise SystemExit(f"{path}:{n}: expected 'old new' or 'old -'")
            old, new = words
            if new == "-":
                removed[old] = note.strip()
            else:
                renames[old] = new
    clash = set(renames.values()) & (set(renames) | set(removed))
    if clash:
        raise SystemExit(f"{path}: a new name is also an old one: {sorted(clash)}")
    return renames, removed


def migrate(text, renames, removed):
    """Returns (new text, [(line, old name, note)] of uses of removed names)."""
    names = sorted(set(renames) | set(removed), key=len, reverse=True)
    pattern = re.compile(r"\b(" + "|".join(map(re.escape, names)) + r")\b")
    notes = []
    out = []
    skip = False
    for n, line in enumerate(text.splitlines(keepends=True), 1):
        if "migrate-0.3: off" in line or skip:
            skip = "migrate-0.3: on" not in line
            out.append(line)
            continue

        def sub(m):
            old = m.group(1)
            if old in removed:
                notes.append((n, old, removed[old]))
                return old
            return renames[old]
        out.append(pattern.sub(sub, line))
    return "".join(out), notes


def files_of(paths):
    for p in paths:
        if os.path.isdir(p):
            for root, dirs, files in os.walk(p):
                dirs[:] = sorted(d for d in dirs if not d.startswith(".") and
                                 not d.startswith("build"))
                for name in sorted(files):
                    if name.endswith(SUFFIXES):
                        yield os.path.join(root, name)
        else:
            yield p


def main(argv):
    check = "--check" in argv
    paths = [a for a in argv if a != "--check"]
    if not paths:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    renames, removed = load_table()
    me = {os.path.abspath(__file__), os.path.abspath(TABLE)}
    changed = 0
    for path in files_of(paths):
        if os.path.abspath(path) in me:
            continue
        with open(path, encoding="utf-8", errors="surrogateescape") as f:
            text = f.read()
        new, notes = migrate(text, renames, removed)
        for n, old, note in notes:
            print(f"{path}:{n}: {old}: removed in 0.3: {note}")
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
