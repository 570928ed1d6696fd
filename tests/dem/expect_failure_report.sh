#!/usr/bin/env bash
# usage: expect_failure_report.sh CODE REGEX... -- COMMAND...
# Passes when COMMAND exits with CODE and its stderr+stdout has a line matching each
# extended REGEX (a failure report spans lines: who failed, then the engine's own text).
set -u
want_code=$1
shift
regexes=()
while [[ $# -gt 0 && $1 != "--" ]]; do
  regexes+=("$1")
  shift
done
shift
start=$SECONDS
output=$("$@" 2>&1)
code=$?
if [[ $code -ne $want_code ]]; then
  printf 'expected exit code %s, got %s\noutput:\n%s\n' "$want_code" "$code" "$output"
  exit 1
fi
for regex in "${regexes[@]}"; do
  if ! grep -Eq -- "$regex" <<<"$output"; then
    printf 'output has no line matching /%s/:\n%s\n' "$regex" "$output"
    exit 1
  fi
done
echo "ok: exit $code after $((SECONDS - start)) s, output matches all of: ${regexes[*]}"
