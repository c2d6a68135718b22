#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The public headers document what every call can return, and name no
private file.

- every function declared `COONS_EXPORT coons_status` in include/coons/*.h
  has a comment right before it whose `@return` names at least one status
  (::COONS_OK or ::COONS_E_...), so that a caller can see every return
  without reading the source;
- no public header mentions a path under src/ (a banner naming a private
  file goes stale when the file moves, and means nothing to a user).

Usage: test_header_docs.py --bin <ignored> --src <source dir> --build <ignored>
"""
import argparse
import glob
import os
import re
import sys

RETURN = re.compile(r"@return\b[^@]*::COONS_(?:OK|E_[A-Z]+)\b", re.S)
STATUS_FN = re.compile(r"COONS_EXPORT\s+coons_status\s+(coons_\w+)\s*\(")


def comment_before(text, pos):
    """The /* ... */ comment that ends right before pos (blanks between), or ""."""
    before = text[:pos].rstrip()
    if not before.endswith("*/"):
        return ""
    return before[before.rindex("/*"):]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default="")
    ap.add_argument("--src", required=True)
    ap.add_argument("--build", default="")
    args = ap.parse_args()
    headers = sorted(glob.glob(os.path.join(args.src, "include", "coons", "*.h")) +
                     [os.path.join(args.src, "include", "coons.h")])
    failed = 0
    total = 0
    lacking = []
    private = []
    for h in headers:
        with open(h) as f:
            text = f.read()
        for m in STATUS_FN.finditer(text):
            total += 1
            if not RETURN.search(comment_before(text, m.start())):
                lacking.append(f"{os.path.basename(h)}: {m.group(1)}")
        for n, line in enumerate(text.splitlines(), 1):
            if re.search(r"\bsrc/", line):
                private.append(f"{os.path.basename(h)}:{n}: {line.strip()}")
    ok = total > 50 and not lacking
    print(("ok   " if ok else "FAIL ") +
          f"every status-returning function lists its returns ({total} functions)")
    if not ok:
        failed += 1
        print("lacking @return with a ::COONS_ status:\n  " + "\n  ".join(lacking))
    ok = not private
    print(("ok   " if ok else "FAIL ") + "no public header names a private file (src/...)")
    if not ok:
        failed += 1
        print("  " + "\n  ".join(private))
    print(f"{2 - failed} passed, {failed} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
