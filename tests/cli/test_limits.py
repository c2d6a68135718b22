# SPDX-License-Identifier: GPL-3.0-or-later
"""coons2stl under adverse conditions: mesh sizes above the limits, a full
disk, a file size limit, an unwritable standard output, signals before the
output exists.

In every case the run must fail with a message (exit status 3 for a limit
or a write failure), an earlier file at the output path must keep its bytes
and no other file (no temporary .NAME.coons-XXXXXX) may be left in the
directory. The full disk is a 256 KiB tmpfs mounted in a private mount
namespace (unshare -rm); where that is not permitted the case is skipped
with a note.
"""
import json
import os
import re
import resource
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner  # noqa: E402

OLD = b"solid previous\nan earlier output that must survive\n\x00\xff"
UNDER_VALGRIND = bool(os.environ.get("COONS_TEST_UNDER_VALGRIND"))
# Under valgrind the refusals take a limit 5 times lower and a refining
# tolerance 5 times looser: the same paths (refused at once from the first
# lattice, refused while refining, the suggested tolerance checked to fit)
# at a fifth of the triangles (the memcheck stage: 117 s -> see docs/TESTING.md).
MAXT = "20000" if UNDER_VALGRIND else "100000"
REFINE_TOL = "1.5e-3" if UNDER_VALGRIND else "3e-4"


def prepare(root):
    d = tempfile.mkdtemp(dir=root)
    out = os.path.join(d, "out.stl")
    with open(out, "wb") as f:
        f.write(OLD)
    return d, out


def kept(d, out):
    with open(out, "rb") as f:
        same = f.read() == OLD
    return same and os.listdir(d) == ["out.stl"], f"unchanged {same}, files {os.listdir(d)}"


def stl_volume_area(path):
    """Volume (divergence theorem) and area of a binary STL, computed here."""
    with open(path, "rb") as f:
        data = f.read()
    n = struct.unpack_from("<I", data, 80)[0]
    vol = area = 0.0
    for i in range(n):
        v = struct.unpack_from("<9f", data, 84 + 50 * i + 12)
        a, b, c = v[0:3], v[3:6], v[6:9]
        vol += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6
        u = [b[k] - a[k] for k in range(3)]
        w = [c[k] - a[k] for k in range(3)]
        x = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
        area += 0.5 * sum(q * q for q in x) ** 0.5
    return vol, area


