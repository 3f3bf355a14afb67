#!/usr/bin/env bash
# expect_exit.sh CODE [--match REGEX] command...: runs the command, prints its output, and
# succeeds only if it exited with CODE and (if given) its output matches the extended REGEX.
expected=$1
shift
pattern=""
if [ "${1:-}" = "--match" ]; then
  pattern=$2
  shift 2
fi
output=$("$@" 2>&1)
code=$?
printf '%s\n' "$output"
if [ "$code" -ne "$expected" ]; then
  echo "expect_exit.sh: exit code $code, expected $expected"
  exit 1
fi
if [ -n "$pattern" ] && ! grep -Eq -- "$pattern" <<<"$output"; then
  echo "expect_exit.sh: output does not match: $pattern"
  exit 1
fi
