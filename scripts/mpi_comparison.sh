#!/usr/bin/env bash
# One process with 2 threads against 2 processes with 1 thread each, on the same case
# and machine: the 2D dam break at 40k and 200k fluid particles and the 3D dam break at
# 100k (the examples at a finer spacing, a snapshot only at the start and the end).
# Prints each run's summary and, for the split runs, the per-process report (halo,
# bytes per refresh, time in refreshes and in communication, load imbalance).
# Usage: bash scripts/mpi_comparison.sh [work folder]  (figures in docs/scaling.md)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --mpi
cargo build --release -q -p sph-cli --features mpi
bin="$PWD/target/release/sph-cli"
work="${1:-$(mktemp -d)}"
mkdir -p "$work"
make_case() { # example spacing name
  sed -e "s/^spacing = .*/spacing = $2/" -e "s/^output_interval = .*/output_interval = 10.0/" \
    -e "s/^interval = .*/interval = 0.05/" "examples/$1.toml" >"$work/$3.toml"
}
make_case dam_break_2d 0.0042 d2_40k
make_case dam_break_2d 0.0019 d2_200k
make_case dam_break_3d 0.0081 d3_100k
compare() { # name until
  local keep="particles|simulated|wall time|throughput|max \||processes|process |imbalance"
  echo "=== $1: 1 process, 2 threads"
  RAYON_NUM_THREADS=2 "$bin" run "$work/$1.toml" --until "$2" --out "$work/serial_$1" \
    --force -q | grep -E "$keep"
  echo "=== $1: 2 processes, 1 thread each"
  RAYON_NUM_THREADS=1 mpirun --allow-run-as-root --oversubscribe -n 2 "$bin" run \
    "$work/$1.toml" --until "$2" --out "$work/split_$1" --force -q | grep -E "$keep"
}
compare d2_40k 0.05
compare d2_200k 0.02
compare d3_100k 0.04
