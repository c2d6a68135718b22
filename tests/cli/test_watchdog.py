# SPDX-License-Identifier: GPL-3.0-or-later
"""A watchdog over every mode of coons2stl (issue 15, "bounded work"):
every example (examples/*.json) and every tests/data model that loads
finishes each mode within RUN_BOUND seconds, killed by signal never:

- `-o` to each surface format (.stl at the model's own tolerance; .off,
  .scad, .3mf at a coarse one),
- `--info` (the volume integral, the solid checks),
- `--eval --jacobian` (three points on standard input),
- `-o` to the volume formats .msh and .vtu (coarse).

A run may fail (a fold refused, a volume mesh with inverted cells: exit 1
or 3, with a message), but it must end, by itself, with a status of the
documented ones. RUN_BOUND is a hang detector, not a timing assertion: it
is many times what any run takes (the slowest here take about a second in
a release build). The coarse tolerance is 1/50 of the model's control
box diagonal (from `--info --no-solid`), so that the formats' writers are
exercised on small meshes and the whole test stays short in CI.
"""
import concurrent.futures
import glob
import json
import os
import shutil
import subprocess
import tempfile

from clitest import Runner

UNDER_VALGRIND = bool(os.environ.get("COONS_TEST_UNDER_VALGRIND"))
RUN_BOUND = 600 if UNDER_VALGRIND else 60  # seconds per run
STATUSES = (0, 1, 3)  # success, bad input, a geometric operation failed
POINTS = "0 0 0\n0.5 0.25 0.75\n1 1 1\n"


def models(src):
    out = sorted(glob.glob(os.path.join(src, "examples", "*.json")))
    for sub in ("ok", "csg", "refs", "hostile", "bad"):
        out += sorted(glob.glob(os.path.join(src, "tests", "data", sub, "*.json")))
    return out


def run(binary, args, stdin=None, cwd=None):
    """(status or None on timeout, seconds, stderr tail)."""
    import time
    t0 = time.monotonic()
    try:
        p = subprocess.run([binary] + args, input=stdin, cwd=cwd, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True, errors="replace",
                           timeout=RUN_BOUND)
        return p.returncode, time.monotonic() - t0, p.stdout, p.stderr[-300:]
    except subprocess.TimeoutExpired:
        return None, time.monotonic() - t0, "", "timed out"


def diagonal(info):
    try:
        box = json.loads(info)["control_bbox"]
    except (ValueError, KeyError, TypeError):
        return None
    lo, hi = box["min"], box["max"]
    return sum((hi[i] - lo[i]) ** 2 for i in range(3)) ** 0.5


def main():
    T = Runner(__doc__)
    root = tempfile.mkdtemp(prefix="coons_watchdog_")
    try:
        # ---- which models load, and their size (--info --no-solid) ----------
        loaded = []
        for m in models(T.src):
            rel = os.path.relpath(m, T.src)
            rc, dt, out, err = run(T.bin, ["-q", "--info", "--no-solid", m])
            T.check(f"{rel}: --info --no-solid ends ({dt:.2f} s, status {rc})",
                    rc in STATUSES, err)
            if rc == 0:
                d = diagonal(out)
                T.check(f"{rel}: --info gives the control box", d is not None and d > 0,
                        out[:200])
                if d:
                    loaded.append((m, rel, d))
        T.check("most examples and tests/data models load", len(loaded) >= 50,
                f"{len(loaded)} loaded")

        # ---- every mode of every model that loads -----------------------------
        jobs = []
        for i, (m, rel, d) in enumerate(loaded):
            work = os.path.join(root, str(i))
            os.mkdir(work)
            coarse = ["-t", f"{d / 50:.6g}"]
            jobs.append((rel, ["-q", "-o", "out.stl", m], None, work))
            for ext in ("off", "scad", "3mf"):
                jobs.append((rel, ["-q"] + coarse + ["-o", f"out.{ext}", m], None, work))
            jobs.append((rel, ["-q", "--info"] + coarse + [m], None, work))
            jobs.append((rel, ["-q", "--eval", "--jacobian", m], POINTS, work))
            for ext in ("msh", "vtu"):
                jobs.append((rel, ["-q"] + coarse + ["-o", f"out.{ext}", m], None, work))
        slowest = (0.0, "")
        with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
            futures = [(j, pool.submit(run, T.bin, j[1], j[2], j[3])) for j in jobs]
            for (rel, args, _, _), f in futures:
                rc, dt, _, err = f.result()
                label = " ".join(a for a in args if a not in ("-q",) and not a.endswith(".json"))
                T.check(f"{rel}: {label}: ends within {RUN_BOUND} s, status {rc} ({dt:.2f} s)",
                        rc in STATUSES, err)
                if dt > slowest[0]:
                    slowest = (dt, f"{rel} {label}")
        print(f"# {len(jobs)} runs; slowest {slowest[0]:.2f} s: {slowest[1]}")
    finally:
        shutil.rmtree(root, ignore_errors=True)
    T.finish()


if __name__ == "__main__":
    main()
