#!/usr/bin/env bash
# One run status told the same way everywhere (issue 42): trial 2 of the null run hangs
# (debug.stall_trial) and times out, so that run is partial:timeout (trial 1 ok; trial 3
# failed:not-run: a timeout ends its run) and the deferred run ok.
# summary.csv's rows, meta.yaml, summary.json, summary.md, report.md, the terminal of
# `run` and of `run --resume` on the finished folder all name that run with that status;
# both exit 1, as README says of a partial run.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat > st.yaml <<'YAML'
shadesweep: 1
name: status
scene: shapes
renderers: [null, deferred]
resolution: 16x16
trials: 3
warmup: {frames: 0}
duration: {frames: 2}
clock: fixed
timeout: 8
lights: {count: 4}
debug: {stall_trial: 2, busy_renderer: null}
YAML
set +e
"$SHADESWEEP" run -o out st.yaml >run.out 2>run.err; rc=$?
set -e
[ $rc -eq 1 ] || fail "run: exit $rc, want 1: $(cat run.err)"
id=$(awk -F, 'NR > 1 && $0 ~ /,null,/ {print $2; exit}' out/plan.csv)
ok=$(awk -F, 'NR > 1 && $0 ~ /,deferred,/ {print $2; exit}' out/plan.csv)
[ ${#id} -eq 12 ] && [ ${#ok} -eq 12 ] || fail "run ids from plan.csv: '$id' '$ok'"

# nok: the null run's ok trials (1: trial 3 is not run after the timeout)
nok=$("$PYTHON" - "$id" "$ok" <<'PY'
import csv, json, sys
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
bad, good = sys.argv[1], sys.argv[2]
rows = {(r["run_id"], r["trial"]): r["status"] for r in csv.DictReader(open("out/summary.csv"))}
third = rows.get((bad, "3"))
if third != "failed:not-run": fail(f"summary.csv: trial 3 of {bad}: {third}")
want = {(bad, "1"): "ok", (bad, "2"): "failed:timeout", (bad, "3"): third,
        (good, "1"): "ok", (good, "2"): "ok", (good, "3"): "ok"}
if rows != want: fail(f"summary.csv statuses {rows}")
nok = 1 + (third == "ok")
d = json.load(open("out/summary.json"))
runs = {r["run_id"]: r for p in d["points"] for r in p["runs"]}
if runs[bad]["status"] != "partial:timeout" or runs[good]["status"] != "ok":
    fail(f"summary.json statuses {[(k, r['status']) for k, r in runs.items()]}")
if (runs[bad]["trials"], runs[bad]["trials_ok"]) != (3, nok): fail(f"summary.json {runs[bad]}")
if [t["status"] for t in runs[bad]["trial_results"]] != ["ok", "failed:timeout", third]:
    fail(f"summary.json trial_results {runs[bad]['trial_results']}")
for rid, st in ((bad, '"partial:timeout"'), (good, '"ok"')):
    if f"status: {st}\n" not in open(f"out/runs/{rid}/meta.yaml").read():
        fail(f"meta.yaml of {rid} lacks status: {st}")
print(nok)
PY
) || fail "the files disagree"
want="run $id (null): partial:timeout, $nok of 3 trials ok"

grep -q "| $id | .* | $nok of 3 ok, partial:timeout |$" out/summary.md ||
  fail "summary.md: $(grep -F "$id" out/summary.md)"
grep -q "| $ok | .* | 3 of 3 ok |$" out/summary.md || fail "summary.md: $(grep -F "$ok" out/summary.md)"
grep -qx "2 runs, 0 failed, 1 partial ($((4 + nok)) trials), in .*" run.err ||
  fail "run's count: $(cat run.err)"
grep -qxF "$want" run.err || fail "run names no partial run: $(cat run.err)"
[ "$(grep -c '^run .*trials ok$' run.err)" -eq 1 ] || fail "run names an ok run: $(cat run.err)"

# --resume on the finished folder: nothing to run, the same account, the same exit status
set +e
"$SHADESWEEP" run --resume -o out st.yaml >resume.out 2>resume.err; rc=$?
set -e
[ $rc -eq 1 ] || fail "run --resume: exit $rc, want 1: $(cat resume.err)"
grep -qx "2 runs, 0 failed, 1 partial (no trial run now), in .*" resume.err ||
  fail "resume's count: $(cat resume.err)"
grep -qxF "$want" resume.err || fail "resume names no partial run: $(cat resume.err)"

"$SHADESWEEP" report out >report.out 2>report.err || fail "report: $(cat report.err)"
grep -qx "report: wrote out/report.md: status, [0-9]* plot(s)" report.out ||
  fail "report's line: $(cat report.out)"
grep -qi "recognised" report.out out/report.md && fail "a user manifest 'not recognised'"
grep -qx "Runs: 2 planned, 2 with measured trials, 0 failed, 1 partial." out/report.md ||
  fail "report.md: $(grep '^Runs' out/report.md)"
grep -qxF "Partial runs (their ok trials are used): $id null: partial:timeout, $nok of 3 trials ok." \
  out/report.md || fail "report.md names no partial run: $(grep -A1 '^Runs' out/report.md)"
echo "run_status: ok"
