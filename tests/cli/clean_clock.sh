#!/usr/bin/env bash
# A clean clock (issue 15, item 4): every run draws primed frames over its schedule
# before the first trial (meta.yaml timing.prime_*), and comparisons with the reference
# run with the measured clock paused. Two runs, one with five error.at comparisons and
# one without, must both give fps_mean = 1e6 / frametime_mean_us within 1% (the
# harness, a few CSV rows a frame, costs well under 1% of these 192x144 frames of 64
# lights, even in the sanitizer build), measured_s = frames x (frametime +
# harness) by construction, per-second bins that count exactly the frames that ended
# in them, a schedule time (clock: wall) equal to each frame's start on the measured
# clock, and no comparison's cost (nor the first frame's coverage check) between the
# frame it compared and the next one.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
for e in none five; do
  cat > $e.yaml <<YAML
shadesweep: 1
name: $e
scene: shapes
renderers: [deferred]
resolution: 192x144
duration: {seconds: 2}
lights: {count: 64, radius: 8, attenuation: linear-range}
YAML
  [ $e = five ] && cat >> $e.yaml <<'YAML'
error:
  reference: {renderer: forward-spml}
  at: [0.1, 0.4, 0.7, 1.1, 1.3]
  save_images: true
YAML
  "$SHADESWEEP" run -o out/$e $e.yaml >out.txt 2>err.txt || fail "$e: $(cat err.txt)"
done
"$PYTHON" - <<'PY'
import csv, glob, math, sys, yaml
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
for name, ncomp in (("none", 0), ("five", 5)):
    [d] = glob.glob(f"out/{name}/runs/*/")
    [s] = list(csv.DictReader(open(d + "summary.csv")))
    meta = yaml.safe_load(open(d + "meta.yaml"))
    tm = meta["timing"]
    # primed: five frames over the schedule (0, 0.5 .. 2 s) plus one at each comparison's time
    if tm["prime_frames"] != 5 + ncomp: fail(f"{name}: prime_frames {tm['prime_frames']}")
    if not tm["prime_s"] > 0: fail(f"{name}: prime_s {tm['prime_s']}")
    # paused: the first measured frame's coverage check, and each comparison
    if not tm["paused_s"] > 0: fail(f"{name}: paused_s {tm['paused_s']}")
    n = int(s["frames"]); ft = float(s["frametime_mean_us"]); fps = float(s["fps_mean"])
    measured = float(s["measured_s"]); harness = float(s["harness_us_mean"])
    if abs(fps * ft / 1e6 - 1) > 0.01:
        fail(f"{name}: fps_mean {fps} vs 1e6 / frametime_mean_us {1e6 / ft}")
    if abs(measured * 1e6 / n / (ft + harness) - 1) > 1e-3:
        fail(f"{name}: measured_s {measured} != {n} x ({ft} + {harness}) us")
    frames = list(csv.DictReader(open(d + "frames.csv")))
    if len(frames) != n: fail(f"{name}: {len(frames)} rows in frames.csv")
    tw = [float(f["t_wall_s"]) for f in frames]
    fts = [float(f["frametime_us"]) / 1e6 for f in frames]
    gaps = [tw[k] - fts[k] - (tw[k - 1] if k else 0) for k in range(n)]
    for k, f in enumerate(frames):
        # clock: wall: a frame is drawn at its start on the measured clock
        if abs(float(f["t_scene_s"]) - (tw[k] - fts[k])) > 3e-6:
            fail(f"{name}: frame {k}: t_scene_s {f['t_scene_s']} is not its start {tw[k] - fts[k]}")
        if gaps[k] < -3e-6: fail(f"{name}: frame {k} starts before the last one ended")
    bins = list(csv.DictReader(open(d + "seconds.csv")))
    if [b["second"] for b in bins] != ["0", "1", "2"]: fail(f"{name}: seconds {bins}")
    if [b["complete"] for b in bins] != ["1", "1", "0"]: fail(f"{name}: complete flags")
    for b in bins:
        sec = int(b["second"])
        want = sum(1 for t in tw if math.floor(t) == sec)
        if int(b["frames"]) != want: fail(f"{name}: second {sec}: {b['frames']} frames, frames.csv has {want}")
    if name == "none" and n > 1 and gaps[1] > tm["paused_s"] / 4:
        fail(f"the coverage check ({tm['paused_s'] * 1e3:.2f} ms paused) left "
             f"{gaps[1] * 1e3:.3f} ms on the measured clock")
    if name == "five":
        errs = list(csv.DictReader(open(d + "errors.csv")))
        if len(errs) != 5: fail(f"{len(errs)} comparisons")
        per = tm["paused_s"] / 5
        for e in errs:
            k = int(e["frame"])
            if k + 1 < n and gaps[k + 1] > per / 4:
                fail(f"the comparison at frame {k} ({per * 1e3:.2f} ms paused) left "
                     f"{gaps[k + 1] * 1e3:.3f} ms on the measured clock")
PY
echo ok
