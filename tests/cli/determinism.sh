#!/usr/bin/env bash
# issue 4's determinism: with `clock: fixed` two runs of the same manifest give
# bit-identical screenshots and identical work counts (per frame and per pass), and
# so do two trials of one run. Two manifests: seed 000's interior with its authored
# lights (shadow maps on) and seed 003's scene 3 with MSVC-rand lights seeded 1337
# growing every frame; every renderer family.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat >interior.yaml <<'YAML'
shadesweep: 1
name: det-interior
scene: interior
renderers: [deferred, forward-mpml, forward-spml, forward-plus, clustered, tiled-deferred,
            deferred-lighting]
resolution: 80x60
trials: 2
warmup: {frames: 1}
duration: {frames: 8}
clock: fixed
step: 0.25
lights: {placement: scene}
outputs: {screenshots: [0.5, 1.5]}
YAML
cat >growth.yaml <<'YAML'
shadesweep: 1
name: det-growth
scene: curtis-scene3
renderers: [deferred, forward-mpml, forward-spml, forward-plus, clustered, tiled-deferred,
            deferred-lighting]
resolution: 80x60
trials: 2
warmup: {frames: 1}
duration: {frames: 8}
clock: fixed
step: 0.25
lights: {placement: random, rng: msvc, seed: 1337, radius: 10,
         count: {start: 0, step: 10, every: 0.25, max: 100}}
outputs: {screenshots: [0.5, 1.5]}
YAML
for m in interior growth; do
  for k in a b; do
    "$SHADESWEEP" run --debug-gl --out "$k-$m" "$m.yaml" >/dev/null 2>"$k-$m.err" \
      || { cat "$k-$m.err" >&2; fail "$m run $k exited non-zero"; }
  done
done

"$PYTHON" - <<'PY'
import csv, glob, os, sys
def fail(msg):
    print("FAIL:", msg, file=sys.stderr); sys.exit(1)
def table(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))
WORK = {"frames.csv": ["trial", "frame", "t_scene_s", "lights", "draw_calls", "state_changes",
                       "fragments", "samples"],
        "passes.csv": ["trial", "frame", "pass", "draw_calls", "state_changes", "fragments",
                       "samples",
                       "primitives", "dispatches", "cell_lights_mean", "cell_lights_max",
                       "light_evals_per_pixel", "scissor_pixels"]}
for m in ("interior", "growth"):
    a, b = f"a-{m}", f"b-{m}"
    ids = sorted(os.listdir(os.path.join(a, "runs")))
    if len(ids) != 7 or ids != sorted(os.listdir(os.path.join(b, "runs"))):
        fail(f"{m}: runs {ids}")
    for s in table(os.path.join(a, "summary.csv")) + table(os.path.join(b, "summary.csv")):
        if s["status"] != "ok":
            fail(f"{m}: {s['run_id']} {s['status']} {s['message']}")
    for rid in ids:
        ra, rb = os.path.join(a, "runs", rid), os.path.join(b, "runs", rid)
        shots = sorted(os.path.basename(p)
                       for p in glob.glob(os.path.join(ra, "screenshot-*.png")))
        if len(shots) != 4:
            fail(f"{m} {rid}: screenshots {shots}")
        # the lights reaching each pixel (issue 36) are as deterministic as the frame
        heat = os.path.join(ra, "lights-heat-trial1.png")
        if os.path.exists(heat) and \
                open(heat, "rb").read() != open(os.path.join(rb, "lights-heat-trial1.png"), "rb").read():
            fail(f"{m} {rid}: the heat maps of the two folders differ")
        data = {}
        for name in shots:
            with open(os.path.join(ra, name), "rb") as f:
                x = f.read()
            with open(os.path.join(rb, name), "rb") as f:
                y = f.read()
            if x != y:
                fail(f"{m} {rid}: {name} differs between the two runs")
            data[name] = x
        # the trials agree too, and the scene moved between the two times
        if data["screenshot-trial1-t0.5.png"] != data["screenshot-trial2-t0.5.png"]:
            fail(f"{m} {rid}: trials 1 and 2 differ at t = 0.5")
        if data["screenshot-trial1-t0.5.png"] == data["screenshot-trial1-t1.5.png"]:
            fail(f"{m} {rid}: the same image at t = 0.5 and 1.5: nothing moved")
        # the tiled renderers' light-list histograms of the screenshot frames
        grid = os.path.join(ra, "lightgrid.csv")
        if os.path.exists(grid):
            ga, gb = table(grid), table(os.path.join(rb, "lightgrid.csv"))
            if not ga or [tuple(r.values())[1:] for r in ga] != [tuple(r.values())[1:] for r in gb]:
                fail(f"{m} {rid}: lightgrid.csv differs between the runs")
        for f, cols in WORK.items():
            ta, tb = table(os.path.join(ra, f)), table(os.path.join(rb, f))
            ka = [tuple(r[c] for c in cols) for r in ta]
            kb = [tuple(r[c] for c in cols) for r in tb]
            if not ka or ka != kb:
                fail(f"{m} {rid}: {f} work counts differ between the runs")
            t1 = [k[1:] for k in ka if k[0] == "1"]
            t2 = [k[1:] for k in ka if k[0] == "2"]
            if t1 != t2:
                fail(f"{m} {rid}: {f} work counts differ between trials 1 and 2")
        frames = table(os.path.join(ra, "frames.csv"))
        lights = [int(r["lights"]) for r in frames if r["trial"] == "1"]
        if m == "growth" and not (lights[0] < lights[-1] and lights == sorted(lights)):
            fail(f"growth {rid}: lights per frame {lights}")
        if m == "interior":
            if lights != [9] * 8:
                fail(f"interior {rid}: lights per frame {lights}")
            if not any(r["pass"] == "shadows" for r in table(os.path.join(ra, "passes.csv"))):
                fail(f"interior {rid}: no shadows pass")
print("determinism: ok")
PY
echo "determinism: ok"
