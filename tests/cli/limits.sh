#!/usr/bin/env bash
# Limits with one meaning each (issue 42): `timeout` is each trial's, its warm-up
# included (two trials that together take longer than it both finish; a warm-up longer
# than it is stopped, and the run's later trials are failed:not-run, saying why); and
# --smoke's draw_limit bounds the frames of a run of the heaviest built-in manifests,
# counted in frames.csv and meta.yaml rather than timed.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"

# a warm-up of 6 s: two trials take longer than the 10 s limit that each has alone (the
# slack of 4 s is the start-up's, on a loaded sanitizer build too); the other run warms
# up for 30 s
cat > t.yaml <<'YAML'
shadesweep: 1
name: t
scene: empty
renderers: [null]
resolution: 16x16
trials: 2
duration: {frames: 2}
clock: fixed
timeout: 10
sweep:
  warmup: [{seconds: 6}, {seconds: 30}]
YAML
rc=0; "$SHADESWEEP" run t.yaml >t.out 2>t.err || rc=$?
[ $rc -eq 1 ] || fail "a sweep with a timed-out run exits 1, got $rc: $(cat t.err)"
"$PYTHON" - <<'PY' || fail "timeout rows"
import csv, sys
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
plan = {r["run_id"]: r["warmup"] for r in csv.DictReader(open("out/t/plan.csv"))}
rows = {(plan[r["run_id"]], r["trial"]): r for r in csv.DictReader(open("out/t/summary.csv"))}
for k in "12":
    r = rows[("seconds:6", k)]
    if r["status"] != "ok" or r["frames"] != "2" or r["message"]:
        fail(f"trial {k} of the quick run: {r['status']} {r['frames']} {r['message']}")
r = rows[("seconds:30", "1")]
if r["status"] != "failed:timeout" or r["frames"] != "0" or \
        "timeout: 10 s a trial, warm-up included" not in r["message"] or \
        not r["message"].startswith("stopped after 10."):
    fail(f"trial 1 of the slow warm-up: {r['status']} {r['message']}")
for k in "2":
    r = rows[("seconds:30", k)]
    want = ("not run: trial 1 was stopped by its limit (timeout: 10 s a trial, warm-up "
            "included), which ends the run")
    if r["status"] != "failed:not-run" or r["message"] != want or r["frames"] != "0":
        fail(f"trial {k} after the timeout: {r['status']} {r['message']}")
PY
grep -q "^run [0-9a-f]*: trial 1: stopped after 10\.[0-9] s: timeout: 10 s a trial, warm-up included" t.err \
  || fail "console: $(cat t.err)"
# draw_limit with a screenshot left: a fixed clock goes straight to the frame that
# takes it (t = 4 s: frame 40), after the frames (0.2 s of CPU each) that fit 0.5 s
cat > d.yaml <<'YAML'
shadesweep: 1
name: d
scene: empty
renderers: [null]
resolution: 16x16
duration: {frames: 50}
clock: fixed
step: 0.1
draw_limit: 0.5
debug: {busy_us: 200000}
outputs: {screenshots: [4]}
YAML
"$SHADESWEEP" run d.yaml >/dev/null 2>d.err || fail "draw_limit with a screenshot: $(cat d.err)"
ls out/d/runs/*/screenshot-trial1-t4.png >/dev/null || fail "no screenshot at t = 4"
"$PYTHON" - <<'PY' || fail "draw_limit frames"
import csv, glob
frames = [int(r["frame"]) for r in csv.DictReader(open(glob.glob("out/d/runs/*/frames.csv")[0]))]
if frames[-1] != 40 or not 1 <= len(frames) - 1 <= 3 or frames[:-1] != list(range(len(frames) - 1)):
    raise SystemExit(f"FAIL: frames {frames}")
PY

# --smoke on the heaviest manifest, renderers-tiled-volumes (at 16,384 lights its
# fullscreen frames take 30 s each on llvmpipe: five priming frames and five measured
# ones were minutes; here 1,024 lights, a second or two a frame): the frames stop once
# 2 s are spent, priming included, and there is no warm-up
"$SHADESWEEP" run --smoke -o vol --set lights.count=1024 --set scene=curtis-scene3 \
  --set deferred.light_volumes=fullscreen "$SOURCE_ROOT/experiments/renderers-tiled-volumes.yaml" \
  >/dev/null 2>vol.err || fail "renderers-tiled-volumes --smoke: $(tail -5 vol.err)"
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
# every frame but the last began before the 2 s of frames were spent
tm, frames, ends, s = one("vol")
if not 1 <= tm["prime_frames"] <= 5 or not 1 <= len(frames) <= 5 or \
        frames != list(range(len(frames))) or any(tm["prime_s"] + e >= 2 for e in ends[:-1]):
    fail(f"renderers-tiled-volumes: {tm['prime_frames']} priming frames in {tm['prime_s']} s, "
         f"frames {frames} ending {ends}")
tm, frames, ends, s = one("noise")
if not 1 <= len(frames) <= 9 or frames != list(range(len(frames))) or tm["prime_frames"] > 5 or \
        any(tm["prime_s"] + e >= 2 for e in ends[:-1]):
    fail(f"noise-aa: {tm['prime_frames']} priming frames in {tm['prime_s']} s, frames {frames} ending {ends}")
PY
echo ok
