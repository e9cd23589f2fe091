#!/usr/bin/env bash
# Runs every test of the project: unit, integration (physics) and CLI tests, in release
# mode because the physics tests move thousands of particles.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cargo test --release --workspace
