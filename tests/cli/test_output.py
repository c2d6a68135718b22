#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""coons2stl's mesh output: formats, read-back, atomicity, signals.

- -o with .stl (binary), .off, .scad, -f stl-ascii, standard output (binary
  STL by default, `-o -` too); the binary STL header never starts with
  "solid" and carries the units, OFF carries them in a comment;
- the outputs read back here (own readers) with the same counts: facets of
  binary and ASCII STL = OFF faces = SCAD faces, distinct STL vertices =
  OFF vertices = SCAD points; same volume; outward (positive volume);
- the same run twice gives the same bytes;
- the output may not be the model file (also through a hard or symbolic
  link): usage error 2, the model untouched;
- a failed run (bad model, missing directory, unknown extension) leaves an
  existing output byte for byte and creates nothing;
- SIGTERM or SIGINT while the output is being written (seen by the
  temporary file appearing next to it): the process dies of the signal,
  says nothing was written, the previous output is unchanged and no
  temporary file remains.

Usage: test_output.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import os
import re
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner  # noqa: E402


def stl_binary(data):
    (n,) = struct.unpack_from("<I", data, 80)
    assert len(data) == 84 + 50 * n, "size does not match the count"
    return [struct.unpack_from("<12f", data, 84 + 50 * i) for i in range(n)]


def stl_ascii(text):
    facets, cur = [], []
    words = text.split()
    assert words[0] == "solid"
    for i, w in enumerate(words):
        if w == "normal":
            cur = [float(x) for x in words[i + 1:i + 4]]
        elif w == "vertex":
            cur += [float(x) for x in words[i + 1:i + 4]]
            if len(cur) == 12:
                facets.append(tuple(cur))
    return facets


def off(text):
    lines = [l for l in text.splitlines() if l.strip() and not l.startswith("#")]
    assert lines[0] == "OFF"
    nv, nf, ne = (int(x) for x in lines[1].split())
    v = [tuple(float(x) for x in l.split()) for l in lines[2:2 + nv]]
    f = []
    for l in lines[2 + nv:2 + nv + nf]:
        w = [int(x) for x in l.split()]
        assert w[0] == 3
        f.append(tuple(w[1:]))
    assert len(lines) == 2 + nv + nf
    comments = [l for l in text.splitlines() if l.startswith("#")]
    return v, f, comments


def scad(text):
    """Points and faces of every polyhedron(points = [...], faces = [...])."""
    pts, faces = [], []
    for m in re.finditer(r"points\s*=\s*\[(.*?)\]\s*,\s*faces\s*=\s*\[(.*?)\]\s*,\s*convexity",
                         text, re.S):
        pts += re.findall(r"\[\s*(-?[\d.e-]+)\s*,\s*(-?[\d.e-]+)\s*,\s*(-?[\d.e-]+)\s*\]",
                          m.group(1))
        faces += re.findall(r"\[\s*(\d+)\s*,\s*(\d+)\s*,\s*(\d+)\s*\]", m.group(2))
    return pts, faces


def soup_volume(tris):
    v = 0.0
    for t in tris:
        ax, ay, az, bx, by, bz, cx, cy, cz = t[-9:]
        v += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)
    return v / 6.0


def distinct_vertices(tris):
    s = set()
    for t in tris:
        for k in range(3):
            s.add(t[-9 + 3 * k:-6 + 3 * k] if k < 2 else t[-3:])
    return len(s)


