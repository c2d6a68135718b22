# SPDX-License-Identifier: GPL-3.0-or-later
"""Shared fixtures of the Python package's tests: the examples and the
coons2stl built with the package (coons/bin/coons2stl: the same build of
the library, so its outputs are the reference), or $COONS2STL."""
import glob
import os
import subprocess

import pytest

import coons

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.environ.get("COONS_EXAMPLES") or os.path.join(HERE, "..", "..", "examples")
EXAMPLE_FILES = sorted(glob.glob(os.path.join(EXAMPLES, "*.json")))
CLI = os.environ.get("COONS2STL") or os.path.join(os.path.dirname(coons.__file__), "bin",
                                                  "coons2stl")

assert EXAMPLE_FILES, "no examples found in " + EXAMPLES


def example(name):
    return os.path.join(EXAMPLES, name)


def run_cli(*args, stdin=None, check=True):
    p = subprocess.run([CLI, "-q"] + [str(a) for a in args], input=stdin, capture_output=True,
                       text=True)
    if check and p.returncode != 0:
        raise AssertionError("coons2stl %s failed (%d): %s" % (args, p.returncode, p.stderr))
    return p


def ids(files):
    return [os.path.basename(f) for f in files]


@pytest.fixture(params=EXAMPLE_FILES, ids=ids(EXAMPLE_FILES))
def example_file(request):
    return request.param
