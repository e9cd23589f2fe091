#!/usr/bin/env bash
# Builds the Python wheel for manylinux2014 (glibc 2.17 and later: the HPC clusters and
# long-term-support systems that the wheel of scripts/install-python.sh, tagged for this
# machine's glibc, does not install on). maturin links with zig (the `ziglang` package
# from PyPI) against glibc 2.17's symbols, and CMake builds HDF5 and zlib-ng with the
# same zig compiler. The wheel goes to target/wheels-manylinux; auditwheel shows its
# tag and the libraries it needs. Test it in a fresh venv with
#   DELTASPH_WHEEL=target/wheels-manylinux/<file> python3 -m pytest tests/python/test_wheel.py
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
pip=(python3 -m pip install -q --disable-pip-version-check --root-user-action=ignore)
"${pip[@]}" "maturin>=1.8,<2" ziglang auditwheel
rm -rf target/wheels-manylinux
# a target folder of its own: the zig-linked build shares nothing with the native one
CARGO_TARGET_DIR=target/manylinux python3 -m maturin build --release --quiet --zig \
    --compatibility manylinux2014 -m crates/sph-py/Cargo.toml -o target/wheels-manylinux
python3 -m auditwheel show target/wheels-manylinux/deltasph-*.whl
