#!/usr/bin/env bash
# A sweep killed at any moment (SIGKILL included) resumes with no duplicated and no
# partial rows, and does not redo complete runs; SIGINT discards the current run
# cleanly and says how to resume.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat > long.yaml <<'YAML'
shadesweep: 1
name: long
scene: empty
renderers: [null]
resolution: 16x16
trials: 2
duration: {seconds: 0.3}
lights: {count: 8}
sweep:
  lights.seed: [1, 2, 3, 4, 5, 6]
YAML
complete() { { ls out/long/runs/*/summary.csv 2>/dev/null || true; } | wc -l; }
wait_complete() {   # n: wait (60 s at most: ASan on a loaded CI machine) until n runs are complete
  for _ in $(seq 1 1200); do [ "$(complete)" -ge "$1" ] && return 0; sleep 0.05; done
  fail "runs did not complete in time"
}

# 1. SIGKILL mid-sweep: no orphan run goes on, resume finishes exactly the rest.
"$SHADESWEEP" run long.yaml 2>kill.err &
pid=$!
wait_complete 2
kill -9 $pid
wait $pid 2>/dev/null || true
sleep 0.5
n_before=$(complete)
[ "$n_before" -ge 2 ] && [ "$n_before" -lt 6 ] || fail "$n_before runs complete when killed"
for f in out/long/runs/*/summary.csv; do stat -c '%n %i %Y' "$f"; done | sort >before.txt
# nothing keeps writing after the sweep died (the child dies with its parent)
snap1=$(find out -type f -printf '%p %s\n' | sort | md5sum)
sleep 0.6
snap2=$(find out -type f -printf '%p %s\n' | sort | md5sum)
[ "$snap1" = "$snap2" ] || fail "files changed after the sweep was killed"

set +e
"$SHADESWEEP" run long.yaml 2>again.err; rc=$?
set -e
[ $rc -eq 2 ] && grep -q -- "--resume" again.err || fail "rerun without --resume: rc $rc"
"$SHADESWEEP" run --resume long.yaml 2>resume.err || fail "resume failed: $(cat resume.err)"
grep -q "resuming: $n_before of 6 runs already complete" resume.err || fail "resume report: $(cat resume.err)"
# a progress line per trial run: the incomplete runs' trials, less those a killed run
# had complete (resume keeps them, and says how many)
kept=$(sed -n 's/.*: \([0-9]*\) of its trials kept.*/\1/p' resume.err | awk '{s += $1} END {print s + 0}')
[ "$(grep -c '^[0-9]* of [0-9]*: run ' resume.err)" -eq $((2 * (6 - n_before) - kept)) ] ||
  fail "resume ran complete runs or trials again: $(cat resume.err)"
for f in $(cut -d' ' -f1 before.txt); do stat -c '%n %i %Y' "$f"; done | sort >after.txt
cmp -s before.txt after.txt || fail "complete runs were rewritten by resume"

"$PYTHON" - <<'PY'
import csv, glob, os, sys
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
plan = [p["run_id"] for p in csv.DictReader(open("out/long/plan.csv"))]
rows = list(csv.DictReader(open("out/long/summary.csv")))
keys = [(r["run_id"], r["trial"]) for r in rows]
if keys != [(i, t) for i in plan for t in ("1", "2")]: fail(f"summary rows {keys}")
if any(r["status"] != "ok" for r in rows): fail("statuses")
for i in plan:
    fr = list(csv.DictReader(open(f"out/long/runs/{i}/frames.csv")))
    per = [r["trial"] for r in fr]
    if per != sorted(per) or set(per) != {"1", "2"}: fail(f"frames.csv of {i} mixes runs")
    s = list(csv.DictReader(open(f"out/long/runs/{i}/summary.csv")))
    for t in ("1", "2"):
        if int([x for x in s if x["trial"] == t][0]["frames"]) != per.count(t):
            fail(f"{i} trial {t}: frames.csv and summary disagree")
if glob.glob("out/long/**/*.tmp.*", recursive=True): fail("temporary files left")
PY

# 2. SIGINT: the trial in progress is discarded (a run stopped in its second trial keeps
#    its first), the summary holds the complete runs, the message says how to resume,
#    the exit status is 130.
rm -rf out
"$SHADESWEEP" run long.yaml 2>int.err &
pid=$!
wait_complete 1
kill -INT $pid
set +e
wait $pid; rc=$?
set -e
[ $rc -eq 130 ] || fail "SIGINT exit status $rc"
grep -q "interrupted by SIGINT" int.err && grep -q "shadesweep run --resume -o out/long" int.err \
  || fail "no resume instructions: $(cat int.err)"
n=$(complete)
kept=0
for d in out/long/runs/*/; do
  [ -f "$d/summary.csv" ] && continue
  # the one incomplete run: its complete first trial, nothing of the discarded second
  [ -f "$d/trial-1/files.txt" ] && [ ! -e "$d/trial-2" ] ||
    fail "the interrupted trial was not discarded: $(ls -R "$d")"
  kept=$((kept + 1))
done
[ $kept -le 1 ] || fail "$kept incomplete runs after SIGINT"
[ "$(tail -n +2 out/long/summary.csv | wc -l)" -eq $((2 * n)) ] || fail "summary after SIGINT"
"$SHADESWEEP" run --resume long.yaml 2>resume2.err || fail "resume after SIGINT"
[ "$(grep -c ': 1 of its trials kept' resume2.err)" -eq $kept ] ||
  fail "resume did not keep the complete trial: $(cat resume2.err)"
[ "$(tail -n +2 out/long/summary.csv | wc -l)" -eq 12 ] || fail "summary after resume"
echo ok
