#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Installs the build into a temporary prefix and uses it as a client would,
then does the same with the Debian package.

tests/api/consumer.c (includes only <coons.h>, checks values it computes
itself) is built against the installed files
  (a) with `pkg-config --cflags --libs coons` and the shared library,
  (b) with `pkg-config --static` against libcoons.a,
  (c) with a CMake project using find_package(coons) and coons::coons /
      coons::coons_static (and once more with OpenMesh's CMake package
      hidden, so the static target's plain-name dependencies are used),
and each executable is run. Also checks that the shared library exports
only coons_* symbols, its soname, the installed headers, man pages and
CMake version file.

The Debian package (`cpack -G DEB`, cmake/CoonsPackage.cmake) is built into
a scratch directory and checked with dpkg's own tools: its name, version and
architecture (`dpkg-deb -f`), its file list (`dpkg-deb -c`: the libraries,
every public header, coons2stl, every man page, coons.pc, the CMake package,
nothing outside /usr), and its Depends: exactly the Debian packages that own
(`dpkg -S`) the shared libraries its ELF files need (readelf NEEDED,
resolved by ldd), each with a version. Extracted with `dpkg -x` into a
scratch root, the consumer is built against it with pkg-config and with
CMake's find_package and run, and the packaged coons2stl meshes the spool.

Usage: test_install.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
check = T.check


def run(cmd, env=None, cwd=None):
    """Runs cmd; returns (returncode, combined output)."""
    p = subprocess.run(cmd, env=env, cwd=cwd, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True)
    return p.returncode, p.stdout


def cache_value(build, key):
    try:
        with open(os.path.join(build, "CMakeCache.txt")) as f:
            for line in f:
                m = re.match(rf"^{re.escape(key)}:[A-Z]+=(.*)$", line.strip())
                if m:
                    return m.group(1)
    except OSError:
        pass
    return None


def header_version(build):
    with open(os.path.join(build, "include", "coons", "version.h")) as f:
        text = f.read()
    parts = [int(re.search(rf"#define COONS_VERSION_{k} (\d+)", text).group(1))
             for k in ("MAJOR", "MINOR", "PATCH")]
    return parts


def needed(exe):
    rc, out = run(["readelf", "-d", exe])
    return re.findall(r"\(NEEDED\)\s+Shared library: \[([^\]]+)\]", out) if rc == 0 else []


# What the example programs of the manual print, computed by hand: the
# body 2 of libcoons.3 is the unit cube, so F(u,v,w) = (u,v,w) and det J = 1.
EXAMPLE_OUTPUT = {"libcoons.3": "0.25 0.5 1, det J = 1"}


def man_programs(src):
    """(page, C text) of each literal display that is a whole program."""
    out = []
    for page in sorted(glob.glob(os.path.join(src, "man", "man3", "*.3"))):
        with open(page) as f:
            text = f.read()
        for block in re.findall(r"^\.Bd -literal[^\n]*\n(.*?)^\.Ed", text, re.M | re.S):
            if block.startswith("#include <coons.h>") and "main(" in block:
                out.append((page, block.replace("\\e", "\\").replace("\\-", "-")))
    return out


def main():
    src, build = os.path.abspath(T.src), os.path.abspath(T.build)
    consumer = os.path.join(src, "tests", "api", "consumer.c")
    cc = os.environ.get("CC", "cc")
    cflags = ["-std=c11", "-Wall", "-Wextra", "-Wpedantic", "-Werror"]
    major, minor, patch = header_version(build)

    tmp = tempfile.mkdtemp(prefix="coons-install-")
    try:
        prefix = os.path.join(tmp, "prefix")
        rc, out = run(["cmake", "--install", build, "--prefix", prefix])
        if not check("cmake --install", rc == 0, out):
            return
        libs = glob.glob(os.path.join(prefix, "lib*", "**", "libcoons.so"), recursive=True)
        if not check("libcoons.so installed", len(libs) == 1, str(libs)):
            return
        libdir = os.path.dirname(libs[0])
        check("libcoons.a installed", os.path.isfile(os.path.join(libdir, "libcoons.a")))

        # Headers: the umbrella, every public header and the generated ones.
        inc = os.path.join(prefix, "include")
        want = ["coons.h"] + [os.path.join("coons", os.path.basename(h)) for h in
                              glob.glob(os.path.join(src, "include", "coons", "*.h"))]
        want += [os.path.join("coons", "version.h"), os.path.join("coons", "export.h")]
        missing = [h for h in want if not os.path.isfile(os.path.join(inc, h))]
        check("public headers installed", not missing, f"missing: {missing}")

        # Man pages: every page of man/manN lands in share/man/manN.
        pages = glob.glob(os.path.join(src, "man", "man[0-9]", "*.[0-9]"))
        mandir = cache_value(build, "CMAKE_INSTALL_MANDIR") or "share/man"
        missing = [p for p in pages if not os.path.isfile(os.path.join(
            prefix, mandir, os.path.basename(os.path.dirname(p)), os.path.basename(p)))]
        check(f"{len(pages)} man pages installed", not missing, f"missing: {missing}")

        # Soname: the major version (STYLE item 13); before 1.0 every minor
        # version may change the ABI, so it is major.minor there.
        soname = f"libcoons.so.{major}" if major else f"libcoons.so.0.{minor}"
        rc, out = run(["readelf", "-d", libs[0]])
        check(f"soname is {soname}", f"[{soname}]" in out, out)

        # Only coons_* is exported (STYLE item 14), from the build and the install.
        for lib in (os.path.join(build, "src", "libcoons.so"), libs[0]):
            rc, out = run(["nm", "-D", "--defined-only", lib])
            syms = [ln.split()[-1] for ln in out.splitlines() if ln.strip()]
            bad = [s for s in syms if not s.startswith("coons_")]
            check(f"{os.path.relpath(lib, tmp if lib.startswith(tmp) else build)} exports "
                  f"only coons_* ({len(syms)} symbols)",
                  rc == 0 and syms and not bad, f"rc={rc} foreign: {bad[:20]}")

        pcdirs = sorted({os.path.dirname(p) for p in glob.glob(
            os.path.join(prefix, "**", "coons.pc"), recursive=True)})
        if not check("coons.pc installed", len(pcdirs) == 1, str(pcdirs)):
            return
        env = dict(os.environ, PKG_CONFIG_PATH=pcdirs[0])
        rc, ver = run(["pkg-config", "--modversion", "coons"], env=env)
        check("pkg-config --modversion", ver.strip() == f"{major}.{minor}.{patch}", ver)

        # (a) shared, through pkg-config.
        rc, flags = run(["pkg-config", "--cflags", "--libs", "coons"], env=env)
        exe = os.path.join(tmp, "consumer_shared")
        rc, out = run([cc] + cflags + [consumer, "-o", exe] + flags.split())
        if check("(a) build with pkg-config --cflags --libs", rc == 0, flags + out):
            check("(a) executable needs libcoons.so", soname in needed(exe))
            renv = dict(os.environ, LD_LIBRARY_PATH=libdir)
            rc, out = run([exe], env=renv)
            check("(a) run", rc == 0, out)

        # The complete programs of the section 3 pages build and run as shown.
        rc, out = run(["nm", "-D", "--defined-only", libs[0]])
        exported = {ln.split()[-1] for ln in out.splitlines() if ln.strip()}
        renv = dict(os.environ, LD_LIBRARY_PATH=libdir)
        for page, prog in man_programs(src):
            used = set(re.findall(r"\b(coons_[a-z0-9_]+)\s*\(", prog))
            lacking = sorted(used - exported)
            name = f"{os.path.basename(page)} example program"
            if lacking:
                print(f"skip {name}: the library lacks {', '.join(lacking)}")
                continue
            csrc = os.path.join(tmp, "example.c")
            with open(csrc, "w") as f:
                f.write(prog)
            exe = os.path.join(tmp, "example")
            rc, out = run([cc] + cflags + [csrc, "-o", exe] + flags.split())
            if check(f"{name} builds", rc == 0, out):
                rc, out = run([exe], env=renv)
                want = EXAMPLE_OUTPUT.get(os.path.basename(page))
                check(f"{name} runs" + (f" and prints {want!r}" if want else ""),
                      rc == 0 and (want is None or out.strip() == want), out)

        # (b) static, through pkg-config --static: -lcoons would pick the .so,
        # so ask the linker for the archive by name.
        rc, flags = run(["pkg-config", "--static", "--cflags", "--libs", "coons"], env=env)
        sflags = ["-l:libcoons.a" if f == "-lcoons" else f for f in flags.split()]
        exe = os.path.join(tmp, "consumer_static")
        rc, out = run([cc] + cflags + [consumer, "-o", exe] + sflags)
        if check("(b) build with pkg-config --static", rc == 0, flags + out):
            check("(b) executable does not need libcoons.so",
                  not any(n.startswith("libcoons") for n in needed(exe)), str(needed(exe)))
            rc, out = run([exe])
            check("(b) run", rc == 0, out)

        # (c) CMake: find_package(coons) -> coons::coons, coons::coons_static.
        proj = os.path.join(tmp, "cmake-consumer")
        os.makedirs(proj)
        with open(os.path.join(proj, "CMakeLists.txt"), "w") as f:
            f.write(f"""cmake_minimum_required(VERSION 3.18)
project(consumer C)
# SameMajorVersion (before 1.0 SameMinorVersion): the next major, and
# before 1.0 an earlier minor, must not be accepted.
find_package(coons {major + 1} CONFIG QUIET)
if(coons_FOUND)
  message(FATAL_ERROR "find_package(coons {major + 1}) accepted version ${{coons_VERSION}}")
endif()
if({major} EQUAL 0 AND {minor} GREATER 0)
  find_package(coons 0.{max(minor - 1, 0)} CONFIG QUIET)
  if(coons_FOUND)
    message(FATAL_ERROR "find_package(coons 0.{max(minor - 1, 0)}) accepted version ${{coons_VERSION}}")
  endif()
endif()
find_package(coons {major}.{minor} CONFIG REQUIRED)
if(NOT coons_VERSION STREQUAL "{major}.{minor}.{patch}")
  message(FATAL_ERROR "coons_VERSION is ${{coons_VERSION}}")
endif()
add_executable(consumer_shared {consumer})
target_link_libraries(consumer_shared PRIVATE coons::coons)
add_executable(consumer_static {consumer})
target_link_libraries(consumer_static PRIVATE coons::coons_static)
""")
        gen = ["-G", "Ninja"] if shutil.which("ninja") else []
        for variant, extra in (("", []),
                               (" without OpenMesh's package",
                                ["-DCMAKE_DISABLE_FIND_PACKAGE_OpenMesh=ON"])):
            bdir = os.path.join(tmp, "cmake-build" + ("-noom" if extra else ""))
            rc, out = run(["cmake", "-S", proj, "-B", bdir, "-DCMAKE_PREFIX_PATH=" + prefix,
                           "-DCMAKE_C_FLAGS=" + " ".join(cflags)] + gen + extra)
            if not check(f"(c) configure with find_package(coons){variant}", rc == 0, out):
                continue
            targets = ["consumer_shared", "consumer_static"]
            rc, out = run(["cmake", "--build", bdir, "--target"] + targets)
            if not check(f"(c) build {' '.join(targets)}{variant}", rc == 0, out):
                continue
            for t in targets:
                exe = os.path.join(bdir, t)
                is_static = t.endswith("static")
                check(f"(c) {t} links libcoons {'statically' if is_static else 'shared'}{variant}",
                      any(n.startswith("libcoons") for n in needed(exe)) != is_static,
                      str(needed(exe)))
                rc, out = run([exe])  # the shared one finds the library via its RPATH
                check(f"(c) run {t}{variant}", rc == 0, out)
        deb_checks(src, build, tmp, cc, cflags, consumer, soname, gen)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def owner(path):
    """The Debian package that owns a file (also through the /usr merge)."""
    for p in (path, os.path.realpath(path), re.sub(r"^/usr/lib/", "/lib/", path),
              re.sub(r"^/lib/", "/usr/lib/", path)):
        rc, out = run(["dpkg", "-S", p])
        if rc == 0:
            return out.split(":")[0].strip()
    return None


def deb_checks(src, build, tmp, cc, cflags, consumer, soname, gen):
    """Builds the .deb, checks its fields and files, and uses it extracted."""
    for tool in ("cpack", "dpkg-deb", "dpkg-shlibdeps"):
        check(f"{tool} is installed", shutil.which(tool) is not None)
    out_dir = os.path.join(tmp, "deb")
    rc, out = run(["cpack", "-G", "DEB", "--config", os.path.join(build, "CPackConfig.cmake"),
                   "-B", out_dir])
    debs = glob.glob(os.path.join(out_dir, "*.deb"))
    if not check("cpack -G DEB makes one .deb", rc == 0 and len(debs) == 1, out):
        return
    deb = debs[0]
    major, minor, patch = header_version(build)
    version = f"{major}.{minor}.{patch}"
    rc, arch = run(["dpkg", "--print-architecture"])
    arch = arch.strip()
    check(f"named libcoons_{version}_{arch}.deb",
          os.path.basename(deb) == f"libcoons_{version}_{arch}.deb", deb)
    fields = {}
    for key in ("Package", "Version", "Architecture", "Depends", "Suggests", "Maintainer",
                "Description"):
        rc, val = run(["dpkg-deb", "-f", deb, key])
        fields[key] = val.strip() if rc == 0 else ""
    check("Package libcoons, Version, Architecture",
          fields["Package"] == "libcoons" and fields["Version"] == version and
          fields["Architecture"] == arch, str(fields))
    check("Maintainer and Description are set",
          fields["Maintainer"] and len(fields["Description"].splitlines()) > 1, str(fields))

    # The file list.
    rc, listing = run(["dpkg-deb", "-c", deb])
    files = set()
    for line in listing.splitlines():
        name = line.split()[5] if len(line.split()) > 5 else ""
        files.add(re.sub(r"^\./", "/", name).rstrip("/"))
    want = {"/usr/bin/coons2stl", "/usr/lib/libcoons.a", "/usr/lib/libcoons.so",
            f"/usr/lib/{soname}", f"/usr/lib/libcoons.so.{version}",
            "/usr/lib/pkgconfig/coons.pc", "/usr/lib/cmake/coons/coonsConfig.cmake",
            "/usr/lib/cmake/coons/coonsConfigVersion.cmake",
            "/usr/lib/cmake/coons/coons-targets.cmake", "/usr/include/coons.h",
            "/usr/include/coons/version.h", "/usr/include/coons/export.h",
            "/usr/share/doc/libcoons/copyright"}
    want |= {"/usr/include/coons/" + os.path.basename(h)
             for h in glob.glob(os.path.join(src, "include", "coons", "*.h"))}
    want |= {f"/usr/share/man/{os.path.basename(os.path.dirname(p))}/{os.path.basename(p)}"
             for p in glob.glob(os.path.join(src, "man", "man[0-9]", "*.[0-9]"))}
    missing = sorted(want - files)
    check(f"the package holds the {len(want)} expected files", not missing, f"missing {missing}")
    outside = sorted(f for f in files if f and f != "/" and not f.startswith("/usr"))
    check("nothing outside /usr", not outside, str(outside))

    # Extract, then Depends against the owners of what the ELF files need.
    root = os.path.join(tmp, "root")
    rc, out = run(["dpkg", "-x", deb, root])
    if not check("dpkg -x into a scratch root", rc == 0, out):
        return
    libdir = os.path.join(root, "usr", "lib")
    renv = dict(os.environ, LD_LIBRARY_PATH=libdir)
    owners, unresolved = set(), []
    for elf in (os.path.join(libdir, f"libcoons.so.{version}"),
                os.path.join(root, "usr", "bin", "coons2stl")):
        rc, ldd = run(["ldd", elf], env=renv)
        paths = dict(re.findall(r"^\s*(\S+) => (\S+)", ldd, re.M))
        for path in re.findall(r"^\s*(/\S+) \(0x", ldd, re.M):  # the dynamic loader
            paths.setdefault(os.path.basename(path), path)
        for lib in needed(elf):
            if lib.startswith("libcoons"):
                continue
            pkg = owner(paths.get(lib, "")) if paths.get(lib) else None
            if pkg:
                owners.add(pkg.split(":")[0])
            else:
                unresolved.append(lib)
    check("every needed library has an owning package", not unresolved, str(unresolved))
    deps = [d.strip() for d in fields["Depends"].split(",") if d.strip()]
    names = {re.match(r"[a-z0-9.+-]+", d).group(0) for d in deps}
    check(f"Depends names exactly the owners of the needed libraries ({len(owners)})",
          names == owners, f"Depends: {sorted(names)}; owners: {sorted(owners)}")
    check("every dependency has a minimum version",
          deps and all(re.search(r"\(>= [^)]+\)$", d) for d in deps), fields["Depends"])
    with_3mf = (cache_value(build, "COONS_WITH_LIB3MF") or "OFF").upper() in ("ON", "1", "TRUE")
    check(f"lib3mf1 is a dependency exactly when 3MF is built in ({with_3mf})",
          ("lib3mf1" in names) == with_3mf, fields["Depends"])

    # The consumer against the extracted tree: pkg-config (the .pc file is
    # relocatable: its prefix follows where it lies), then CMake.
    env = dict(os.environ, PKG_CONFIG_PATH=os.path.join(libdir, "pkgconfig"),
               PKG_CONFIG_LIBDIR=os.path.join(libdir, "pkgconfig"))
    rc, flags = run(["pkg-config", "--cflags", "--libs", "coons"], env=env)
    dirs = {f[:2]: os.path.normpath(f[2:]) for f in flags.split() if f[:2] in ("-I", "-L")}
    check("deb: pkg-config points into the extracted tree",
          rc == 0 and dirs.get("-I") == os.path.join(root, "usr", "include") and
          dirs.get("-L") == libdir, flags)
    exe = os.path.join(tmp, "deb_consumer")
    rc, out = run([cc] + cflags + [consumer, "-o", exe] + flags.split())
    if check("deb: consumer builds with pkg-config", rc == 0, flags + out):
        rc, ldd = run(["ldd", exe], env=renv)
        check("deb: it loads the packaged libcoons", f"{soname} => {libdir}/{soname}" in ldd, ldd)
        rc, out = run([exe], env=renv)
        check("deb: consumer runs", rc == 0, out)
    proj = os.path.join(tmp, "deb-cmake")
    os.makedirs(proj)
    with open(os.path.join(proj, "CMakeLists.txt"), "w") as f:
        f.write(f"""cmake_minimum_required(VERSION 3.18)
project(consumer C)
find_package(coons {major}.{minor} CONFIG REQUIRED)
if(NOT coons_DIR STREQUAL "{libdir}/cmake/coons")
  message(FATAL_ERROR "found coons in ${{coons_DIR}}")
endif()
add_executable(consumer_shared {consumer})
target_link_libraries(consumer_shared PRIVATE coons::coons)
""")
    bdir = os.path.join(tmp, "deb-cmake-build")
    rc, out = run(["cmake", "-S", proj, "-B", bdir, "-DCMAKE_PREFIX_PATH=" + os.path.join(
        root, "usr"), "-DCMAKE_C_FLAGS=" + " ".join(cflags)] + gen)
    if check("deb: find_package(coons) finds the extracted package", rc == 0, out):
        rc, out = run(["cmake", "--build", bdir])
        if check("deb: consumer builds with coons::coons", rc == 0, out):
            rc, out = run([os.path.join(bdir, "consumer_shared")], env=renv)
            check("deb: CMake consumer runs", rc == 0, out)
    stl = os.path.join(tmp, "spool.stl")
    rc, out = run([os.path.join(root, "usr", "bin", "coons2stl"),
                   os.path.join(src, "examples", "spool.json"), "-o", stl], env=renv)
    size = os.path.getsize(stl) if os.path.exists(stl) else 0
    check("deb: the packaged coons2stl meshes the spool",
          rc == 0 and size > 84 and (size - 84) % 50 == 0, out)


if __name__ == "__main__":
    main()
    T.finish()
