#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""coons2stl's command line: --help and --version (exit 0, stdout), usage
errors (exit 2, a message and a --help hint on stderr, nothing on stdout,
no output file touched), option spellings, and the mesh writer's promise:
whatever it does, a run that fails leaves an existing output file as it
was.

Usage: test_usage.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import os
import re
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
OK = os.path.join(T.data, "ok")
BOX = os.path.join(OK, "affine-box.json")
TWO = os.path.join(OK, "bezier-volume.json")

for args in (["--help"], ["-h"]):
    rc, out, err = T.run(args)
    T.check(f"{args[0]}: exit 0, usage on stdout", rc == 0 and out.startswith("Usage: coons2stl")
            and err == "", f"{rc} {err!r}")
    for opt in ("--output", "--format", "--tolerance", "--eval", "--jacobian", "--info",
                "--body", "--quiet", "--help", "--version"):
        if opt not in out:
            T.check(f"{args[0]} mentions {opt}", False)

with open(os.path.join(T.src, "CMakeLists.txt")) as f:
    version = re.search(r"project\(libcoons VERSION ([0-9.]+)", f.read()).group(1)
rc, out, err = T.run(["--version"])
T.check(f"--version: exit 0, names version {version} and format 1",
        rc == 0 and version in out and "format version 1" in out and err == "", f"{rc} {out!r} {err!r}")

work = tempfile.mkdtemp(prefix="coons_usage_")
SENTINEL = b"keep me\n"
out_file = os.path.join(work, "keep.stl")

USAGE = [
    ([], "no model file"),
    (["--frobnicate", BOX], "unknown option"),
    (["-x", BOX], "unknown option"),
    (["-qh", BOX], "unknown option"),
    (["--quiet=yes", BOX], "takes no value"),
    (["-o"], "needs a value"),
    (["--output"], "needs a value"),
    (["-f", "ply", BOX], "unknown format"),
    (["--format=stlx", BOX], "unknown format"),
    (["-t", "0", BOX], "--tolerance"),
    (["-t", "-1", BOX], "--tolerance"),
    (["--tolerance", "abc", BOX], "--tolerance"),
    (["--tolerance=1e999", BOX], "--tolerance"),
    ([BOX, TWO], "more than one model"),
    (["--eval", "--info", BOX], "cannot be combined"),
    (["--info", "-o", out_file, BOX], "standard output"),
    (["--eval", "-f", "off", BOX], "standard output"),
    (["--eval", "-"], "must come from a file"),
    (["-o", os.path.join(work, "mesh.txt"), BOX], "cannot tell the output format"),
    (["-o", os.path.join(work, "mesh"), BOX], "cannot tell the output format"),
    (["-o", os.path.join(work, ".stl"), BOX], "cannot tell the output format"),
    # Volume meshes and iso surfaces (outputs.md): bad values and combinations.
    (["--element", "hex9", "-o", os.path.join(work, "part.msh"), BOX], "--element needs hex8"),
    (["--element", "hex27", "-o", os.path.join(work, "part.inp"), BOX], "hex27 cannot"),
    (["--element", "hex20", "-o", out_file, BOX], "are for volume meshes"),
    (["--allow-inverted", "-o", out_file, BOX], "are for volume meshes"),
    (["--resolution", "2,3,4", "-o", out_file, BOX], "are for volume meshes"),
    (["--resolution", "2,3", "-o", os.path.join(work, "part.msh"), BOX], "--resolution needs"),
    (["--resolution", "2,3,4,5", "-o", os.path.join(work, "part.msh"), BOX], "--resolution needs"),
    (["--resolution", "2,,4", "-o", os.path.join(work, "part.msh"), BOX], "--resolution needs"),
    (["--resolution", "0,3,4", "-o", os.path.join(work, "part.msh"), BOX], "--resolution needs"),
    (["--volume-mesh", BOX], "--volume-mesh is for --info"),
    (["--info", "--volume-mesh", "-o", os.path.join(work, "part.vtu"), BOX], "leave out -o"),
    (["--iso", "u=1.5", "-o", os.path.join(work, "iso.off"), BOX], "outside the parameter range"),
    (["--iso", "w=-0.1", "-o", os.path.join(work, "iso.off"), BOX], "outside the parameter range"),
    (["--iso", "x=0.5", "-o", os.path.join(work, "iso.off"), BOX], "D one of u, v, w"),
    (["--iso", "u=0.5,a", "-o", os.path.join(work, "iso.off"), BOX], "is not a number"),
    (["--iso", "u=0.5", "-o", os.path.join(work, "part.msh"), BOX], "cannot hold"),
    (["--iso", "u=0.5", "-o", os.path.join(work, "part.inp"), BOX], "cannot hold"),
    (["--iso", "u=0.5", "-o", out_file, BOX], "cannot hold"),
    (["--with-boundary", "-o", os.path.join(work, "iso.off"), BOX], "--with-boundary is for --iso"),
    (["--body", "1", "--info", BOX], "indices 0..0"),
    (["--body", "nosuch", "--eval", BOX], "no body of that name"),
    (["--body", "99999999999999999999999", "--info", BOX], "the model has 1 body"),
]
for args, words in USAGE:
    with open(out_file, "wb") as f:
        f.write(SENTINEL)
    rc, out, err = T.run(args, stdin="0 0 0\n")
    with open(out_file, "rb") as f:
        same = f.read() == SENTINEL
    T.check(f"usage error {args}: exit 2, '{words}'",
            rc == 2 and words in err and err.startswith("coons2stl: ") and out == "" and same
            and sorted(os.listdir(work)) == ["keep.stl"], f"{rc} {err!r} {out!r}")
