#!/usr/bin/env bash
# Only the run's top level makes a Collective tag (Core/Parallel/Communicator.h,
# docs/parallel.md): lists every call of Communicator::everyRank() outside the places where every
# rank is known to take the same path, and fails if there is one. Usage: check_collective_tags.sh
# SOURCE_DIR
set -uo pipefail
cd "$1"
allowed='^(Core/Parallel/|StandAlone/sus\.cc|StandAlone/Driver/Simulation\.(cc|h)|tests/)'
found=$(grep -rn --include='*.cc' --include='*.h' 'everyRank()' Core Components StandAlone vis tests |
  grep -vE "$allowed")
if [ -n "$found" ]; then
  echo "Communicator::everyRank() outside the run's top level (pass the caller's tag instead):"
  echo "$found"
  exit 1
fi
echo "Collective tags are made only at the run's top level"
