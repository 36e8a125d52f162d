#!/usr/bin/env bash
# Limits with one meaning each (issue 42): `timeout` is each trial's, its warm-up
# included (three trials that together take longer than it all finish; a warm-up longer
# than it is stopped, and the run's later trials are failed:not-run, saying why); and
# --smoke's draw_limit bounds the frames of a run of the heaviest built-in manifests,
# counted in frames.csv and meta.yaml rather than timed.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"

# a warm-up of 4 s: two trials take longer than the 7 s limit that each has alone (the
# slack of 3 s is the start-up's); the other run warms up for 30 s
cat > t.yaml <<'YAML'
shadesweep: 1
name: t
scene: empty
renderers: [null]
resolution: 16x16
trials: 2
duration: {frames: 2}
clock: fixed
timeout: 7
sweep:
  warmup: [{seconds: 4}, {seconds: 30}]
YAML
rc=0; "$SHADESWEEP" run t.yaml >t.out 2>t.err || rc=$?
[ $rc -eq 1 ] || fail "a sweep with a timed-out run exits 1, got $rc: $(cat t.err)"
"$PYTHON" - <<'PY' || fail "timeout rows"
import csv, sys
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
plan = {r["run_id"]: r["warmup"] for r in csv.DictReader(open("out/t/plan.csv"))}
rows = {(plan[r["run_id"]], r["trial"]): r for r in csv.DictReader(open("out/t/summary.csv"))}
for k in "12":
    r = rows[("seconds:4", k)]
    if r["status"] != "ok" or r["frames"] != "2" or r["message"]:
        fail(f"trial {k} of the quick run: {r['status']} {r['frames']} {r['message']}")
r = rows[("seconds:30", "1")]
if r["status"] != "failed:timeout" or r["frames"] != "0" or \
        "timeout: 7 s a trial, warm-up included" not in r["message"] or \
        not r["message"].startswith("stopped after 7."):
    fail(f"trial 1 of the slow warm-up: {r['status']} {r['message']}")
for k in "2":
    r = rows[("seconds:30", k)]
    want = ("not run: trial 1 was stopped by its limit (timeout: 7 s a trial, warm-up "
            "included), which ends the run")
    if r["status"] != "failed:not-run" or r["message"] != want or r["frames"] != "0":
        fail(f"trial {k} after the timeout: {r['status']} {r['message']}")
PY
grep -q "^run [0-9a-f]*: trial 1: stopped after 7\.[0-9] s: timeout: 7 s a trial, warm-up included" t.err \
  || fail "console: $(cat t.err)"
# timeout: 0 names the limit it computed

# --smoke on renderers-tiled (16,384 lights: seconds a frame at 160x120 on llvmpipe):
# its five priming frames and five measured ones took a minute; now the frames until
# 2 s are spent, then frame 4 (t = 2 s, the error and screenshot time: a fixed clock
# goes straight to it), no warm-up
"$SHADESWEEP" run --smoke -o tiled --renderer deferred --set lights.count=16384 \
  --set scene=shapes "$SOURCE_ROOT/experiments/renderers-tiled.yaml" >/dev/null 2>tiled.err \
  || fail "renderers-tiled --smoke: $(tail -5 tiled.err)"
# noise-aa (120 frames): 0.25 s of CPU a measured frame stops it after at most 9
"$SHADESWEEP" run --smoke -o noise --renderer deferred --set debug.busy_us=250000 \
  "$SOURCE_ROOT/experiments/noise-aa.yaml" >/dev/null 2>noise.err \
  || fail "noise-aa --smoke: $(tail -5 noise.err)"
"$PYTHON" - <<'PY' || fail "smoke frames"
import csv, glob, os, sys
import yaml
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
def one(out):
    plan = list(csv.DictReader(open(f"{out}/plan.csv")))
    summ = list(csv.DictReader(open(f"{out}/summary.csv")))
    if len(plan) != 1 or len(summ) != 1 or summ[0]["status"] != "ok":
        fail(f"{out}: {[(s['status'], s['message']) for s in summ]}")
    if plan[0]["warmup"] != "frames:0" or plan[0]["draw_limit"] != "2":
        fail(f"{out}: warm-up {plan[0]['warmup']}, draw_limit {plan[0]['draw_limit']}")
    d = f"{out}/runs/{plan[0]['run_id']}"
    meta = yaml.safe_load(open(glob.glob(f"{d}/trial-1/meta.yaml")[0]
                               if os.path.exists(f"{d}/trial-1") else f"{d}/meta.yaml"))
    frames = list(csv.DictReader(open(f"{d}/frames.csv")))
    return meta["timing"], [int(f["frame"]) for f in frames], [float(f["t_wall_s"]) for f in frames], summ[0]
# every frame but the last (and the capture's) began before the 2 s of frames were spent
tm, frames, ends, s = one("tiled")
if not 1 <= tm["prime_frames"] <= 5 or frames[-1] != 4 or len(frames) > 5 or \
        s["image_rmse"] == "" or any(tm["prime_s"] + e >= 2 for e in ends[:-2]):
    fail(f"renderers-tiled: {tm['prime_frames']} priming frames, measured {frames} ending "
         f"{ends}, rmse {s['image_rmse']}")
tm, frames, ends, s = one("noise")
if not 1 <= len(frames) <= 9 or frames != list(range(len(frames))) or tm["prime_frames"] > 5 or \
        any(tm["prime_s"] + e >= 2 for e in ends[:-1]):
    fail(f"noise-aa: {tm['prime_frames']} priming frames in {tm['prime_s']} s, frames {frames} ending {ends}")
PY
echo ok
