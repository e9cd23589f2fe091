#!/usr/bin/env bash
# Builds sph-cli and runs the 2D dam break (δ-SPH benchmark, H/Δx = 50, to t·sqrt(g/H) = 7)
# end to end. Output goes to a new folder under out/, never over an existing one.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cargo build --release -p sph-cli
out="out/dam_break_2d-$(date +%Y%m%d-%H%M%S)"
mkdir -p out
./target/release/sph-cli run examples/dam_break_2d.toml --out "$out"
echo "open $out/particles.xmf in ParaView; time series in $out/timeseries.csv"
