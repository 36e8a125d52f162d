#!/usr/bin/env bash
# The bound of every run (issue 38, item 2). A tiny sweep with no profile cached: its
# summary.csv's bound_us, limiter and bound_pct are empty and summary.md says why in one
# line; after `probe --quick`, the next sweep's summary.csv has them for every ok trial
# (bound_pct = 100 x bound_us / frametime_mean_us) and summary.md lists each run's bound
# and names every run whose bound is above its measured time as a model error; each row of
# its passes.csv has the pass's bound_us and limiter (bound_pct empty: llvmpipe's pass
# times are not the passes'), empty in the first sweep's; `bound --passes` bounds each
# pass of an existing folder the same way. Over the committed llvmpipe folders (their
# device.yaml: a full probe of this device), `shadesweep bound` flags exactly the runs
# whose bound is above the measured time, and names bytes or fill, not draws, the limiter
# of deferred `volume` at 4,096 lights; with the quick profile of this machine, the same
# holds of the flags. Seconds: one probe --quick, two runs of 2 frames, committed data.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat >tiny.yaml <<'YAML'
shadesweep: 1
name: tiny
scene: shapes
renderers: [deferred, forward-plus]
resolution: 32x24
lights: {count: 4}
trials: 1
warmup: {frames: 0}
duration: {frames: 2}
clock: fixed
outputs: {seconds: false}
YAML

"$SHADESWEEP" run -o none tiny.yaml >run.out 2>run.err || fail "run: $(cat run.err)"
grep -q '^no device profile of .* cached' run.err || fail "no line on the profile: $(cat run.err)"
grep -qF 'No bound: this folder has no profile of the hardware it ran on (`shadesweep probe`' none/summary.md ||
  fail "summary.md: no line on the missing profile"

"$SHADESWEEP" probe --quick >quick.yaml 2>probe.err || fail "probe: $(cat probe.err)"
"$SHADESWEEP" run -o with tiny.yaml >run2.out 2>run2.err || fail "run: $(cat run2.err)"

"$PYTHON" - <<'PY' || fail "the bound columns"
import csv, glob, math, re
names = {"bytes", "fill", "alu", "draws", "dispatches"}
for r in csv.DictReader(open("none/summary.csv")):
    assert (r["bound_us"], r["limiter"], r["bound_pct"]) == ("", "", ""), r
md = open("with/summary.md").read()
sec = md[md.index("## Bounds"):md.index("## Warnings")]
rows = list(csv.DictReader(open("with/summary.csv")))
assert rows and all(r["status"] == "ok" for r in rows), rows
for r in rows:
    b, m, p = float(r["bound_us"]), float(r["frametime_mean_us"]), float(r["bound_pct"])
    assert b > 0 and r["limiter"] in names, r
    assert abs(p - 100 * b / m) <= 0.05 + 1e-3 * p, r
    assert f"| {r['run_id']} | {r['renderer']} |" in sec, (r["run_id"], sec)
    named = f"model error: run {r['run_id']} ({r['renderer']})" in sec
    assert named == (b > m), (r, sec)   # above the measured time: named, never hidden
assert ("Model errors: none" in sec) == all(float(r["bound_us"]) <= float(r["frametime_mean_us"])
                                              for r in rows), sec
# passes.csv: the bound of each pass, written by the trial from the cached profile
for folder, cached in (("none", False), ("with", True)):
    for f in glob.glob(folder + "/runs/*/passes.csv"):
        prows = list(csv.DictReader(open(f)))
        assert list(prows[0])[-3:] == ["bound_us", "limiter", "bound_pct"], f
        for r in prows:
            assert r["bound_pct"] == "" and (r["gpu_us_attributed"] == "0"), r
            if not cached:
                assert (r["bound_us"], r["limiter"]) == ("", ""), r
                continue
            assert float(r["bound_us"]) >= 0 and r["limiter"] in names, r
PY

# per pass: a row for each run and pass of passes.csv, model errors flagged the same way
"$SHADESWEEP" bound --passes with >passes.csv 2>passes.err || fail "bound --passes: $(cat passes.err)"
"$PYTHON" - <<'PY' || fail "bound --passes"
import csv, glob
rows = list(csv.DictReader(open("passes.csv")))
want = set()
for f in glob.glob("with/runs/*/passes.csv"):
    want |= {(r["run_id"], r["pass"]) for r in csv.DictReader(open(f))}
assert {(r["run_id"], r["pass"]) for r in rows} == want and len(rows) == len(want), rows
for r in rows:
    assert r["limiter"] in ("fill", "draws", "dispatches") and r["attributed"] == "0", r
    assert (r["model_error"] == "yes") == (float(r["bound_us"]) > float(r["measured_us"])), r
PY

# the committed folders, by their own device.yaml and by this machine's quick profile
D=$SOURCE_ROOT/docs/results/2026-12-03-llvmpipe/data
for f in renderers-tiled renderers-tiled-volumes; do
  "$SHADESWEEP" bound "$D/$f" >"$f.csv" 2>"$f.err" || fail "bound $f: $(cat "$f.err")"
  "$SHADESWEEP" bound --profile quick.yaml "$D/$f" >"$f-quick.csv" 2>"$f-quick.err" ||
    fail "bound --profile $f: $(cat "$f-quick.err")"
done
"$PYTHON" - "$D" <<'PY' || fail "the committed folders' bounds"
import csv, sys
D = sys.argv[1]
def check(path):
    rows = list(csv.DictReader(open(path)))
    for r in rows:
        if not r["bound_us"]:
            assert not r["measured_us"], r   # only a run with no ok trial has none
            continue
        above = float(r["bound_us"]) > float(r["measured_us"])
        assert (r["model_error"] == "yes") == above, r
    return {r["run_id"]: r for r in rows}
for f in ("renderers-tiled", "renderers-tiled-volumes"):
    check(f + "-quick.csv")
    b = check(f + ".csv")
    plan = list(csv.DictReader(open(f"{D}/{f}/plan.csv")))
    vol = [p["run_id"] for p in plan if p["renderer"] == "deferred"
           and p["deferred.light_volumes"] == "volume" and p["lights.count"] == "4096"]
    for i in vol:
        assert b[i]["limiter"] in ("bytes", "fill"), b[i]
    assert vol or f == "renderers-tiled-volumes", f
    # issue 38's check: by the folder's own profile every bound is at most its run's time
    errors = [i for i, r in b.items() if r["model_error"] == "yes"]
    assert not errors, (f, [(b[i]["renderer"], b[i]["bound_pct"]) for i in errors])
    print(f, len(b), "runs, no model error; deferred volume at 4,096 lights:",
          [b[i]["limiter"] for i in vol])
PY

expect 2 "shadesweep bound: expected an output folder" "$SHADESWEEP" bound
expect 2 "no-such.yaml" "$SHADESWEEP" bound --profile no-such.yaml "$D/renderers-tiled"
expect 0 "shadesweep bound: none: No bound: this folder has no profile" "$SHADESWEEP" bound none
echo ok
