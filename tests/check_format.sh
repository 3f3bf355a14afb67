#!/usr/bin/env bash
# The code is formatted with the repository's .clang-format: lists every file that is not and
# fails (run `clang-format -i` on them). Usage: check_format.sh CLANG_FORMAT SOURCE_DIR
set -uo pipefail
cd "$2"
files=$(find Core Components StandAlone vis tests \( -name '*.cc' -o -name '*.h' \) | sort)
"$1" --dry-run -Werror $files 2>&1 | grep -E "^[^ ].*: error:" | sed 's/:[0-9]*:[0-9]*: error:.*//' | sort -u > /tmp/check_format.$$
status=0
if [ -s /tmp/check_format.$$ ]; then
  echo "not formatted with .clang-format (run clang-format -i on them):"
  cat /tmp/check_format.$$
  status=1
fi
rm -f /tmp/check_format.$$
exit $status
