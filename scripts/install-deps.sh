#!/usr/bin/env bash
# Installs the system packages deltasph needs, with apt, when they are missing:
# libhdf5 with its headers (always), and with --test what the tests use besides:
# ParaView's Python reader (python3-paraview) and a virtual display (xvfb) to open and
# render the output as a user would, and unshare (util-linux) for the full-disk test.
set -euo pipefail
want=()
if ! pkg-config --exists hdf5 2>/dev/null && [ ! -f /usr/include/hdf5/serial/hdf5.h ]; then
  want+=(libhdf5-dev pkg-config)
fi
if [ "${1:-}" = "--test" ]; then
  command -v pvpython >/dev/null || want+=(python3-paraview)
  command -v xvfb-run >/dev/null || want+=(xvfb xauth)
  command -v unshare >/dev/null || want+=(util-linux)
fi
[ ${#want[@]} -eq 0 ] && exit 0
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
echo "installing ${want[*]} (apt)" >&2
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${want[@]}" >/dev/null
