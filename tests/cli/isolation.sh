#!/usr/bin/env bash
# Run isolation: a run that aborts, segfaults, is killed with SIGKILL or
# hangs past its timeout fails alone, with its status and the tail of its log in
# summary.csv, and the sweep goes on to the next run.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
export SHADESWEEP_TEST_SCENES=1
# Under AddressSanitizer a SIGSEGV would become ASan's report and exit 1.
export ASAN_OPTIONS="${ASAN_OPTIONS:-}:handle_segv=0"
cat > faults.yaml <<'YAML'
shadesweep: 1
name: faults
renderers: [null]
resolution: 16x16
trials: 2
duration: {frames: 10}
clock: fixed
step: 0.05
timeout: 3
sweep:
  scene: [test-abort, test-segv, test-hang, test-sigkill, empty]
YAML
set +e
"$SHADESWEEP" run faults.yaml >out.txt 2>err.txt; rc=$?
set -e
[ $rc -eq 1 ] || fail "a sweep with failing runs exits 1, got $rc: $(cat err.txt)"
"$PYTHON" - <<'PY'
import csv, os, sys
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
rows = list(csv.DictReader(open("out/faults/summary.csv")))
got = [(r["scene"], r["trial"], r["status"]) for r in rows]
want = []
for scene, status in [("test-abort", "failed:SIGABRT"), ("test-segv", "failed:SIGSEGV"),
                      ("test-hang", "failed:timeout"), ("test-sigkill", "failed:SIGKILL"),
                      ("empty", "ok")]:
    # a failure that ends the run is trial 1's: the trial after it did not run
    want += [(scene, "1", status), (scene, "2", "failed:not-run" if status != "ok" else status)]
if got != want: fail(f"statuses {got}")
for r in rows:
    if r["status"] == "ok":
        if r["message"] or r["frames"] != "10": fail(f"ok row {r}")
        continue
    # the tail of the run's log, with the scene's own last words, and no measurements
    if r["status"] == "failed:not-run":
        first = [x for x in rows if x["run_id"] == r["run_id"] and x["trial"] == "1"][0]
        want = ("not run: trial 1 was stopped by its limit (timeout: 3 s"
                if first["status"] == "failed:timeout"
                else f"not run: trial 1 ended the run ({first['status']})")
        if not r["message"].startswith(want):
            fail(f"not-run message: {r}")
    elif "as this test scene does" not in r["message"]: fail(f"message lacks the log tail: {r}")
    if r["frames"] != "0" or r["fps_mean"] != "": fail(f"failed row has numbers: {r}")
    d = os.path.join("out/faults/runs", r["run_id"])
    if not os.path.exists(os.path.join(d, "meta.yaml")): fail("failed run lacks meta.yaml")
    if [f for f in os.listdir(d) if ".tmp." in f]: fail(f"temporary files left in {d}")
    if os.path.exists(os.path.join(d, "frames.csv")): fail("a crashed run has a final frames.csv")
timeout = [r for r in rows if r["scene"] == "test-hang"][0]["message"]
if not timeout.startswith("stopped after 3.") or "timeout: 3 s a trial, warm-up included" not in timeout:
    fail(f"timeout message: {timeout}")
PY
# (the priming frames before the first trial get there first: t = 0.250 at step 0.05)
grep -q "test-abort: failing at t = 0\.2[0-9]* s" out/faults/runs/*/log.txt || fail "log.txt of the aborted run"
for s in SIGABRT SIGSEGV SIGKILL timeout; do
  grep -q "failed:$s" err.txt || fail "console lacks failed:$s: $(cat err.txt)"
done
# The test scenes do not exist without the switch.
unset SHADESWEEP_TEST_SCENES
set +e
"$SHADESWEEP" validate faults.yaml 2>err.txt; rc=$?
set -e
[ $rc -eq 2 ] && grep -q "expected one of empty, shapes, .*, found 'test-abort'" err.txt &&
  ! grep -q "test-[a-z]*, " err.txt || fail "test scenes leak: $(cat err.txt)"
echo ok
