#!/usr/bin/env bash
# One definition of the measured quantities (results/metrics.def): docs/columns.md is
# its output and must not be stale; the listing names every column of frames.csv and
# summary.csv in the order the files have them.
. "$(dirname "$0")/lib.sh"
cd "$T"

"$SHADESWEEP" columns --markdown >columns.md
cmp -s columns.md "$SOURCE_ROOT/docs/columns.md" \
  || fail "docs/columns.md is stale: run 'shadesweep columns --markdown > docs/columns.md'"
"$SHADESWEEP" columns >columns.txt || fail "columns exited $?"
grep -q "^frames.csv:  run_id, trial, frame, t_wall_s, t_scene_s, lights, frametime_us, gpu_us," columns.txt \
  || fail "columns: $(head -3 columns.txt)"
grep -q "^summary.csv: experiment, run_id, .*, status, message$" columns.txt \
  || fail "columns: $(head -3 columns.txt)"
grep -q "^gpu_us -> gpu_mean_us  (us)$" columns.txt || fail "columns: gpu_us entry"
"$SHADESWEEP" columns --help | grep -q "^usage: shadesweep columns" || fail "columns --help"
if "$SHADESWEEP" columns --bogus 2>err.txt; then fail "columns --bogus succeeded"; fi
echo "ok"
