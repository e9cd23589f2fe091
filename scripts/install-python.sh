#!/usr/bin/env bash
# Builds the Python wheel of deltasph (crates/sph-py, by maturin: one abi3 wheel for
# CPython 3.9+, HDF5 linked in) into target/wheels and installs it into the current
# Python, with what the tests and examples use (numpy, scipy, h5py, pytest, matplotlib,
# pyvista for the optional pyvista front, mypy for the typing checks).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
pip=(python3 -m pip install -q --disable-pip-version-check --root-user-action=ignore)
"${pip[@]}" numpy scipy h5py pytest matplotlib pyvista jsonschema "maturin>=1.8,<2" "mypy==2.4.1"
rm -f target/wheels/deltasph-*.whl
python3 -m maturin build --release --quiet -m crates/sph-py/Cargo.toml -o target/wheels
"${pip[@]}" --force-reinstall --no-deps target/wheels/deltasph-*.whl
