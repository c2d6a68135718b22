# SPDX-License-Identifier: GPL-3.0-or-later
"""coons2stl on hostile input: malformed, truncated, wrongly encoded and
absurdly large models.

Every file in tests/data/hostile has an entry below (and back). For each,
coons2stl -o out.stl must exit with status 1 and one line on stderr,
"coons2stl: FILE:LINE:COL: PATH: ...", whose position is computed here from
the file's bytes (the first occurrence of a marker, or the end of the file),
counting lines as LF, CR LF or CR and columns in code points; a file that
already exists at out.stl must keep its bytes and nothing else may appear
in the directory. Large inputs are made at test time (a million nested
arrays, 9 million values, a million points, a 1.1 GB sparse file, every
example cut short) and must end in an error within bounded time and memory.
"""
import os
import shutil
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner  # noqa: E402

EOF = None
# name: (marker or EOF, bytes past the marker's start, JSON path, words)
CASES = {
    "truncated-number": (EOF, 0, "/bodies/0/corners/1/1",
                         ["expected ',' or ']'", "end of the input"]),
    "truncated-string": (b': "bod', 2, "/bodies/0/type", ["unterminated string"]),
    "truncated-after-key": (EOF, 0, "/bodies", ["expected ':'", "end of the input"]),
    "truncated-escape": (b'"mm', 0, "/units", ["unterminated string"]),
    "utf8-latin1-name": (b"\xe9", 0, "/bodies/0/name", ["invalid UTF-8", "0xE9"]),
    "utf8-overlong": (b"\xc0", 0, "/units", ["invalid UTF-8", "0xC0"]),
    "utf8-surrogate": (b"\xed", 0, "/units", ["invalid UTF-8", "0xED"]),
    "utf8-cut-sequence": (b"\xe2", 0, "/units", ["invalid UTF-8", "0xE2"]),
    "utf8-above-max": (b"\xf4", 0, "/units", ["invalid UTF-8", "0xF4"]),
    "utf16le": (b"\xff\xfe", 0, "", ["JSON object", "0xFF"]),
    "byte-outside-string": (b"\xff", 0, "/coons", ["expected a value", "0xFF"]),
    "number-1e400": (b"1e400", 0, "/bodies/0/corners/3/2", ["1e400", "range of a double"]),
    "number-minus-1e400": (b"-1e400", 0, "/tolerance", ["-1e400", "range of a double"]),
    "token-nan": (b"NaN", 0, "/tolerance", ["expected a value", "'N'"]),
    "token-infinity": (b"Infinity", 0, "/bodies/0/corners/3/1", ["expected a value", "'I'"]),
    "token-minus-infinity": (b"-Infinity", 0, "/bodies/0/corners/3/1",
                             ["invalid number", "-Infinity"]),
    "number-hex": (b"0x1F", 0, "/bodies/0/corners/3/1", ["invalid number", "0x1F"]),
    "number-plus": (b"+1", 0, "/bodies/0/corners/3/1", ["expected a value", "'+'"]),
    "number-leading-zero": (b"01", 0, "/bodies/0/corners/3/1", ["invalid number", '"01"']),
    "number-trailing-dot": (b"1.,", 0, "/bodies/0/corners/3/1", ["invalid number", '"1."']),
    "nul-in-string": (b"\x00", 0, "/units", ["control character", "U+0000"]),
    "nul-name-escape": (b'"a\\u0000b"', 0, "/bodies/0/name", ["U+0000"]),
    "lone-low-surrogate": (b"\\udc00", 0, "/units", ["surrogate"]),
    "empty": (b"", 0, "", ["empty document"]),
    "whitespace-only": (EOF, 0, "", ["empty document"]),
    "top-level-array": (b"[", 0, "", ["JSON object", "'['"]),
    "comment": (b"//", 0, "", ["expected a key", "'/'"]),
    "trailing-comma": (b", ]", 2, "/bodies/0/corners/8", ["expected a value", "']'"]),
    "single-quotes": (b"'", 0, "", ["expected a key"]),
    "degree-above-limit": (b"65", 0, "/bodies/0/degree/0", ["65", "limit of 64"]),
    "crlf-lines": (b'"colour"', 0, "/bodies/0/colour", ["unknown key", "colour"]),
    "cr-lines": (b'"colour"', 0, "/bodies/0/colour", ["unknown key", "colour"]),
    "text-after-object": (b"\n{", 1, "", ["after the end of the top-level object"]),
}
# Files that are valid despite looking odd: they must load.
VALID = ["bom-valid"]

SENTINEL = b"solid previous\nthis output must survive a failed run\n\x00\xff"
UNDER_VALGRIND = bool(os.environ.get("COONS_TEST_UNDER_VALGRIND"))
# Peak memory bounds leave room for a sanitizer build (about 55 MiB of
# shadow memory and runtime before the first byte of the model).
SLOW = 20 if UNDER_VALGRIND else 1


