"""The wheel that scripts/install-python.sh builds: one abi3 wheel, HDF5 linked in (no
libhdf5 among the extension's libraries), and in a fresh virtual environment holding
only it and numpy it runs a case, reads the snapshot back and answers as `deltasph`."""

import os
import pathlib
import re
import subprocess
import venv
import zipfile

import pytest

from conftest import EXAMPLES, ROOT

WHEELS = ROOT / "target" / "wheels"


@pytest.fixture(scope="module")
def wheel():
    """The wheel of scripts/install-python.sh, or the one DELTASPH_WHEEL names (the
    manylinux2014 wheel of scripts/build-wheel-manylinux.sh)."""
    if os.environ.get("DELTASPH_WHEEL"):
        return pathlib.Path(os.environ["DELTASPH_WHEEL"]).resolve()
    found = sorted(WHEELS.glob("deltasph-*.whl"))
    assert len(found) == 1, f"expected the one wheel of scripts/install-python.sh in {WHEELS}"
    return found[0]


def test_one_abi3_wheel_for_python_3_9_on(wheel):
    assert "-cp39-abi3-" in wheel.name, wheel.name
    with zipfile.ZipFile(wheel) as z:
        names = z.namelist()
        meta = z.read(next(n for n in names if n.endswith(".dist-info/METADATA"))).decode()
        entry = z.read(next(n for n in names if n.endswith("entry_points.txt"))).decode()
    assert "Requires-Python: >=3.9" in meta
    assert re.search(r"Requires-Dist: tomli.*python_(full_)?version *< *['\"]3\.11", meta), meta
    assert re.search(r"^deltasph *= *deltasph\._cli:run$", entry, re.M), entry
    # `pip install "deltasph[plot]"` brings what `deltasph plot` draws with
    assert "Provides-Extra: plot" in meta, meta
    assert re.search(r"Requires-Dist: matplotlib.*extra *== *['\"]plot['\"]", meta), meta
    assert any(n.startswith("deltasph/_core") and n.endswith(".so") for n in names)


@pytest.fixture(scope="module")
def fresh_env(wheel, tmp_path_factory):
    root = tmp_path_factory.mktemp("venv")
    venv.create(root, with_pip=True)
    python = root / "bin" / "python"
    subprocess.run([python, "-m", "pip", "install", "-q", "--disable-pip-version-check",
                    str(wheel), "numpy"], check=True)
    return root


def test_the_extension_links_no_libhdf5(fresh_env):
    ext = next((fresh_env / "lib").glob("python3*/site-packages/deltasph/_core*.so"))
    libraries = subprocess.run(["ldd", ext], capture_output=True, text=True, check=True).stdout
    assert "libhdf5" not in libraries, libraries
    # zlib (the snapshots' deflate) is linked in too: libz is not among the libraries a
    # manylinux wheel may expect on the system
    assert "libz" not in libraries, libraries
    assert "not found" not in libraries, libraries


def test_a_case_runs_and_reads_back_in_a_fresh_env(fresh_env, tmp_path):
    script = f"""
import numpy as np, deltasph as ds
sim = ds.Simulation.from_toml(r"{EXAMPLES / 'hydrostatic_2d.toml'}")
sim.run(until=0.01, out=r"{tmp_path / 'run'}")
run = ds.load(r"{tmp_path / 'run'}")
assert np.array_equal(run[-1]["position"], sim.positions)
print(len(run), run[-1].time)
"""
    done = subprocess.run([fresh_env / "bin" / "python", "-c", script], capture_output=True,
                          text=True, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    count, time = done.stdout.split()
    assert int(count) >= 2 and float(time) == pytest.approx(0.01)
    check = subprocess.run([fresh_env / "bin" / "deltasph", "check",
                            EXAMPLES / "dam_break_2d.toml"], capture_output=True, text=True)
    assert check.returncode == 0, check.stderr
    assert "valid 2D case 'dam_break_2d'" in check.stdout
    # without the plot extra, `deltasph plot` names it in one line
    plot = subprocess.run([fresh_env / "bin" / "deltasph", "plot", tmp_path / "run"],
                          capture_output=True, text=True)
    assert plot.returncode == 2 and 'pip install "deltasph[plot]"' in plot.stderr, plot.stderr
    assert plot.stderr.count("\n") == 1, plot.stderr
