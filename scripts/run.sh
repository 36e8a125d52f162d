#!/usr/bin/env bash
# Set-up if needed, build, then `shadesweep ARGS`.
# With no arguments: the quick-start experiment on EGL + llvmpipe, into out/quickstart,
# ending with the ranked table, the verdicts and the crossovers, and a plot.
# On a terminal it says what it is doing (scripts/say.sh).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
. "$root/scripts/say.sh"
say "run: checking the packages it needs (scripts/setup.sh)"
"$root/scripts/setup.sh"
"$root/scripts/build.sh" "$root/build"
exe="$root/build/runner/shadesweep"
if [ $# -eq 0 ]; then
  # Mesa's software rasterizer even where a GPU driver exists: the quick-start's numbers
  # are comparable across machines.
  export LIBGL_ALWAYS_SOFTWARE=1
  cd "$root"
  # the run ends with the renderers ranked (also out/quickstart/summary.md), a verdict
  # per point and where they change places as the lights grow; the report adds the plot
  # of the metric against lights per renderer. The run's answer is printed once, last,
  # after the report (its progress goes to stderr as it runs).
  rc=0
  log=$(mktemp)
  trap 'rm -f "$log"' EXIT
  say "run: running experiments/quickstart.yaml into out/quickstart"
  "$exe" run --force experiments/quickstart.yaml >"$log" || rc=$?
  if [ $rc -ne 2 ]; then
    say "run: writing the report (out/quickstart/report.md)"
    "$exe" report out/quickstart >&2 &&
      echo "plot: out/quickstart/plots/quickstart_frametime_lights.png (in out/quickstart/report.md)"
  fi
  cat "$log"
  exit $rc
fi
exec "$exe" "$@"
