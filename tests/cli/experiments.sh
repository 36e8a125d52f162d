#!/usr/bin/env bash
# The smoke variant (`run --smoke`: 160x120, one trial, at most 2 s a run) of every
# reproduction manifest under experiments/ (issue 4), with a debug context, then what
# each must show: every run ok, the paper's structure in the numbers (shadow passes
# only where lights cast shadows, coverage small then full, the stencil masks' draw
# calls), and scripts/report over them all; draw_limit lifted (the frame counts the checks
# compare must not depend on the machine's load). The G-buffer study (issue 5, 120 runs) is
# tests/cli/gbuffer_error.sh: one shard of it, in parallel with this one.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
manifests=(s003-exp1 s003-exp2 s000-resolution s000-drawcalls s000-spot-coverage
           s000-two-spots s000-stencil s000-illumination-sets)
for m in "${manifests[@]}"; do
  # 4 frames a run (a smoke run draws 2 s or 120 frames): the checks below compare work
  # per frame and the values of every frame drawn, which 4 frames hold as well; seed 003's
  # experiment 2 keeps its 2 s, as its check reads the lights of its second second
  short=(--set 'duration={frames: 4}')
  [ "$m" = s003-exp2 ] && short=()
  if ! "$SHADESWEEP" run --smoke --debug-gl --set draw_limit=3600 "${short[@]}" \
       --out "out/$m-smoke" "$SOURCE_ROOT/experiments/$m.yaml" >"$m.out" 2>"$m.err"; then
    tail -n 30 "$m.err" >&2
    fail "$m --smoke exited non-zero"
  fi
done

"$PYTHON" - out <<'PY'
import csv, os, sys
import yaml
out = sys.argv[1]
def fail(msg):
    print("FAIL:", msg, file=sys.stderr); sys.exit(1)
def table(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))
def runs(exp):
    """plan rows (every parameter of each run) by run id, and summary rows."""
    d = os.path.join(out, exp + "-smoke")
    plan = {p["run_id"]: p for p in table(os.path.join(d, "plan.csv"))}
    summ = table(os.path.join(d, "summary.csv"))
    for s in summ:
        if s["status"] != "ok":
            fail(f"{exp}: run {s['run_id']} {s['status']} {s['message']}")
        if s["width"] != "160" or s["height"] != "120" or s["trial"] != "1":
            fail(f"{exp}: not a smoke run: {s['width']}x{s['height']} trial {s['trial']}")
    with open(os.path.join(d, "sweep.yaml")) as f:
        sw = yaml.safe_load(f)
    if sw["experiment"] != exp + "-smoke" or sw["smoke"] is not True:
        fail(f"{exp}: sweep.yaml {sw}")
    return d, plan, summ
def passes(d, run_id):
    """pass name -> total draw calls over the run's frames, and the frame count."""
    rows = table(os.path.join(d, "runs", run_id, "passes.csv"))
    tot, frames = {}, set()
    for r in rows:
        tot[r["pass"]] = tot.get(r["pass"], 0) + int(r["draw_calls"])
        frames.add(r["frame"])
    return tot, len(frames)

# seed 003: three scenes x two renderers; 160 lights; growth reaches 10 a second
d, plan, summ = runs("s003-exp1")
if sorted({(p["scene"], p["renderer"]) for p in plan.values()}) != sorted(
        (s, r) for s in ("curtis-scene1", "curtis-scene2", "curtis-scene3")
        for r in ("deferred", "forward-spml")):
    fail(f"s003-exp1 plan {plan}")
if any(s["lights_count"] != "160" for s in summ):
    fail("s003-exp1: not 160 lights")
d, plan, summ = runs("s003-exp2")
for rid in plan:
    secs = table(os.path.join(d, "runs", rid, "seconds.csv"))
    if secs[0]["lights_min"] != "0" or int(secs[-1]["lights_max"]) not in (10, 20):
        fail(f"s003-exp2: lights per second {[(s['lights_min'], s['lights_max']) for s in secs]}")

# seed 000 draw calls: shadow passes on the interior only when shadows are on; the
# canyon's sun casts none, so auto and off draw the same. forward-mpml with the
# directional lights in its base pass: the same base draws, the lights pass less the
# directional lights' V each (the canyon: no lights pass at all)
d, plan, summ = runs("s000-drawcalls")
dc, base = {}, {}
for rid, p in plan.items():
    tot, n = passes(d, rid)
    if p["forward.directional_in_base"] == "true":
        base[(p["scene"], p["shadows"])] = (tot, n)
    else:
        dc[(p["scene"], p["shadows"], p["renderer"])] = (tot, n)
