#!/usr/bin/env bash
# Configures (once) and builds one build folder; prints the build log only on failure.
#   scripts/build.sh DIR [meson setup options...]
set -euo pipefail
cd "$(dirname "$0")/.."
dir=$1; shift
log=$(mktemp)
trap 'rm -f "$log"' EXIT
if [ ! -f "$dir/build.ninja" ]; then
  if ! meson setup "$dir" "$@" >"$log" 2>&1; then
    cat "$log" >&2; echo "build: meson setup $dir failed" >&2; exit 1
  fi
fi
if ! ninja -C "$dir" >"$log" 2>&1; then
  cat "$log" >&2; echo "build: ninja -C $dir failed" >&2; exit 1
fi