rc, out, err = T.run(["--bogus"])
T.check("usage errors hint at --help", "Try 'coons2stl --help'" in err, err)

# Option spellings that must work.
for args in (["--info", "--body=1", TWO], ["--info", "--body", "1", TWO], ["--info", "-q", TWO],
             ["--info", "--", TWO], ["--quiet", "--info", TWO]):
    rc, out, err = T.run(args)
    T.check(f"accepted: {args[:-1]}", rc == 0 and out.startswith("{"), f"{rc} {err!r}")
rc, out, err = T.run(["--jacobian", BOX], stdin="0 0 0\n")
T.check("--jacobian implies --eval (13 numbers)", rc == 0 and len(out.split()) == 13, f"{rc} {out!r} {err!r}")

# Format names are the library's (coons_format_from_name): any case, and
# "stl-binary" for "stl"; each gives the bytes of its canonical name.
for canonical, others in (("stl", ("STL", "stl-binary", "Stl-Binary")), ("off", ("OFF",)),
                          ("stl-ascii", ("STL-ASCII",))):
    rc0, want, _ = T.run(["-f", canonical, BOX], binary=True)
    for name in others:
        rc, out, err = T.run(["-f", name, BOX], binary=True)
        T.check(f"-f {name} is -f {canonical}", rc0 == 0 and rc == 0 and out == want and out,
                f"{rc0} {rc} {err!r}")

# Writing a mesh: if it fails, the existing file is unchanged and nothing else appears;
# if it succeeds, the file is replaced. (-ofile, --output=file, and the format from
# the extension in any case.)
for args in (["-o" + os.path.join(work, "keep.stl"), BOX],
             ["--output=" + os.path.join(work, "keep.stl"), BOX],
             ["-o", os.path.join(work, "keep.STL"), BOX],
             ["-f", "off", "-o", os.path.join(work, "keep.stl"), BOX]):
    for f in os.listdir(work):
        os.remove(os.path.join(work, f))
    target = [a for a in args if "keep" in a][0].split("=")[-1]
    target = target[2:] if target.startswith("-o") else target
    with open(target, "wb") as f:
        f.write(SENTINEL)
    rc, out, err = T.run(args)
    with open(target, "rb") as f:
        data = f.read()
    if rc == 0:
        T.check(f"mesh written {args[:-1]}", data != SENTINEL and os.listdir(work) == [os.path.basename(target)],
                str(os.listdir(work)))
    else:
        T.check(f"mesh not written {args[:-1]}: exit 3, output untouched",
                rc == 3 and data == SENTINEL and os.listdir(work) == [os.path.basename(target)]
                and err.startswith("coons2stl: "), f"{rc} {err!r} {os.listdir(work)}")

shutil.rmtree(work)
T.finish()