if sorted(base) != sorted((s, h) for s in ("canyon", "interior") for h in ("auto", "off")):
    fail(f"s000-drawcalls: folded runs {sorted(base)}")
for (scene, sh), (tot, n) in base.items():
    own, n2 = dc[(scene, sh, "forward-mpml")]
    if n != n2 or tot.get("base") != own.get("base") or tot.get("shadows") != own.get("shadows"):
        fail(f"{scene} {sh}: directional_in_base {tot}, own passes {own}")
    if scene == "canyon" and ("lights" in tot or own["lights"] != own["base"]):
        fail(f"canyon {sh}: directional_in_base {tot}, own passes {own}")
    if scene == "interior" and not 0 < tot["lights"] < own["lights"]:
        fail(f"interior {sh}: directional_in_base {tot}, own passes {own}")
for r in ("deferred", "forward-mpml"):
    on, off = dc[("interior", "auto", r)][0], dc[("interior", "off", r)][0]
    if not on.get("shadows") or off.get("shadows"):
        fail(f"interior {r}: shadow draw calls on {on.get('shadows')} off {off.get('shadows')}")
    if sum(v for k, v in on.items() if k != "shadows") != sum(off.values()):
        fail(f"interior {r}: the passes other than shadows differ with shadows on: {on} {off}")
    if dc[("canyon", "auto", r)][0] != dc[("canyon", "off", r)][0] or \
       dc[("canyon", "auto", r)][0].get("shadows"):
        fail(f"canyon {r}: {dc[('canyon', 'auto', r)]} {dc[('canyon', 'off', r)]}")

# seed 000 coverage scenes: coverage.csv per run; hold 1 is full screen, hold 0 is not
for exp, nlights in (("s000-spot-coverage", 1), ("s000-two-spots", 2)):
    d, plan, summ = runs(exp)
    for rid, p in plan.items():
        cov = table(os.path.join(d, "runs", rid, "coverage.csv"))
        lights = {c["light"] for c in cov}
        if lights != {str(i) for i in range(nlights)}:
            fail(f"{exp}: coverage lights {lights}")
        vals = [float(c["coverage"]) for c in cov]
        if p["camera.hold"] == "1" and min(vals) < 0.999:
            fail(f"{exp}: hold 1 coverage {min(vals)}")
        if p["camera.hold"] == "0" and max(vals) > 0.8:
            fail(f"{exp}: hold 0 coverage {max(vals)}")

# seed 000 5.5: the floating spot: two stencil draws + one light draw a frame with the
# two-pass mask (the paper counts the two mask passes), one with the others (hull, the
# paper's unmasked baseline, and scissor among them)
d, plan, summ = runs("s000-stencil")
want = {"stencil-two-pass": 3, "stencil": 2, "volume": 1, "fullscreen": 1, "hull": 1,
        "scissor": 1}
for rid, p in plan.items():
    tot, n = passes(d, rid)
    mode = p["deferred.light_volumes"]
    if tot.get("spot", 0) != want[mode] * n:
        fail(f"s000-stencil {mode}: spot pass {tot.get('spot')} draw calls in {n} frames")

d, plan, summ = runs("s000-illumination-sets")
dcs = {plan[s["run_id"]]["forward.illumination_sets"]: float(s["draw_calls_mean"]) for s in summ}
if not dcs["true"] < dcs["false"]:
    fail(f"illumination sets do not save draw calls: {dcs}")

runs("s000-resolution")
print("experiments: ok")
PY

# The report over all of them (skipped, not failed, where matplotlib is missing)
if "$PYTHON" -c 'import matplotlib' 2>/dev/null; then
  "$SOURCE_ROOT/scripts/report" out >report.out 2>report.err \
    || { cat report.err >&2; fail "scripts/report exited non-zero"; }
  [ -s out/report.md ] || fail "no out/report.md"
  for m in s003-exp1 s000-drawcalls s000-stencil; do
    grep -q "$m" out/report.md || fail "report.md does not mention $m"
  done
fi
echo "experiments: ok"
