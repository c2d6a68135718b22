#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Lints the hand-written mdoc manual pages and checks they cover the code.

- every man/manN/*.N passes `mandoc -Tlint -W warning` and
  `groff -mandoc -ww -z` without a single message (each linter is used when
  installed; at least one must be);
- its .Dt names the file and section;
- every function declared COONS_EXPORT in include/coons/*.h is documented
  (.Fn or .Fo) in a section 3 page, and has its prototype in the SYNOPSIS of
  exactly one of them (libcoons.3, the overview, or its family's page such
  as coons_curve.3); libcoons.3 names every other man3 page in SEE ALSO;
- every curve, patch and body `type` of the model format contract
  (the spec, when it is present, else the names in coons-model.5's own
  tables) is described in coons-model.5 with a full example;
- with --bin, every long option that `coons2stl --help` prints is in
  coons2stl.1; the options of --help (its table: short and long name,
  value or none) are exactly those of coons2stl.1's option list; and every
  option the page documents is accepted by the program as documented (with
  a value: "needs a value" without one; without: "takes no value" with one).

Usage: test_man.py --bin <coons2stl or ""> --src <source dir> --build <build dir>
"""
import glob
import json
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
check = T.check


def run(cmd):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    return p.returncode, p.stdout, p.stderr


def exported_functions(src):
    names = set()
    for h in glob.glob(os.path.join(src, "include", "coons", "*.h")) + \
            [os.path.join(src, "include", "coons.h")]:
        with open(h) as f:
            text = f.read()
        # COONS_EXPORT <return type> <name>(   -- the name is the last word before "(".
        for m in re.finditer(r"COONS_EXPORT\b([^;{(]*?)\b(coons_\w+)\s*\(", text):
            names.add(m.group(2))
    return names


def synopsis_functions(page):
    """The functions whose prototype (.Fo NAME or .Fn NAME "type arg") is in
    the page's SYNOPSIS, each as often as it is there."""
    names = []
    with open(page) as f:
        text = f.read()
    m = re.search(r"^\.Sh SYNOPSIS\n(.*?)^\.Sh ", text, re.M | re.S)
    for line in (m.group(1) if m else "").splitlines():
        m2 = re.match(r"^\.(?:Fo|Fn)\s+(coons_\w+)", line)
        if m2:
            names.append(m2.group(1))
    return names


def documented_functions(pages):
    names = set()
    for p in pages:
        with open(p) as f:
            for line in f:
                m = re.match(r"^\.(?:Fn|Fo)\s+(\w+)", line)
                if m:
                    names.add(m.group(1))
    return names


BODY_TYPES = ("body0", "body1", "body2", "bezier-volume", "bspline-volume", "shell", "morph")

# Types listed in the spec (or the page) tables: rows start with | `type` |.
TYPE_ROW = re.compile(r"^\|\s*`([a-z0-9-]+)`\s*\|")


def spec_types(spec):
    types, section = {}, None
    with open(spec) as f:
        for line in f:
            m = re.match(r"^## (Curves|Patches|Bodies)", line)
            if m:
                section = m.group(1)
                continue
            if line.startswith("## "):
                section = None
            m = TYPE_ROW.match(line)
            if section and m and m.group(1) != "type":
                types.setdefault(section, []).append(m.group(1))
    return types


def model_examples(page):
    """The JSON texts in the page's literal displays: (text, parsed or None).

    A display may hold several JSON values separated by blank lines; \\- is
    the roff escape of a minus sign. The schema sketch with "..." is skipped.
    """
    with open(page) as f:
        text = f.read()
    out = []
    for block in re.findall(r"^\.Bd -literal[^\n]*\n(.*?)^\.Ed", text, re.M | re.S):
        block = block.replace("\\-", "-")
        if not block.lstrip().startswith("{") or "..." in block:
            continue
        for part in re.split(r"\n\s*\n", block):
            try:
                out.append((part, json.loads(part)))
            except ValueError:
                out.append((part, None))
    return out


def main():
    args = T
    src = os.path.abspath(T.src)

    pages = sorted(glob.glob(os.path.join(src, "man", "man[0-9]", "*.[0-9]")))
    check("man pages found", len(pages) >= 3, str(pages))
    for want in ("man1/coons2stl.1", "man3/libcoons.3", "man5/coons-model.5"):
        check(f"{want} exists", os.path.isfile(os.path.join(src, "man", want)))

    mandoc, groff = shutil.which("mandoc"), shutil.which("groff")
    check("mandoc or groff installed", mandoc or groff)
    for p in pages:
        rel = os.path.relpath(p, src)
        if mandoc:
            rc, out, err = run([mandoc, "-Tlint", "-W", "warning", p])
            check(f"mandoc -Tlint -W warning {rel}", rc == 0 and not out and not err,
                  f"rc={rc}\n{out}{err}")
        if groff:
            rc, out, err = run([groff, "-mandoc", "-ww", "-z", p])
            check(f"groff -mandoc -ww -z {rel}", rc == 0 and not out and not err,
                  f"rc={rc}\n{out}{err}")
        name, section = os.path.splitext(os.path.basename(p))
        with open(p) as f:
            text = f.read()
        m = re.search(r"^\.Dt\s+(\S+)\s+(\d)", text, re.M)
        check(f"{rel}: .Dt matches its file name",
              m and m.group(1).lower() == name.lower() and "." + m.group(2) == section,
              m.group(0) if m else "no .Dt")

    # Every exported function is documented in section 3.
    man3 = [p for p in pages if p.endswith(".3")]
    missing = sorted(exported_functions(src) - documented_functions(man3))
    check(f"every COONS_EXPORT function has .Fn/.Fo in man3 "
          f"({len(exported_functions(src))} functions)", not missing,
          "undocumented: " + ", ".join(missing) +
          "\n  -> add each to its family's page man/man3/coons_<family>.3: its prototype"
          "\n     (.Ft/.Fo/.Fa/.Fc) in SYNOPSIS and a .It Fn entry under DESCRIPTION")
    # ... in exactly one page's SYNOPSIS.
    where = {}
    for p in man3:
        for n in synopsis_functions(p):
            where.setdefault(n, []).append(os.path.basename(p))
    exported = exported_functions(src)
    nowhere = sorted(n for n in exported if n not in where)
    twice = sorted(f"{n} ({', '.join(w)})" for n, w in where.items() if len(w) > 1)
    check("every COONS_EXPORT function has its prototype in one man3 SYNOPSIS",
          not nowhere, "in no SYNOPSIS: " + ", ".join(nowhere))
    check("no function's prototype is in two man3 SYNOPSIS entries", not twice,
          "twice: " + "; ".join(twice))
    overview = os.path.join(src, "man", "man3", "libcoons.3")
    if os.path.isfile(overview):
        with open(overview) as f:
            see = f.read().split(".Sh SEE ALSO", 1)[-1]
        listed = set(re.findall(r"^\.Xr (\S+) 3", see, re.M))
        others = {os.path.basename(p)[:-2] for p in man3} - {"libcoons"}
        check("libcoons.3 lists every other man3 page in SEE ALSO", others <= listed,
              "missing: " + ", ".join(sorted(others - listed)))
    stale = sorted(f for f in documented_functions(man3) - exported_functions(src)
                   if f.startswith("coons_") and "_X_" not in f)
    check("man3 documents no function the headers lack", not stale,
          "not in include/: " + ", ".join(stale))

    # Every model type is in coons-model.5, with an example ("type": "<name>").
    model5 = os.path.join(src, "man", "man5", "coons-model.5")
    # The contract lives beside the repository (../shared, or ../../shared
    # from a worktree); a fresh clone has none and uses the page's own list.
    spec = next((c for c in (os.path.join(src, up, "shared", "spec", "model-format.md")
                             for up in ("..", os.path.join("..", "..")))
                 if os.path.isfile(c)), "")
    if os.path.isfile(model5):
        with open(model5) as f:
            page = f.read()
        if os.path.isfile(spec):
            types = spec_types(spec)
        else:
            # Without the spec, the page's own type list: .It Cm <name> items.
            types = {"types": re.findall(r'^\.It Cm (\S+)', page, re.M)}
        check("model types found", sum(len(v) for v in types.values()) >= 18, str(types))
        for section, names in types.items():
            for t in names:
                check(f"coons-model.5 describes {section} type {t} with an example",
                      re.search(rf"^\.It Cm {re.escape(t)}\b", page, re.M) and
                      f'"type": "{t}"' in page)

    # The JSON examples of coons-model.5 are JSON; complete models load.
    if os.path.isfile(model5):
        models = model_examples(model5)
        check("coons-model.5 has JSON examples", len(models) >= 20, str(len(models)))
        complete = [m for m in models if m[1] is not None and "coons" in m[1]]
        check("coons-model.5 has complete model examples", len(complete) >= 2)
        for text, obj in models:
            check(f"coons-model.5 example is valid JSON: {text[:50]!r}...", obj is not None)
        if args.bin and os.path.isfile(args.bin):
            # Each body example, as the one body of a model, loads too.
            bodies = [json.dumps({"coons": 1, "bodies": [obj]}) for _, obj in models
                      if isinstance(obj, dict) and obj.get("type") in BODY_TYPES]
            covered = {obj.get("type") for _, obj in models if isinstance(obj, dict)}
            covered |= {b.get("type") for _, obj in complete for b in obj.get("bodies", [])
                        if isinstance(b, dict)}
            check("coons-model.5 has an example of every body type",
                  set(BODY_TYPES) <= covered, f"missing {set(BODY_TYPES) - covered}")
            for text in [t for t, _ in complete] + bodies:
                p = subprocess.run([args.bin, "--info", "-"], input=text, text=True,
                                   stdout=subprocess.PIPE, stderr=subprocess.PIPE)
                check(f"coons2stl --info loads coons-model.5 example {text[:40]!r}...",
                      p.returncode == 0, p.stderr)

    # With the program: its long options are documented.
    if args.bin and os.path.isfile(args.bin):
        rc, out, err = run([args.bin, "--help"])
        opts = sorted(set(re.findall(r"(?<![\w-])--([a-z][a-z-]*)", out)))
        check("coons2stl --help lists long options", rc == 0 and opts, out + err)
        with open(os.path.join(src, "man", "man1", "coons2stl.1")) as f:
            page1 = f.read()
        undocumented = [o for o in opts if not re.search(
            rf"^\.(?:It )?Fl (?:[a-zA-Z] , )?(?:Fl )?-{re.escape(o)}\b", page1, re.M)
            and f"Fl -{o}" not in page1]
        check(f"coons2stl.1 documents every --help option ({len(opts)})",
              not undocumented, "undocumented: " + ", ".join(undocumented))
        check_option_table(args.bin, out, page1)


# --help rows: "  -o, --output FILE      text" or "      --eval             text".
HELP_ROW = re.compile(r"^  (?:-([A-Za-z]), |    )--([a-z][a-z-]*)(?: (\S+))?(?:  |$)")
# coons2stl.1 items: ".It Fl o Ar file , Fl -output Ar file", ".It Fl -eval".
MAN_ITEM = re.compile(r"^\.It Fl (?:([A-Za-z])(?: Ar \S+)? , Fl )?-([a-z][a-z-]*)( Ar)?")


def help_table(text):
    """{long: (short or None, takes a value)} of the --help option rows."""
    rows = {}
    for line in text.splitlines():
        m = HELP_ROW.match(line)
        if m:
            rows[m.group(2)] = (m.group(1), m.group(3) is not None)
    return rows


def man_table(page):
    """The same for the option list of coons2stl.1 (its DESCRIPTION)."""
    desc = re.search(r"^\.Sh DESCRIPTION\n(.*?)^\.Sh ", page, re.M | re.S)
    rows = {}
    for line in (desc.group(1) if desc else "").splitlines():
        m = MAN_ITEM.match(line)
        if m:
            rows[m.group(2)] = (m.group(1), m.group(3) is not None)
    return rows


def check_option_table(binary, help_text, page):
    helps, mans = help_table(help_text), man_table(page)
    check(f"--help has an option table ({len(helps)} rows)", len(helps) >= 15, help_text)
    check(f"coons2stl.1 has an option list ({len(mans)} items)", len(mans) >= 15)
    check("--help and coons2stl.1 list the same options",
          sorted(helps) == sorted(mans),
          f"only in --help: {sorted(set(helps) - set(mans))}\n"
          f"only in coons2stl.1: {sorted(set(mans) - set(helps))}")
    for name in sorted(set(helps) & set(mans)):
        check(f"--{name}: same short name and value in --help and coons2stl.1",
              helps[name] == mans[name], f"--help {helps[name]}, page {mans[name]}")
    # Accepted as documented: before the model file is missing, an option
    # is unknown, lacks a value or has one it does not take.
    for name, (short, value) in sorted(mans.items()):
        spellings = [f"--{name}"] + ([f"-{short}"] if short else [])
        for opt in spellings:
            rc, out, err = run([binary, opt])
            if name in ("help", "version"):
                ok = rc == 0 and out and not err
            elif value:
                ok = rc == 2 and f"option '{opt}' needs a value" in err
            else:
                ok = rc == 2 and "no model file given" in err
            check(f"coons2stl accepts {opt} as coons2stl.1 documents it", ok, f"{rc} {err!r}")
        rc, out, err = run([binary, f"--{name}=1"])
        if value:
            ok = rc == 2 and "no model file given" in err
        else:
            ok = rc == 2 and f"option '--{name}=1' takes no value" in err
        check(f"coons2stl --{name}=1: {'a value' if value else 'no value'}, as documented",
              ok, f"{rc} {err!r}")


if __name__ == "__main__":
    main()
    T.finish()
