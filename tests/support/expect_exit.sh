#!/usr/bin/env bash
# usage: expect_exit.sh CODE REGEX -- COMMAND...
# Passes when COMMAND exits with CODE and its stderr+stdout matches the extended REGEX.
set -u
want_code=$1 regex=$2
shift 3
output=$("$@" 2>&1)
code=$?
if [[ $code -ne $want_code ]]; then
  printf 'expected exit code %s, got %s\noutput:\n%s\n' "$want_code" "$code" "$output"
  exit 1
fi
if ! grep -Eq -- "$regex" <<<"$output"; then
  printf 'output does not match /%s/:\n%s\n' "$regex" "$output"
  exit 1
fi
echo "ok: exit $code, message matches /$regex/"
