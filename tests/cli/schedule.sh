#!/usr/bin/env bash
# The schedule (runner/cli/schedule.c): trials: auto stops when the ranking is decided, or
# when measure.budget is spent (and says so); `schedule: sequential` runs each run's
# trials back to back; auto with sequential is refused; run --round K adds one round at
# a time and merges the runs after the last. No assertion reads a time.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
manifest() {  # manifest NAME EXTRA...
  cat <<YAML
shadesweep: 1
name: $1
scene: shapes
renderers: [null, deferred]
resolution: 32x32
warmup: {frames: 2}
duration: {frames: 10}
clock: fixed
lights: {count: 4, radius: 4}
outputs: {frames: false, seconds: false}
YAML
  shift
  printf '%s\n' "$@"
}

# auto, decided: null against deferred differ by far more than any noise, so the paired
# ratio's interval excludes 1 after the 3 rounds auto starts with
manifest auto "trials: auto" "measure: {precision: 0.5}" >auto.yaml
"$SHADESWEEP" run -o auto auto.yaml >auto.out 2>auto.err || fail "auto: $(cat auto.err)"
"$PYTHON" - auto <<'PY'
import csv, sys
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
rows = list(csv.DictReader(open(f"{sys.argv[1]}/summary.csv")))
trials = {}
for r in rows: trials.setdefault(r["run_id"], []).append(int(r["trial"]))
if len(trials) != 2 or any(sorted(t) != [1, 2, 3] for t in trials.values()):
    fail(f"auto should stop at 3 decided rounds: {trials}")
PY
grep -q "differs" auto/summary.md || fail "no table"
grep -q "| yes |" auto/summary.md || fail "auto: the two renderers should differ: $(cat auto/summary.md)"

# auto with a precision no 3 trials reach and a budget the first rounds spend: it
# stops after the 3 rounds auto always runs, saying so, unless the ratio was decided
# there by excluding 1 (deferred with no lights in two light-volume modes: the same work)
manifest budget "trials: auto" "measure: {precision: 0.000001, budget: 0.5}" \
  "sweep: {deferred.light_volumes: [stencil, fullscreen]}" | sed 's/count: 4/count: 0/' >budget.yaml
"$SHADESWEEP" run -o budget budget.yaml >budget.out 2>budget.err || fail "budget: $(cat budget.err)"
[ "$(tail -n +2 budget/summary.csv | wc -l)" -eq 9 ] || fail "budget: want 3 runs x 3 trials"
if ! grep -q "^sweep point 0: measure.budget (0.5 s) spent after 3 rounds: some of its ratios are still undecided" budget.err; then
  # decided instead: then every ratio to the fastest excludes 1
  [ "$(grep -c '| yes |' budget/summary.md)" -eq 2 ] || fail "budget: neither spent nor decided: $(cat budget.err)"
fi

# sequential: each run's trials back to back, `order` its place among the point's runs
manifest seq "trials: 3" "schedule: sequential" >seq.yaml
"$SHADESWEEP" run -o seq seq.yaml >seq.out 2>seq.err || fail "sequential: $(cat seq.err)"
"$PYTHON" - seq seq.err <<'PY'
import csv, re, sys
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
rows = list(csv.DictReader(open(f"{sys.argv[1]}/summary.csv")))
plan = [p["run_id"] for p in csv.DictReader(open(f"{sys.argv[1]}/plan.csv"))]
for r in rows:
    if int(r["order"]) != plan.index(r["run_id"]) + 1: fail(f"sequential order {r}")
ran = [m.group(1) for m in re.finditer(r"^[0-9]+ of 6: run ([0-9a-f]{12}) ", open(sys.argv[2]).read(), re.M)]
if ran != [plan[0]] * 3 + [plan[1]] * 3: fail(f"sequential ran {ran}")
PY
grep -q "^  mode: sequential$" seq/runs/*/meta.yaml || fail "meta.yaml schedule"

# auto needs rounds
manifest bad "trials: auto" "schedule: sequential" >bad.yaml
set +e
"$SHADESWEEP" validate bad.yaml >/dev/null 2>bad.err; rc=$?
set -e
[ $rc -eq 2 ] && grep -q "schedule: expected interleaved with trials: auto" bad.err ||
  fail "auto + sequential: rc $rc $(cat bad.err)"

# --round K: round 1 leaves the runs incomplete (trial folders only), round 2 adds to
# them, round 3 merges; the folder is then as one run of the manifest makes it
manifest rounds "trials: 3" >rounds.yaml
set +e
"$SHADESWEEP" run --round 1 -o rounds rounds.yaml >r1.out 2>r1.err; rc1=$?
set -e
[ $rc1 -eq 1 ] || fail "round 1: rc $rc1 $(cat r1.err)"
[ "$(ls -d rounds/runs/*/trial-1 | wc -l)" -eq 2 ] && [ -z "$(ls rounds/runs/*/files.txt 2>/dev/null)" ] ||
  fail "round 1 left: $(find rounds/runs)"
set +e
"$SHADESWEEP" run --resume --round 2 -o rounds rounds.yaml >r2.out 2>r2.err; rc2=$?
set -e
[ $rc2 -eq 1 ] && [ "$(ls -d rounds/runs/*/trial-2 | wc -l)" -eq 2 ] || fail "round 2: rc $rc2 $(cat r2.err)"
"$SHADESWEEP" run --resume --round 3 -o rounds rounds.yaml >r3.out 2>r3.err || fail "round 3: $(cat r3.err)"
[ "$(ls rounds/runs/*/files.txt | wc -l)" -eq 2 ] && [ -z "$(ls -d rounds/runs/*/trial-* 2>/dev/null)" ] ||
  fail "round 3 did not merge: $(find rounds/runs)"
[ "$(tail -n +2 rounds/summary.csv | wc -l)" -eq 6 ] || fail "rounds: want 6 rows"
grep -q "^  - trial: 3$" rounds/runs/*/meta.yaml || fail "meta.yaml trials"
set +e
"$SHADESWEEP" run --round 1 -o x auto.yaml >/dev/null 2>x.err; rc=$?
set -e
[ $rc -eq 2 ] && grep -q -- "--round: not with trials: auto" x.err || fail "--round with auto: $(cat x.err)"
echo "schedule: ok"
