#!/usr/bin/env bash
# The README's second command: installs the packages (as root, Debian 12), builds everything and
# runs every test. .ci/run runs this script, through the README, on a clean clone on 2 cores; it
# must stay within 25 minutes there. The quick pass under the sanitizers is its own command,
# tests/run_sanitizers.sh (docs/stability.md, "Sanitizers"). A compiler cache is used when
# CMAKE_CXX_COMPILER_LAUNCHER says so.
set -euo pipefail
cd "$(dirname "$0")/.."
apt-get update
DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
  cmake make g++ pkg-config python3 python3-numpy libvtk9-dev libeigen3-dev libtinyxml2-dev \
  libosmesa6-dev libgtest-dev libopenmpi-dev openmpi-bin libpetsc-real3.18-dev clang-format black
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2
cd build && ctest --output-on-failure -j2
