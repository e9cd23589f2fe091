#!/usr/bin/env bash
# Builds and installs the Python module `deltasph` (crates/sph-py, via maturin) into
# the current Python, with what its tests and examples use (numpy, h5py, pytest,
# matplotlib).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
python3 -m pip install -q --disable-pip-version-check --root-user-action=ignore numpy h5py pytest matplotlib
python3 -m pip install -q --disable-pip-version-check --root-user-action=ignore ./crates/sph-py
