"""The output opens in ParaView as it is: the run folder's particles.xmf, and a
snapshot written from Python, read by ParaView's own reader (pvpython, Debian's
python3-paraview, which the README's test command installs) and rendered in its
default view. Every time step must carry one vertex cell per particle (without them
the default Surface view is empty), every field with the range of the HDF5 data, and
the picture must show the particles."""

import json
import re
import shutil
import subprocess

import h5py
import matplotlib.image
import numpy as np
import pytest

import deltasph as ds
from conftest import EXAMPLES, ROOT
from test_simulation import cli_binary

CHECK = ROOT / "tests" / "python" / "paraview_check.py"
FIELDS = ("position", "velocity", "density", "pressure", "kind", "id")


def paraview_view(index, png):
    """What ParaView reads from `index` (see paraview_check.py), rendered to `png`."""
    for tool in ("pvpython", "xvfb-run"):
        assert shutil.which(tool), f"{tool} not found: bash scripts/install-deps.sh installs it"
    done = subprocess.run(
        ["xvfb-run", "-a", "pvpython", str(CHECK), str(index), str(png)],
        capture_output=True, text=True, timeout=300,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    line = [l for l in done.stdout.splitlines() if l.startswith("{")][-1]
    return json.loads(line)


def shows_particles(png):
    """Fraction of the picture that differs from its background colour, and the number
    of distinct colours there (the pressure colour map). A view without cells is the
    bare background: 0 and 0. The coarse cases here, drawn as one-pixel points, cover
    about 1% of the view."""
    image = matplotlib.image.imread(png)[..., :3]
    background = np.median(image.reshape(-1, 3), axis=0)
    drawn = np.abs(image - background).sum(axis=-1) > 0.05
    colours = np.unique((image[drawn] * 255).round().astype(int), axis=0)
    return float(np.mean(drawn)), len(colours)


def check_against_snapshots(seen, snapshots, dim):
    assert len(seen["steps"]) == len(snapshots)
    for step, path in zip(seen["steps"], snapshots):
        with h5py.File(path) as f:
            # compressed as every snapshot is by default: ParaView's reader inflates them
            assert all(d.compression == "gzip" and d.shuffle for d in f.values()), path
            n = f["id"].shape[0]
            assert step["points"] == step["cells"] == n, (path, step["points"], step["cells"])
            for name in FIELDS:
                if name == "position":
                    continue  # the geometry, not a field
                assert name in step["fields"], (path, name, sorted(step["fields"]))
                data = f[name][:]
                if data.ndim == 2:
                    data = np.linalg.norm(data[:, :dim], axis=1)
                lo, hi = step["fields"][name]["range"]
                assert np.isclose(lo, data.min(), rtol=1e-6, atol=1e-9), (name, lo, data.min())
                assert np.isclose(hi, data.max(), rtol=1e-6, atol=1e-9), (name, hi, data.max())


@pytest.mark.parametrize("name, spacing, dim", [("dam_break_2d", 0.05, 2), ("dam_break_3d", 0.08, 3)])
def test_paraview_opens_a_run_folder(tmp_path, name, spacing, dim):
    """A coarse copy of the example, three snapshots, as the CLI writes them."""
    text = (EXAMPLES / f"{name}.toml").read_text()
    text = re.sub(r"^spacing = [0-9.e-]+", f"spacing = {spacing}", text, flags=re.M)
    text = re.sub(r"^output_interval = [0-9.e-]+", "output_interval = 0.03", text, flags=re.M)
    config = tmp_path / "case.toml"
    config.write_text(text)
    out = tmp_path / "run"
    subprocess.run([cli_binary(), "run", config, "--out", out, "--quiet", "--until", "0.06"],
                   check=True, capture_output=True)
    snapshots = sorted(out.glob("particles_*.h5"))
    assert len(snapshots) == 3
    seen = paraview_view(out / "particles.xmf", tmp_path / "view.png")
    assert seen["reader"].startswith("Xdmf3"), seen["reader"]
    assert seen["representation"] == "Surface"
    times = [h5py.File(f).attrs["time"] for f in snapshots]
    assert seen["times"] == pytest.approx(times, rel=1e-8)
    check_against_snapshots(seen, snapshots, dim)
    covered, colours = shows_particles(tmp_path / "view.png")
    assert covered > 0.003 and colours > 20, f"{covered:.2%} of the view drawn, {colours} colours"


def test_paraview_opens_a_python_snapshot(tmp_path, coarse_dam_break):
    sim = ds.Simulation(coarse_dam_break)
    sim.step(5)
    index = sim.write_snapshot(tmp_path / "state.h5")
    seen = paraview_view(index, tmp_path / "view.png")
    check_against_snapshots(seen, [tmp_path / "state.h5"], 2)
    covered, colours = shows_particles(tmp_path / "view.png")
    assert covered > 0.003 and colours > 20, f"{covered:.2%} of the view drawn, {colours} colours"


def test_paraview_opens_a_preview(tmp_path):
    """`sph-cli preview` of the water wedge (a polygon of fluid over a floor): the
    initial particles as ParaView reads them, and the PNG beside them."""
    out = tmp_path / "look"
    subprocess.run([cli_binary(), "preview", EXAMPLES / "validation" / "water_wedge.toml",
                    "--out", out], check=True, capture_output=True)
    assert (out / "preview.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    snapshots = sorted(out.glob("particles_*.h5"))
    assert len(snapshots) == 1
    seen = paraview_view(out / "particles.xmf", tmp_path / "view.png")
    assert seen["reader"].startswith("Xdmf3"), seen["reader"]
    check_against_snapshots(seen, snapshots, 2)
