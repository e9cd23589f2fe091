#!/usr/bin/env bash
# Runs every test of the project: Rust unit, integration (physics), CLI and MPI tests in
# release mode (the physics tests move thousands of particles; sph-cli is built once,
# with its `mpi` feature, so that the runs split over processes under mpirun are checked
# against serial ones by the same build), then builds and installs the Python module
# and runs its pytest suite (with the sph-cli binary built for the Rust tests). Each
# stage's wall time is printed at its end.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
stage() { echo "== $1 done after $((SECONDS - start)) s" >&2; }
bash scripts/install-deps.sh --test
cargo test --release --workspace --features sph-cli/mpi
stage "Rust and MPI tests"
bash scripts/install-python.sh
stage "Python module build"
# the CLI the Rust tests built (with mpi), instead of a second build without it
SPH_CLI="$PWD/target/release/sph-cli" python3 -m pytest tests/python -q --durations=5
stage "Python tests"
