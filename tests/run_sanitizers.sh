#!/usr/bin/env bash
# The quick pass under AddressSanitizer and UndefinedBehaviorSanitizer (docs/stability.md,
# "Sanitizers"): builds sus and a few test programs again in build-asan (-O1 -g1, target
# sanitizer_quick) and runs the tests labelled sanitize there. Needs the packages of
# tests/run_all.sh. Not part of the README's test command: its build alone, from cold, would take
# that command past its 25 minutes on 2 cores (docs/stability.md).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DANODE_SANITIZE=ON
cmake --build build-asan -j2 --target sanitizer_quick
cd build-asan && ctest --output-on-failure -j2 -L sanitize