def main():
    r = Runner(__doc__)
    model = os.path.join(r.src, "examples", "volume-bezier.json")
    tmp = tempfile.mkdtemp(prefix="coons-output-")
    try:
        p = lambda n: os.path.join(tmp, n)  # noqa: E731

        # ---- formats and read-back ------------------------------------------
        runs = {"m.stl": [], "m.off": [], "m.scad": [], "m.txt": ["-f", "stl-ascii"]}
        for name, extra in runs.items():
            st, _, err = r.run(extra + ["-o", p(name), model])
            r.check(f"-o {name} {' '.join(extra)}", st == 0 and os.path.exists(p(name)), err)
        with open(p("m.stl"), "rb") as f:
            b = f.read()
        r.check("binary STL header does not start with 'solid'",
                not b[:80].lstrip().lower().startswith(b"solid"), repr(b[:80]))
        r.check("binary STL header carries the units", b"units=mm" in b[:80], repr(b[:80]))
        tb = stl_binary(b)
        with open(p("m.txt")) as f:
            ta = stl_ascii(f.read())
        with open(p("m.off")) as f:
            v, faces, comments = off(f.read())
        with open(p("m.scad")) as f:
            stext = f.read()
        spts, sfaces = scad(stext)
        r.check("facets: binary STL = ASCII STL = OFF = SCAD",
                len(tb) == len(ta) == len(faces) == len(sfaces) > 0,
                f"{len(tb)} {len(ta)} {len(faces)} {len(sfaces)}")
        r.check("vertices: distinct STL vertices = OFF = SCAD points",
                distinct_vertices(tb) == len(v) == len(spts),
                f"{distinct_vertices(tb)} {len(v)} {len(spts)}")
        r.check("ASCII STL holds the binary STL's floats", [t[3:] for t in tb] ==
                [tuple(struct.unpack("<9f", struct.pack("<9f", *t[3:]))) for t in ta])
        off_tris = [v[a] + v[b2] + v[c] for a, b2, c in faces]
        vb, vo = soup_volume(tb), soup_volume(off_tris)
        r.check(f"outward, same volume: STL {vb:.6f}, OFF {vo:.6f}",
                vo > 0 and abs(vb - vo) <= 1e-5 * vo)
        r.check("OFF carries the units", "# units: mm" in comments, f"{comments}")
        r.check("SCAD carries the units", "// units: mm" in stext)
        # SCAD faces are the OFF faces reversed (single body: same numbering).
        r.check("SCAD faces are the OFF faces reversed",
                [(int(a), int(c), int(b2)) for a, b2, c in sfaces] == faces)

        st, out, err = r.run([model], binary=True)
        r.check("standard output: binary STL by default", st == 0 and out == b, err)
        st, out, err = r.run(["-o", "-", model], binary=True)
        r.check("-o - is standard output", st == 0 and out == b, err)
        st, _, err = r.run(["-o", p("again.stl"), model])
        with open(p("again.stl"), "rb") as f:
            r.check("the same run gives the same bytes", f.read() == b)

        # ---- the model file is never the output ------------------------------
        own = p("own.json")
        shutil.copy(model, own)
        with open(own, "rb") as f:
            before = f.read()
        os.link(own, p("hard.stl"))
        os.symlink("own.json", p("soft.stl"))
        for out in (own, p("hard.stl"), p("soft.stl")):
            st, _, err = r.run(["-f", "stl", "-o", out, own])
            with open(own, "rb") as f:
                r.check(f"-o {os.path.basename(out)} naming the model: exit 2, model kept",
                        st == 2 and f.read() == before and "model file" in err, f"{st} {err}")

        # ---- failures leave the previous output -------------------------------
        old = b"previous output\n"
        target = p("keep.stl")
        with open(target, "wb") as f:
            f.write(old)
        bad = p("bad.json")
        with open(bad, "w") as f:
            f.write('{"coons": 1, "bodies": [ {"type": "body0"} ]}')
        st, _, err = r.run(["-o", target, bad])
        with open(target, "rb") as f:
            r.check("bad model: exit 1, output untouched", st == 1 and f.read() == old, err)
        st, _, err = r.run(["-o", p("missing/x.stl"), model])
        r.check("missing directory: exit 3, message", st == 3 and "missing/x.stl" in err, err)
        st, _, err = r.run(["-o", p("x.obj"), model])
        r.check("unknown extension: exit 2, nothing made", st == 2 and
                not os.path.exists(p("x.obj")), err)
        st, _, err = r.run(["-f", "off", "-o", p("x.obj"), model])
        r.check("-f off overrides the extension", st == 0 and
                open(p("x.obj")).read().startswith("OFF\n"), err)
        leftovers = [n for n in os.listdir(tmp) if ".coons-" in n]
        r.check("no temporary file left anywhere", not leftovers, f"{leftovers}")

        # ---- signals while writing ---------------------------------------------
        spool = os.path.join(r.src, "examples", "spool.json")
        for sig in (signal.SIGTERM, signal.SIGINT):
            d = tempfile.mkdtemp(dir=tmp)
            out = os.path.join(d, "big.off")
            with open(out, "wb") as f:
                f.write(old)
            proc = subprocess.Popen([r.bin, "-t", "0.002", "-o", out, spool],
                                    stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            hit = False
            deadline = time.monotonic() + 120
            while proc.poll() is None and time.monotonic() < deadline:
                if any(n.startswith(".big.off.coons-") for n in os.listdir(d)):
                    proc.send_signal(sig)
                    hit = True
                    break
                time.sleep(0.0005)
            err = proc.communicate(timeout=120)[1]
            with open(out, "rb") as f:
                content = f.read()
            name = signal.Signals(sig).name
            if not hit:
                print(f"note: {name}: the write finished before the temporary file was seen")
                r.check(f"{name}: complete output", content.startswith(b"OFF\n"))
                continue
            r.check(f"{name} while writing: died of the signal", proc.returncode == -sig,
                    f"{proc.returncode} {err}")
            r.check(f"{name} while writing: says nothing was written",
                    "interrupted; nothing was written" in err, err)
            r.check(f"{name} while writing: previous output unchanged, no temporary file",
                    content == old and os.listdir(d) == ["big.off"], f"{os.listdir(d)}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    r.finish()


if __name__ == "__main__":
    main()
