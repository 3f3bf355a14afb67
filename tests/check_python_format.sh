#!/usr/bin/env bash
# The Python is formatted with black (its configuration in pyproject.toml): shows what black would
# change in every tracked *.py file that is not, and fails (run black on them).
# Usage: check_python_format.sh BLACK SOURCE_DIR
set -euo pipefail
cd "$2"
mapfile -t files < <(git ls-files '*.py')
[ ${#files[@]} -gt 0 ] || { echo "no tracked Python file in $2 (not a git checkout?)"; exit 1; }
"$1" --config pyproject.toml --check --diff "${files[@]}"
