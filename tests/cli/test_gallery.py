#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The gallery (docs/gallery.md, made by tools/gallery.sh): seed 000's figures rendered by the
real OpenSCAD (preview, under xvfb-run) from coons2stl's output.

- `gallery.sh --list` names every picture with an existing example model
  and a seed figure, and covers Figs. 2 to 9;
- `gallery.sh -o TMP fig2-deformed-cube` (one picture, made here) writes a
  PNG that this test decodes itself (zlib and the PNG row filters): the
  signature, an IHDR of 480 x 360, 8-bit RGB(A), every IDAT row present, and
  an object drawn, between 2% and 90% of the pixels not of the background
  (the colour of the corners) and none of them touching the border
  (--viewall keeps the model inside the picture);
- every picture committed in examples/img/ is such a PNG, under 60 kB, and
  docs/gallery.md shows it with its model file and its coons2stl command.

Usage: test_gallery.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner  # noqa: E402

W, H = 480, 360          # gallery.sh's --imgsize
MAX_BYTES = 60 * 1024


def decode_png(path):
    """(width, height, rows of pixel tuples) of an 8-bit RGB/RGBA/grey PNG."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("no PNG signature")
    pos, idat, ihdr = 8, b"", None
    while pos < len(data):
        (n,) = struct.unpack_from(">I", data, pos)
        kind = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + n]
        (crc,) = struct.unpack_from(">I", data, pos + 8 + n)
        if zlib.crc32(kind + body) != crc:
            raise ValueError(f"bad CRC in {kind}")
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
        pos += 12 + n
    w, h, depth, ctype, _, _, interlace = ihdr
    channels = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
    if depth != 8 or interlace != 0:
        raise ValueError(f"depth {depth}, interlace {interlace}")
    raw = zlib.decompress(idat)
    stride = w * channels
    if len(raw) != h * (stride + 1):
        raise ValueError(f"{len(raw)} bytes of image data for {w} x {h}")
    rows, prev = [], bytearray(stride)
    for y in range(h):
        ft = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = prev[i]
            c = prev[i - channels] if i >= channels else 0
            if ft == 1:
                line[i] = (line[i] + a) & 255
            elif ft == 2:
                line[i] = (line[i] + b) & 255
            elif ft == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif ft == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
            elif ft != 0:
                raise ValueError(f"filter type {ft}")
        rows.append([tuple(line[x * channels:(x + 1) * channels]) for x in range(w)])
        prev = line
    return w, h, rows


def check_png(r, label, path):
    try:
        w, h, rows = decode_png(path)
    except (ValueError, KeyError, TypeError, zlib.error, struct.error) as e:
        r.check(f"{label}: a valid PNG", False, str(e))
        return
    r.check(f"{label}: a valid PNG of {W} x {H}", (w, h) == (W, H), f"{w} x {h}")
    bg = rows[0][0]
    corners = [rows[0][0], rows[0][w - 1], rows[h - 1][0], rows[h - 1][w - 1]]
    drawn = sum(1 for row in rows for p in row if p != bg)
    border = sum(1 for x in range(w) for y in (0, h - 1) if rows[y][x] != bg) + \
        sum(1 for y in range(h) for x in (0, w - 1) if rows[y][x] != bg)
    frac = drawn / float(w * h)
    r.check(f"{label}: an object drawn ({100 * frac:.1f}% of the pixels), inside the picture",
            all(c == bg for c in corners) and 0.02 <= frac <= 0.90 and border == 0,
            f"background {bg}, corners {corners}, border pixels {border}")


def main():
    r = Runner(__doc__)
    for tool in ("openscad", "xvfb-run"):
        if not shutil.which(tool):
            print(f"FAIL {tool} is not installed (tools/setup.sh installs it)")
            sys.exit(1)
    script = os.path.join(r.src, "tools", "gallery.sh")
    p = subprocess.run(["sh", script, "--list"], stdout=subprocess.PIPE, text=True)
    pics = [ln.split("\t") for ln in p.stdout.splitlines() if ln]
    r.check("gallery.sh --list", p.returncode == 0 and pics and all(len(x) == 4 for x in pics),
            p.stdout)
    figs = set()
    for name, model, args, fig in pics:
        r.check(f"{name}: its model examples/{model} exists",
                os.path.exists(os.path.join(r.src, "examples", model)))
        figs.add(int(fig))
    r.check("Figs. 2 to 9 all pictured", figs >= set(range(2, 10)), f"{sorted(figs)}")

    tmp = tempfile.mkdtemp(prefix="coons-gallery-")
    try:
        one = "fig2-deformed-cube"
        p = subprocess.run(["sh", script, "-b", r.build, "-o", tmp, one],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                           timeout=600)
        png = os.path.join(tmp, one + ".png")
        if r.check(f"gallery.sh {one} writes {one}.png", p.returncode == 0 and
                   os.path.exists(png), p.stderr):
            check_png(r, f"made here: {one}.png", png)
        r.check("gallery.sh writes nothing else", sorted(os.listdir(tmp)) == [one + ".png"],
                f"{os.listdir(tmp)}")
        p = subprocess.run(["sh", script, "-b", r.build, "-o", tmp, "no-such-picture"],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        r.check("gallery.sh refuses an unknown picture", p.returncode == 2 and
                "no-such-picture" in p.stderr, p.stderr)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)

    with open(os.path.join(r.src, "docs", "gallery.md"), encoding="utf-8") as f:
        gallery = f.read()
    for name, model, args, fig in pics:
        path = os.path.join(r.src, "examples", "img", name + ".png")
        if not r.check(f"examples/img/{name}.png is committed", os.path.exists(path)):
            continue
        size = os.path.getsize(path)
        r.check(f"examples/img/{name}.png: {size} bytes < {MAX_BYTES}", size < MAX_BYTES)
        check_png(r, f"examples/img/{name}.png", path)
        cmd = " ".join(["coons2stl", f"examples/{model}"] + args.split() +
                       ["-o", f"{name}.scad"])
        r.check(f"docs/gallery.md shows {name}.png with `{cmd}`",
                f"(../examples/img/{name}.png)" in gallery and f"`{cmd}`" in gallery)
    r.finish()


if __name__ == "__main__":
    main()
