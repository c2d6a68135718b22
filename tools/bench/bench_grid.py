#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Grid-evaluation benchmark of a Coons body 2 with bicubic B-spline faces.

Runs the C program bench_grid (coons_body_eval_grid on an N^3 grid, single
thread, and the memory-write bound for the same output array), then builds
the same volume with splipy (volume_factory.edge_surfaces of the six faces,
installing splipy with pip if it is missing), times splipy's vectorised
evaluation on the same grid, checks that both agree, and prints the numbers
and their ratios.

splipy runs in child processes, once with one BLAS thread (like the C side)
and once with the default thread count.

Usage: bench_grid.py [--bin PATH/bench_grid] [-n 200] [-r 7]
"""
import argparse
import glob
import importlib
import json
import os
import subprocess
import sys
import time


def find_bin():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(os.path.dirname(here))
    for pat in ("build/tools/bench/bench_grid", "build*/tools/bench/bench_grid",
                "../build*/tools/bench/bench_grid"):
        hits = sorted(glob.glob(os.path.join(root, pat)))
        if hits:
            return hits[0]
    return None


def ensure_splipy():
    try:
        return importlib.import_module("splipy")
    except ImportError:
        print("installing splipy with pip ...", file=sys.stderr)
        subprocess.check_call([sys.executable, "-m", "pip", "install", "-q", "splipy"])
        importlib.invalidate_caches()
        return importlib.import_module("splipy")


def splipy_child(args):
    """Times splipy in this (child) process: reads the C program's JSON on
    stdin, prints {"seconds", "worst", "version", "threads"}."""
    splipy = ensure_splipy()
    import numpy as np
    from splipy import BSplineBasis, Surface, volume_factory

    c = json.load(sys.stdin)
    n, m = c["n"], c["net"]
    # Our default knots: clamped uniform, normalised onto [0,1].
    inner = [i / (m - 3) for i in range(1, m - 3)]
    knots = [0.0] * 4 + inner + [1.0] * 4
    surfs = []
    for f in c["faces"]:
        cp = np.array(f, dtype=float).reshape(m, m, 3)  # [a][b], a along s
        surfs.append(Surface(BSplineBasis(4, knots), BSplineBasis(4, knots), cp, raw=True))
    # splipy's order (umin, umax, vmin, vmax, wmin, wmax) and face
    # parametrisations ((v,w), (u,w), (u,v)) are those of body.h.
    vol = volume_factory.edge_surfaces(*surfs)
    t = np.linspace(0.0, 1.0, n)
    best = float("inf")
    res = None
    for _ in range(args.r):
        res = None
        t0 = time.perf_counter()
        res = vol(t, t, t)
        best = min(best, time.perf_counter() - t0)
    worst = 0.0
    for (i, j, k, x, y, z) in c["probes"]:
        worst = max(worst, float(np.max(np.abs(res[i, j, k] - np.array([x, y, z])))))
    json.dump({"seconds": best, "worst": worst, "version": splipy.__version__,
               "threads": os.environ.get("OPENBLAS_NUM_THREADS", "default")}, sys.stdout)


def run_splipy(c, runs, threads):
    env = dict(os.environ)
    if threads:
        for k in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
            env[k] = str(threads)
    out = subprocess.run([sys.executable, os.path.abspath(__file__), "--splipy-child",
                          "-r", str(runs)], input=json.dumps(c), capture_output=True,
                         text=True, env=env, check=True).stdout
    return json.loads(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", help="path of the bench_grid executable")
    ap.add_argument("-n", type=int, default=200, help="samples per direction")
    ap.add_argument("-r", type=int, default=7, help="runs (best is kept)")
    ap.add_argument("--splipy-child", action="store_true", help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.splipy_child:
        splipy_child(a)
        return
    ensure_splipy()  # install before timing anything
    exe = a.bin or find_bin()
    if not exe or not os.path.exists(exe):
        sys.exit("bench_grid: executable not found; build it (target bench_grid) and pass --bin")

    n = a.n
    probes = [(0, 0, 0), (n - 1, n - 1, n - 1), (n // 2, n // 3, n // 5), (1, n - 2, n // 2),
              (n // 7, n // 2, n - 1), (n - 1, 0, n // 4)]
    cmd = [exe, "-n", str(n), "-r", str(a.r), "--net"]
    for p in probes:
        cmd += ["--probe", "%d,%d,%d" % p]
    c = json.loads(subprocess.check_output(cmd))
    s1 = run_splipy(c, a.r, 1)
    sd = run_splipy(c, a.r, None)

    npts = n ** 3
    m = c["net"]
    lib = c["grid_fresh_pts_per_s"]
    print("Coons body 2, bicubic B-spline faces (%dx%d control points each), %d^3 grid = %d points,"
          " best of %d runs" % (m, m, n, npts, a.r))
    print("  max |libcoons - splipy| at %d probe points: %.3g" % (len(probes), max(s1["worst"], sd["worst"])))
    print("  libcoons coons_body_eval_grid, 1 thread, fresh output:  %.4f s  %.3e points/s"
          % (c["grid_fresh_s"], lib))
    print("  libcoons coons_body_eval_grid, 1 thread, reused output: %.4f s  %.3e points/s"
          % (c["grid_warm_s"], c["grid_warm_pts_per_s"]))
    for s in (s1, sd):
        print("  splipy %s edge_surfaces volume, vectorised, BLAS threads %s: %.4f s  %.3e points/s"
              % (s["version"], s["threads"], s["seconds"], npts / s["seconds"]))
    print("  memory-write bound, 24 B/point into a fresh array: memset %.4f s, store loop %.4f s"
          % (c["memset_s"], c["store_loop_s"]))
    print("  store loop into the reused array: %.4f s" % c["warm_store_loop_s"])
    print("  ratio libcoons/splipy (points/s, fresh output): %.2fx vs 1-thread BLAS, %.2fx vs default"
          % (lib * s1["seconds"] / npts, lib * sd["seconds"] / npts))
    print("  libcoons time / write-bound time (fresh arrays): %.2f; reused array vs store loop: %.2f"
          % (c["grid_fresh_s"] / c["write_bound_s"], c["warm_grid_over_warm_store"]))
    print("  libcoons coons_body_eval_grid_threads, %d threads: fresh %.4f s (%.2fx one thread), "
          "reused %.4f s (%.2fx); all-core write bound %.4f s (threads / bound %.2f); "
          "byte-identical to one thread: %s"
          % (c["threads"], c["grid_fresh_threads_s"], c["speedup_fresh"], c["grid_warm_threads_s"],
             c["speedup_warm"], c["store_loop_threads_s"], c["threads_over_bound"],
             c["threads_equal"]))
    if not c["threads_equal"]:
        sys.exit("bench_grid: the threaded grid differs from the one-thread grid")
    if max(s1["worst"], sd["worst"]) > 1e-9:
        sys.exit("bench_grid: libcoons and splipy disagree")


if __name__ == "__main__":
    main()