def line_col(data, offset):
    """1-based line and column (code points) of a byte offset."""
    if data.startswith(b"\xef\xbb\xbf") and offset >= 3:
        data, offset = data[3:], offset - 3
    head = data[:offset]
    line = 1 + head.count(b"\r\n") + head.replace(b"\r\n", b"").count(b"\n") \
        + head.replace(b"\r\n", b"").count(b"\r")
    last = max(head.rfind(b"\n"), head.rfind(b"\r"))
    tail = head[last + 1:]
    return line, 1 + sum(1 for b in tail if b & 0xC0 != 0x80)


def run_measured(T, args, stdin_path=None, cwd=None):
    """Runs coons2stl; returns (status, stderr, seconds, its peak RSS in MiB).
    posix_spawn (a vfork) so that the child's peak is its own, not a copy
    of this process."""
    err = tempfile.TemporaryFile()
    fin = os.open(stdin_path or os.devnull, os.O_RDONLY)
    null = os.open(os.devnull, os.O_WRONLY)
    actions = [(os.POSIX_SPAWN_DUP2, fin, 0), (os.POSIX_SPAWN_DUP2, null, 1),
               (os.POSIX_SPAWN_DUP2, err.fileno(), 2)]
    here = os.getcwd()
    t0 = time.monotonic()
    try:
        if cwd:
            os.chdir(cwd)
        pid = os.posix_spawn(T.bin, [T.bin] + args, os.environ, file_actions=actions)
    finally:
        os.chdir(here)
    _, status, ru = os.wait4(pid, 0)
    dt = time.monotonic() - t0
    os.close(fin)
    os.close(null)
    err.seek(0)
    text = err.read().decode("utf-8", "replace")
    err.close()
    return os.waitstatus_to_exitcode(status), text, dt, ru.ru_maxrss / 1024.0


class Workdir:
    """A directory holding the model and an earlier out.stl."""

    def __init__(self, root):
        self.dir = tempfile.mkdtemp(dir=root)
        self.out = os.path.join(self.dir, "out.stl")
        with open(self.out, "wb") as f:
            f.write(SENTINEL)

    def untouched(self, model_names):
        with open(self.out, "rb") as f:
            same = f.read() == SENTINEL
        extra = sorted(set(os.listdir(self.dir)) - set(model_names) - {"out.stl"})
        return same and not extra, f"out.stl unchanged: {same}, other files: {extra}"


def check_error(T, label, rc, err, name, data, offset, path, words):
    shown = path if path else "(root)"
    if offset is None:
        T.check(f"{label}: exit 1 with a message", rc == 1 and err.startswith(f"coons2stl: {name}"),
                f"status {rc}: {err!r}")
        return
    line, col = line_col(data, offset)
    head = f"coons2stl: {name}:{line}:{col}: {shown}: "
    T.check(f"{label}: exit 1", rc == 1, f"status {rc}: {err!r}")
    T.check(f"{label}: {head.strip()}", err.startswith(head) and err.count("\n") == 1,
            f"got {err!r}")
    missing = [w for w in words if w not in err]
    T.check(f"{label}: says {words}", not missing, f"missing {missing} in {err!r}")


