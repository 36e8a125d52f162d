#!/usr/bin/env bash
# Set-up if needed, build, then `shadesweep ARGS`.
# With no arguments: the quick-start experiment on EGL + llvmpipe, into out/quickstart.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh" "$root/build"
exe="$root/build/runner/shadesweep"
if [ $# -eq 0 ]; then
  # Mesa's software rasterizer even where a GPU driver exists: the quick-start's numbers
  # are comparable across machines.
  export LIBGL_ALWAYS_SOFTWARE=1
  cd "$root"
  exec "$exe" run --force experiments/quickstart.yaml
fi
exec "$exe" "$@"
