#!/usr/bin/env bash
# The README's second command: installs the packages (as root, Debian 12), builds everything, runs
# every test, then builds sus and a few test programs again with
# AddressSanitizer and UndefinedBehaviorSanitizer (build-asan, -O1 -g1, target sanitizer_quick)
# and runs the tests labelled sanitize there (docs/stability.md, "Sanitizers").
# .ci/run runs this script, through the README, on a clean clone on 2 cores; it must stay within
# 25 minutes there. A compiler cache is used when CMAKE_CXX_COMPILER_LAUNCHER says so.
set -euo pipefail
cd "$(dirname "$0")/.."
apt-get update
DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
  cmake make g++ pkg-config python3 python3-numpy libvtk9-dev libeigen3-dev libtinyxml2-dev \
  libosmesa6-dev libgtest-dev libopenmpi-dev openmpi-bin libpetsc-real3.18-dev clang-format black
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2
(cd build && ctest --output-on-failure -j2)
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DANODE_SANITIZE=ON
cmake --build build-asan -j2 --target sanitizer_quick
cd build-asan && ctest --output-on-failure -j2 -L sanitize
