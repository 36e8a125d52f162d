#!/usr/bin/env bash
# Shards and merge: shards run separately and merged equal a single run of the
# manifest (plan, ids, work counts, statuses); merge refuses other manifests' shards
# and reports missing runs.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat > m.yaml <<'YAML'
shadesweep: 1
name: m
scene: empty
renderers: [null]
trials: 2
duration: {frames: 6}
clock: fixed
lights: {count: {start: 0, step: 2, every: 0.01, max: 8}}
sweep:
  resolution: [8x8, 16x16, 24x24]
  lights.seed: [1, 2]
YAML
"$SHADESWEEP" run -o single m.yaml 2>/dev/null || fail "single run"
for i in 1 2 3; do "$SHADESWEEP" run --shard $i/3 -o shard$i m.yaml 2>/dev/null || fail "shard $i"; done
"$SHADESWEEP" merge -o merged shard1 shard2 shard3 2>merge.err || fail "merge: $(cat merge.err)"
grep -q "merged 6 of 6 runs from 3 folders into merged" merge.err || fail "merge report: $(cat merge.err)"
"$PYTHON" - <<'PY'
import csv, os, sys
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
single_plan = open("single/plan.csv").read()
shard_plan = open("shard1/plan.csv").read()
merged_plan = open("merged/plan.csv").read()
if merged_plan != shard_plan: fail("merged plan.csv is not the shards' plan.csv")
strip = lambda t: [l.split(",")[:2] + l.split(",")[3:] for l in t.splitlines()]  # all but shard
if strip(single_plan) != strip(merged_plan): fail("merged plan differs from the single run's")
keys = ("run_id", "trial", "frames", "lights_count", "draw_calls_mean", "state_changes_mean",
        "fragments_mean", "status")
a = [tuple(r[k] for k in keys) for r in csv.DictReader(open("single/summary.csv"))]
b = [tuple(r[k] for k in keys) for r in csv.DictReader(open("merged/summary.csv"))]
if len(a) != 12 or a != b: fail(f"merged summary differs from the single run:\n{a}\n{b}")
for rid in {r[0] for r in a}:
    fr = lambda d: [(r["frame"], r["lights"], r["draw_calls"]) for r in
                    csv.DictReader(open(f"{d}/runs/{rid}/frames.csv"))]
    if fr("single") != fr("merged"): fail(f"frames of {rid} differ")
PY
# a missing shard: exit 1, the missing runs named
set +e
"$SHADESWEEP" merge -o partial shard1 shard3 2>partial.err; rc=$?
set -e
[ $rc -eq 1 ] && grep -q "merged 4 of 6 runs" partial.err && grep -q "missing runs" partial.err \
  || fail "partial merge: rc $rc $(cat partial.err)"
[ "$(tail -n +2 partial/summary.csv | wc -l)" -eq 8 ] || fail "partial summary rows"
# shards of another manifest are refused, and nothing is written
sed 's/duration: {frames: 6}/duration: {frames: 7}/' m.yaml > other.yaml
"$SHADESWEEP" run --shard 2/3 -o other2 other.yaml 2>/dev/null || fail "other shard"
set +e
"$SHADESWEEP" merge -o bad shard1 other2 2>bad.err; rc=$?
set -e
[ $rc -eq 2 ] && grep -q "shards of different manifests cannot be merged" bad.err && [ ! -e bad ] \
  || fail "mixed manifests: rc $rc $(cat bad.err)"
# an existing output folder is not overwritten without --force
set +e
"$SHADESWEEP" merge -o merged shard1 shard2 shard3 2>exists.err; rc=$?
set -e
[ $rc -eq 2 ] && grep -q "exists" exists.err || fail "merge over an existing folder"
"$SHADESWEEP" merge --force -o merged shard1 shard2 shard3 2>/dev/null || fail "merge --force"
echo ok
