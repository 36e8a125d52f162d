#!/usr/bin/env bash
# Configures (once) and builds one build folder. On a terminal it says so and shows
# ninja's one-line progress; elsewhere (or CI=true) it prints the log only on failure.
#   scripts/build.sh DIR [meson setup options...]
# meson compiles through ccache where it is installed (scripts/setup.sh installs it): a
# fresh clone of an unchanged tree, anywhere on the machine (CI's), rebuilds from the cache.
set -euo pipefail
cd "$(dirname "$0")/.."
export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=true
. scripts/say.sh
dir=$1; shift
log=$(mktemp)
trap 'rm -f "$log"' EXIT
if [ ! -f "$dir/build.ninja" ]; then
  say "build: configuring $dir (meson setup)"
  if ! meson setup "$dir" "$@" >"$log" 2>&1; then
    cat "$log" >&2; echo "build: meson setup $dir failed" >&2; exit 1
  fi
fi
if talkative; then
  say "build: building $dir (ninja; the first build takes a few minutes)"
  ninja -C "$dir" >&2 || { echo "build: ninja -C $dir failed" >&2; exit 1; }
elif ! ninja -C "$dir" >"$log" 2>&1; then
  cat "$log" >&2; echo "build: ninja -C $dir failed" >&2; exit 1
fi
