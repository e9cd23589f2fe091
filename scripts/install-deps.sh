#!/usr/bin/env bash
# Installs what deltasph needs to build, when it is missing: CMake 3.26 or later (from
# PyPI, as Debian 12's is older), which builds the HDF5 library linked into deltasph
# (the hdf5-metno-src crate; a build with `--no-default-features` links the system's
# libhdf5-dev instead); and with --test, with apt, what the tests use besides:
# ParaView's Python reader (python3-paraview) and a virtual display (xvfb) to open and
# render the output as a user would, and unshare (util-linux) for the full-disk test;
# and with --mpi (which --test implies), Open MPI (libopenmpi-dev, openmpi-bin) and
# libclang-dev, which the `mpi` feature of sph-cli builds its bindings with.
set -euo pipefail
want=()
cmake_ok() {
  command -v cmake >/dev/null &&
    printf '%s\n' 3.26 "$(cmake --version | sed -n 's/^cmake version //p')" | sort -V -C
}
if ! cmake_ok; then
  echo "installing cmake>=3.26 (pip)" >&2
  python3 -m pip install -q --disable-pip-version-check --root-user-action=ignore "cmake>=3.26,<4"
  hash -r
fi
installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q 'ok installed'; }
if [ "${1:-}" = "--test" ]; then
  command -v pvpython >/dev/null || want+=(python3-paraview)
  command -v xvfb-run >/dev/null || want+=(xvfb xauth)
  command -v unshare >/dev/null || want+=(util-linux)
fi
if [ "${1:-}" = "--test" ] || [ "${1:-}" = "--mpi" ]; then
  for package in libopenmpi-dev openmpi-bin libclang-dev; do
    installed "$package" || want+=("$package")
  done
fi
[ ${#want[@]} -eq 0 ] && exit 0
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
echo "installing ${want[*]} (apt)" >&2
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${want[@]}" >/dev/null
