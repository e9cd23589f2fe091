#!/usr/bin/env bash
# Runs every test of the project: Rust unit, integration (physics) and CLI tests in
# release mode (the physics tests move thousands of particles), the runs split over
# processes against serial ones (sph-cli built with its `mpi` feature, under mpirun),
# then builds and installs the Python module and runs its pytest suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --test
cargo test --release --workspace
cargo test --release -p sph-cli --features mpi --test mpi
bash scripts/install-python.sh
python3 -m pytest tests/python -q