def main():
    T = Runner(__doc__)
    spool = os.path.join(T.src, "examples", "spool.json")
    root = tempfile.mkdtemp(prefix="coons_limits_")
    try:
        # ---- mesh size limits: refused before the mesh is made ----------------
        cases = [
            (["--resolution", "5000"], ["resolution 5000", "300000000 triangles",
                                        "limit of 20000000", "--max-triangles"]),
            (["--resolution", "1048576"], ["resolution 1048576", "limit of 20000000",
                                           "--max-triangles"]),
            (["--resolution", "40", "--max-triangles", "1000"],
             ["resolution 40", "limit of 1000", "--max-triangles"]),
            (["-t", "1e-300", "--max-triangles", MAXT],
             ["tolerance 1e-300", f"more than {MAXT} triangles", "--max-triangles",
              "loosen the tolerance"]),
        ]
        for args, words in cases:
            d, out = prepare(root)
            t0 = time.monotonic()
            rc, _, err = T.run(args + ["-o", out, spool])
            dt = time.monotonic() - t0
            missing = [w for w in words if w not in err]
            label = " ".join(args)
            T.check(f"{label}: exit 3, message says {words}", rc == 3 and not missing,
                    f"status {rc}, missing {missing}: {err!r}")
            T.check(f"{label}: refused in {dt:.2f} s", dt < (60 if UNDER_VALGRIND else 10))
            ok, why = kept(d, out)
            T.check(f"{label}: earlier output unchanged, nothing created", ok, why)
        for args, words in [(["--resolution", "0"], ["--resolution", "1 to 1048576"]),
                            (["--resolution", "1048577"], ["--resolution", "1 to 1048576"]),
                            (["--max-triangles", "0"], ["--max-triangles", "> 0"]),
                            (["--max-triangles", "1e9"], ["--max-triangles", "whole number"])]:
            d, out = prepare(root)
            rc, _, err = T.run(args + ["-o", out, spool])
            missing = [w for w in words if w not in err]
            T.check(f"{' '.join(args)}: usage error (exit 2) naming the range",
                    rc == 2 and not missing, f"status {rc}: {err!r}")
            ok, why = kept(d, out)
            T.check(f"{' '.join(args)}: earlier output unchanged", ok, why)

        # ---- a refusal's suggested tolerance succeeds ---------------------------------
        # Refused at once from the first lattice's prediction (1e-6), and while
        # refining, when the prediction was low (3e-4): each names the tolerance,
        # a predicted count above the limit, and a tolerance that then samples.
        for tol in ("1e-6", REFINE_TOL):
            d, out = prepare(root)
            rc, _, err = T.run(["-t", tol, "--max-triangles", MAXT, "-o", out, spool])
            m = re.search(r"about ([0-9.e+]+) predicted.*\(try ([0-9.e+-]+)", err)
            T.check(f"-t {tol} --max-triangles {MAXT}: refused naming the tolerance, a "
                    "predicted count above the limit and a tolerance to try",
                    rc == 3 and m is not None and f"tolerance {float(tol):g}" in err
                    and float(m.group(1)) > int(MAXT), err)
            ok, why = kept(d, out)
            T.check(f"-t {tol}: earlier output unchanged", ok, why)
            if m:
                rc, _, err = T.run(["-t", m.group(2), "--max-triangles", MAXT, "-o", out,
                                    spool])
                T.check(f"-t {tol}: the suggested -t {m.group(2)} samples within the limit",
                        rc == 0, err)

        # ---- a fixed resolution is measured and warned about ---------------------------
        # The warned deviation d bounds the volume error: |V_mesh - V| <= d * area
        # (V: the model's exact volume from --info; V_mesh and area: the STL's).
        rc, js, err = T.run(["--info", spool])
        exact = json.loads(js)["total_volume"] if rc == 0 else None
        tolerance = json.loads(js)["tolerance"] if rc == 0 else None
        for res, warned in (("4", True), ("64", False)):
            out = os.path.join(root, f"r{res}.stl")
            rc, _, err = T.run(["--resolution", res, "-o", out, spool])
            m = re.search(r"warning: the fixed resolution (\d+) leaves a deviation of "
                          r"([0-9.e+-]+), more than the tolerance ([0-9.e+-]+)", err)
            if warned:
                ok = rc == 0 and m is not None and exact is not None
                if ok:
                    vol, area = stl_volume_area(out)
                    dev = float(m.group(2))
                    ok = (m.group(1) == res and abs(float(m.group(3)) - tolerance) < 1e-3 * tolerance
                          and dev > tolerance and abs(vol - exact) <= dev * area)
                T.check(f"--resolution {res}: written, with a warning naming the deviation "
                        "(above the tolerance, bounding the volume error) and the tolerance",
                        ok, err)
                rc, _, err = T.run(["-q", "--resolution", res, "-o", out, spool])
                T.check(f"--resolution {res} -q: no warning", rc == 0 and err == "", err)
            else:
                vol, area = stl_volume_area(out) if rc == 0 else (0, 0)
                T.check(f"--resolution {res}: written without a warning (its volume error "
                        "is within tolerance x area)",
                        rc == 0 and err == "" and abs(vol - exact) <= tolerance * area, err)

        # ---- the loader's limits can be raised ----------------------------------------
        model = os.path.join(root, "m.json")
        box = ('"type": "body0", "corners": [[0, 0, 0], [0, 0, 1], [0, 1, 0], [0, 1, 1], '
               '[1, 0, 0], [1, 0, 1], [1, 1, 0], [1, 1, 1]]')
        nested = '{"coons": 1, "bodies": [{' + box + '}], "units": ' + "[" * 80 + "]" * 80 + "}"
        line = '{"coons": 1, "bodies": [{' + box + '}]}'
        cube = ('{"coons": 1, "bodies": [{"type": "bezier-volume", "points": '
                '[[[[0,0,0],[0,0,1]],[[0,1,0],[0,1,1]]],[[[1,0,0],[1,0,1]],[[1,1,0],[1,1,1]]]]}]}')
        raise_cases = [
            # (text, limit option, too low, enough, words when too low, words when enough)
            (nested, "--max-depth", "64", "100", ["nested deeper than the limit of 64 levels"],
             ["/units", "expected a string"]),
            (line, "--max-values", "30", "100", ["more than 30 JSON values"], None),
            (line, "--max-bytes", str(len(line) - 1), str(len(line)),
             [f"the model is {len(line)} bytes, above the limit of {len(line) - 1} bytes"], None),
            (cube, "--max-points", "7", "8", ["more than 7 points", "limit of 7 points"], None),
        ]
        for text, opt, low, enough, words, after in raise_cases:
            with open(model, "w") as f:
                f.write(text)
            rc, _, err = T.run(["--info", opt, low, model])
            missing = [w for w in words + [opt + " N"] if w not in err]
            T.check(f"{opt} {low}: exit 1, the limit and how to raise it",
                    rc == 1 and not missing, f"status {rc}, missing {missing}: {err!r}")
            rc, out, err = T.run(["--info", opt, enough, model])
            if after is None:
                T.check(f"{opt} {enough}: loads", rc == 0 and '"body_count": 1' in out, err)
            else:
                T.check(f"{opt} {enough}: past the limit, the next error",
                        rc == 1 and all(w in err for w in after) and opt not in err, err)
        for opt, bad in (("--max-depth", "257"), ("--max-depth", "0"), ("--max-points", "-1"),
                         ("--max-values", "x"), ("--max-bytes", "")):
            rc, _, err = T.run(["--info", opt, bad, spool])
            T.check(f"{opt} '{bad}': usage error (exit 2)",
                    rc == 2 and opt in err and "whole number" in err, f"{rc} {err!r}")
        with open(spool, "rb") as f:
            rc, _, err = T.run(["--info", "--max-bytes", "100", "-"], stdin=f.read(), binary=True)
        T.check("--max-bytes 100 on standard input: exit 1, the limit and how to raise it",
                rc == 1 and b"<stdin>: the model is more than 100 bytes" in err and
                b"--max-bytes N" in err, repr(err))

        # ---- a file size limit (ulimit -f) --------------------------------------
        for fmt in ("stl", "stl-ascii", "off", "scad"):
            d, out = prepare(root)

            def limit():
                resource.setrlimit(resource.RLIMIT_FSIZE, (64 * 1024, 64 * 1024))
            p = subprocess.run([T.bin, "-f", fmt, "--resolution", "16", "-o", out, spool],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               preexec_fn=limit, timeout=600)
            T.check(f"ulimit -f 64 KiB, {fmt}: exit 3, 'File too large'",
                    p.returncode == 3 and "File too large" in p.stderr and "out.stl" in p.stderr,
                    f"status {p.returncode}: {p.stderr!r}")
            ok, why = kept(d, out)
            T.check(f"ulimit -f 64 KiB, {fmt}: earlier output unchanged, no temporary file",
                    ok, why)

        # ---- a full disk -----------------------------------------------------------
        mnt = tempfile.mkdtemp(dir=root)
        script = ('m=$1; old=$2; shift 2\n'
                  'mount -t tmpfs -o size=256k coons-test "$m" || exit 97\n'
                  'printf "%s" "$old" > "$m/out.stl"\n'
                  '"$@"\n'
                  'echo "status=$?"\n'
                  'ls -A "$m" | tr "\\n" " "; echo\n'
                  'cat "$m/out.stl"\n')
        old_text = "an earlier output that must survive"
        for fmt in ("stl", "off"):
            try:
                p = subprocess.run(
                    ["unshare", "-rm", "sh", "-c", script, "sh", mnt, old_text, T.bin, "-f", fmt,
                     "--resolution", "32", "-o", os.path.join(mnt, "out.stl"), spool],
                    stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=600)
            except (OSError, subprocess.TimeoutExpired) as e:
                print(f"note: full disk: skipped ({e})")
                break
            if p.returncode != 0 or not p.stdout.startswith("status="):
                print(f"note: full disk: no private tmpfs here, skipped ({p.stderr.strip()!r})")
                break
            lines = p.stdout.split("\n")
            status = int(lines[0].split("=")[1])
            T.check(f"full disk, {fmt}: exit 3, 'No space left on device'",
                    status == 3 and "No space left on device" in p.stderr,
                    f"status {status}: {p.stderr!r}")
            T.check(f"full disk, {fmt}: earlier output unchanged, no temporary file",
                    lines[1].split() == ["out.stl"] and lines[2] == old_text, f"{lines[:3]}")

        # ---- standard output that cannot be written -------------------------------
        if os.path.exists("/dev/full"):
            for fmt in ("stl", "stl-ascii", "off", "scad"):
                with open("/dev/full", "wb") as full:
                    p = subprocess.run([T.bin, "-f", fmt, "--resolution", "8", spool], stdout=full,
                                       stderr=subprocess.PIPE, text=True, timeout=600)
                T.check(f"standard output on /dev/full, {fmt}: exit 3, says so",
                        p.returncode == 3 and "No space left on device" in p.stderr,
                        f"status {p.returncode}: {p.stderr!r}")

        # ---- signals before the output exists ---------------------------------------
        # A fine tolerance keeps coons2stl sampling for a while; the signal
        # comes before the temporary file is made (if the run gets further,
        # the writer's own handling applies and the same must hold).
        for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            d, out = prepare(root)
            proc = subprocess.Popen([T.bin, "-t", "0.0004", "-o", out, spool],
                                    stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            time.sleep(3.0 if UNDER_VALGRIND else 0.3)
            proc.send_signal(sig)
            err = proc.communicate(timeout=600)[1]
            name = signal.Signals(sig).name
            if proc.returncode == 0:
                print(f"note: {name}: the run finished before the signal")
                continue
            T.check(f"{name} while sampling: died of it", proc.returncode == -sig,
                    f"{proc.returncode} {err!r}")
            ok, why = kept(d, out)
            T.check(f"{name} while sampling: earlier output unchanged, nothing created", ok, why)
    finally:
        shutil.rmtree(root, ignore_errors=True)
    T.finish()


if __name__ == "__main__":
    main()
