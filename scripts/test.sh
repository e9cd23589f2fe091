#!/usr/bin/env bash
# Runs every test of the project: Rust unit, integration (physics) and CLI tests in
# release mode (the physics tests move thousands of particles), then builds and
# installs the Python module and runs its pytest suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --test
cargo test --release --workspace
bash scripts/install-python.sh
python3 -m pytest tests/python -q