def main():
    T = Runner(__doc__)
    hostile = os.path.join(T.data, "hostile")
    present = sorted(f[:-5] for f in os.listdir(hostile) if f.endswith(".json"))
    T.check("every file in tests/data/hostile has a case, and back",
            present == sorted(list(CASES) + VALID), f"{present}")
    root = tempfile.mkdtemp(prefix="coons_hostile_")
    try:
        # ---- the corpus -------------------------------------------------------
        for name in sorted(CASES):
            marker, delta, path, words = CASES[name]
            src = os.path.join(hostile, name + ".json")
            with open(src, "rb") as f:
                data = f.read()
            offset = len(data) if marker is EOF else data.find(marker)
            if offset < 0:
                T.check(f"{name}: marker {marker!r} present", False)
                continue
            w = Workdir(root)
            shutil.copy(src, os.path.join(w.dir, name + ".json"))
            rc, _, err = T.run([name + ".json", "-o", "out.stl"], cwd=w.dir)
            check_error(T, name, rc, err, name + ".json", data, offset + delta, path, words)
            ok, why = w.untouched([name + ".json"])
            T.check(f"{name}: earlier output unchanged, nothing created", ok, why)
        for name in VALID:
            rc, out, err = T.run(["--info", os.path.join(hostile, name + ".json")])
            T.check(f"{name}: loads (exit 0)", rc == 0 and '"body_count": 1' in out, err)

        # ---- every example cut short --------------------------------------------
        examples = os.path.join(T.src, "examples")
        for ex in (os.path.basename(p) for p in T.examples()):
            with open(os.path.join(examples, ex), "rb") as f:
                full = f.read()
            cuts = sorted({len(full) * k // 5 for k in range(1, 5)} | {1, len(full) - 2})
            if UNDER_VALGRIND:  # about a second per run there
                cuts = [len(full) // 2, len(full) - 2]
            w = Workdir(root)
            bad = []
            for cut in cuts:
                data = full[:cut]
                if not data.strip():
                    continue
                model = os.path.join(w.dir, "cut.json")
                with open(model, "wb") as f:
                    f.write(data)
                rc, _, err = T.run(["cut.json", "-o", "out.stl"], cwd=w.dir)
                line, col = line_col(data, len(data))
                # The error is at the end, or at the start of a string or a
                # number the cut left open or incomplete.
                lines_ok = err.startswith("coons2stl: cut.json:") and err.count("\n") == 1
                try:
                    pos = err.split(":")[2:4]
                    el, ec = int(pos[0]), int(pos[1])
                    at_end = (el, ec) == (line, col)
                    in_range = (el, ec) <= (line, col)
                except (ValueError, IndexError):
                    at_end = in_range = False
                if not (rc == 1 and lines_ok and in_range and
                        (at_end or "unterminated string" in err or "invalid number" in err)):
                    bad.append((cut, rc, err))
            ok, why = w.untouched(["cut.json"])
            T.check(f"{ex} cut at {len(cuts)} places: exit 1, error at the cut, output kept",
                    not bad and ok, f"{bad[:3]} {why}")

        # ---- absurd sizes: refused in bounded time and memory --------------------
        def big(label, name, writer, status, words, stdin=False, max_s=10.0, max_mib=300.0):
            w = Workdir(root)
            model = os.path.join(w.dir, name)
            writer(model)
            args = ["-", "-o", "out.stl"] if stdin else [name, "-o", "out.stl"]
            rc, err, dt, rss = run_measured(T, args, stdin_path=model if stdin else None,
                                            cwd=w.dir)
            missing = [x for x in words if x not in err]
            T.check(f"{label}: exit {status}, message says {words}",
                    rc == status and not missing and err.count("\n") == 1,
                    f"status {rc}, missing {missing}: {err[:300]!r}")
            T.check(f"{label}: {dt:.2f} s (limit {max_s * SLOW:g} s)", dt < max_s * SLOW)
            if not UNDER_VALGRIND:
                T.check(f"{label}: peak memory {rss:.0f} MiB (limit {max_mib:g} MiB)",
                        rss < max_mib)
            ok, why = w.untouched([name])
            T.check(f"{label}: earlier output unchanged, nothing created", ok, why)
            os.remove(model)

        # Files are written in pieces: the peak memory measured for the
        # child includes this process's own peak (kept across exec).
        def write_parts(*parts):
            def f(path):
                with open(path, "w") as fp:
                    for text, times in parts:
                        for _ in range(times):
                            fp.write(text)
            return f

        big("a million nested arrays", "deep.json",
            write_parts(('{"coons": 1, "bodies": ', 1), ("[", 1000000)), 1,
            ["deep.json:1:", "nested deeper than the limit of 64 levels", "--max-depth"])
        big("a million nested objects", "deepobj.json",
            write_parts(('{"coons": 1, "bodies": ', 1), ('{"a": ', 1000000)), 1,
            ["nested deeper than the limit of 64 levels", "--max-depth"])
        big("9 million values in one array", "values.json",
            write_parts(('{"coons": 1, "bodies": [', 1), ("0," * 1000, 9000), ("0]}", 1)), 1,
            ["more than 8388608 JSON values", "limit", "--max-values"])
        row = "[" + ",".join(["[[0,0,0],[0,0,1]]"] * 500) + "]"
        big("a volume of 1001 x 500 x 2 points", "points.json",
            write_parts(('{"coons": 1, "bodies": [{"type": "bspline-volume", '
                         '"degree": [1, 1, 1], "points": [', 1), (row + ",", 1000),
                        (row + "]}]}", 1)), 1,
            ["/bodies/0/points/0/0", "limit of 1000000 points", "--max-points"], max_mib=400.0)

        def sparse(path):
            with open(path, "wb") as f:
                f.truncate(1100 * 1024 * 1024)
        big("a 1.1 GB file", "huge.json", sparse, 1,
            ["huge.json: the model is 1153433600 bytes", "limit of 268435456 bytes",
             "--max-bytes"],
            max_s=2.0, max_mib=150.0)
        big("a 1.1 GB file on standard input", "huge.json", sparse, 1,
            ["<stdin>:", "more than 268435456 bytes", "--max-bytes"], stdin=True, max_s=20.0, max_mib=1200.0)
    finally:
        shutil.rmtree(root, ignore_errors=True)
    T.finish()


if __name__ == "__main__":
    main()
