#!/usr/bin/env bash
# Large plans are checked at a small cost per run: validate and list of a 20,000-run
# sweep (2,000 light seeds x 10 counts, every run a distinct scene configuration) give
# the right count and distinct ids. Building each configuration's scene (about 50 ms a
# run) or comparing the runs pairwise would take this test past its timeout; it takes
# about a second. A refusal found at that scale still names the runs, at most 8 lines.
. "$(dirname "$0")/lib.sh"
cd "$T"
manifest() {   # NAME PLACEMENT RADIUS
  { echo "shadesweep: 1"; echo "name: $1"; echo "scene: shapes"
    echo "renderers: [deferred]"; echo "resolution: 64x64"; echo "duration: {seconds: 1}"
    echo "lights: {placement: $2, radius: $3}"
    echo "sweep:"
    printf '  lights.seed: ['; seq -s ', ' 1 2000 | tr -d '\n'; echo ']'
    echo "  lights.count: [10, 20, 30, 40, 50, 60, 70, 80, 90, 100]"
  } >"$1.yaml"
}
manifest big random 2
"$SHADESWEEP" validate big.yaml >out.txt 2>err.txt || fail "validate: $(cat err.txt)"
[ "$(cat out.txt)" = "big.yaml: ok, 20000 runs" ] && [ ! -s err.txt ] \
  || fail "validate: $(cat out.txt err.txt)"
"$SHADESWEEP" list big.yaml >list.txt 2>err.txt || fail "list: $(cat err.txt)"
[ "$(wc -l <list.txt)" -eq 20000 ] || fail "list: $(wc -l <list.txt) lines"
[ "$(cut -d' ' -f1 list.txt | sort -u | wc -l)" -eq 20000 ] || fail "list: ids not distinct"
grep -qx "[0-9a-f]\{12\}  renderer=deferred lights.seed=2000 lights.count=100" <(tail -n 1 list.txt) \
  || fail "list: last line $(tail -n 1 list.txt)"
# grid placement with a radius that makes neighbours overlap in every run: exit 2,
# nothing on stdout, the first 8 distinct configurations named in plan order
manifest overlap grid 50
set +e
"$SHADESWEEP" validate overlap.yaml >out.txt 2>err.txt; rc=$?
set -e
[ $rc -eq 2 ] && [ ! -s out.txt ] || fail "overlap: exit $rc: $(cat out.txt err.txt)"
[ "$(grep -c "^overlap.yaml: scene: expected a scene the runs can render, found: scene 'shapes': grid placement of " err.txt)" -eq 8 ] \
  || fail "overlap: want 8 scene lines: $(cat err.txt)"
# runs 0..7 in plan order: seed 1 with counts 10..80 (the last axis varies fastest)
[ "$(grep -o 'grid placement of [0-9]* lights' err.txt | cut -d' ' -f4 | tr '\n' ' ')" = "10 20 30 40 50 60 70 80 " ] \
  || fail "overlap: not the first 8 configurations: $(cat err.txt)"
