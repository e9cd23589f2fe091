"""Typing: the stubs of the native module match it (mypy's stubtest: every public
call and attribute present, with the signatures the module has), and ``mypy --strict``
passes on the package and on the Python examples as a user's editor checks them."""

import subprocess
import sys

from conftest import ROOT


def mypy(*args):
    done = subprocess.run([sys.executable, "-m", *args], capture_output=True, text=True,
                          cwd=ROOT, timeout=600)
    return done.returncode, done.stdout + done.stderr


def test_the_stubs_cover_the_native_module():
    code, out = mypy("mypy.stubtest", "deltasph._core")
    assert code == 0, out


def test_mypy_strict_passes_on_the_package_and_the_examples():
    code, out = mypy("mypy", "--strict", "--no-incremental", "crates/sph-py/python/deltasph",
                     "examples/python")
    assert code == 0, out
