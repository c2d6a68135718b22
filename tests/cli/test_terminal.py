#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Binary output is never written onto a terminal (coons2stl(1), -o; the
output contract, "Honest output"), on a real pseudo-terminal (pty):

- no -o, standard output a terminal, binary STL (the default) or 3MF:
  exit 2, a hint naming -o FILE and -o -, and not one byte on the terminal;
- `-o -` onto the terminal writes the binary STL on purpose (the bytes
  arrive: an 80-byte header, a count, 50 bytes per triangle);
- text formats (-f off) onto a terminal are written as before, and without
  -o binary STL still goes to a pipe.

Usage: test_terminal.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import os
import pty
import select
import shutil
import struct
import subprocess
import sys
import tempfile
import tty

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
TMP = tempfile.mkdtemp(prefix="coons-tty-")
MODEL = os.path.join(TMP, "box.json")
with open(MODEL, "w") as fh:
    json.dump({"coons": 1, "bodies": [{"type": "body0", "name": "box", "corners": [
        [0, 0, 0], [0, 0, 1], [0, 1, 0], [0, 1, 1], [1, 0, 0], [1, 0, 1], [1, 1, 0],
        [1, 1, 1]]}]}, fh)


def on_tty(args):
    """Runs coons2stl with standard output a pty (standard error a pipe);
    returns (status, bytes that reached the terminal, stderr)."""
    master, slave = pty.openpty()
    # raw: the terminal passes the bytes as written (no \n -> \r\n)
    tty.setraw(slave)
    p = subprocess.Popen([T.bin] + args, stdin=subprocess.DEVNULL, stdout=slave,
                         stderr=subprocess.PIPE)
    os.close(slave)
    got = b""
    while True:
        r, _, _ = select.select([master], [], [], 60)
        if not r:
            break
        try:
            chunk = os.read(master, 65536)
        except OSError:  # EIO: the child closed its end
            break
        if not chunk:
            break
        got += chunk
    err = p.stderr.read().decode("utf-8", "replace")
    rc = p.wait(timeout=T.timeout)
    os.close(master)
    return rc, got, err


for args, what in (([MODEL], "binary STL"), (["-f", "3mf", MODEL], "a 3MF package")):
    rc, got, err = on_tty(args)
    T.check(f"{args[:-1] or 'no -o'}: {what} onto a terminal refused: exit 2, nothing on it",
            rc == 2 and got == b"", f"{rc} {got[:80]!r} {err}")
    T.check(f"{args[:-1] or 'no -o'}: the message names {what}, -o FILE and -o -",
            what in err and "-o FILE" in err and "-o -" in err and "nothing was written" in err
            and err.count("\n") == 1, err)

rc, got, err = on_tty(["-o", "-", MODEL])
n = struct.unpack("<I", got[80:84])[0] if len(got) >= 84 else -1
T.check("-o - onto a terminal: binary STL written on purpose (header, count, 50 bytes each)",
        rc == 0 and n > 0 and len(got) == 84 + 50 * n, f"{rc} {len(got)} {n} {err}")
rc, got, err = on_tty(["-f", "off", MODEL])
T.check("-f off (text) onto a terminal: written as before",
        rc == 0 and got.startswith(b"OFF"), f"{rc} {got[:40]!r} {err}")
rc, out, err = T.run([MODEL], binary=True)
T.check("no -o into a pipe: binary STL on standard output as before",
        rc == 0 and len(out) > 84 and not out.startswith(b"solid"), err)

shutil.rmtree(TMP)
T.finish()
