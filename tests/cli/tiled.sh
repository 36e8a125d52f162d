#!/usr/bin/env bash
# The tiled and clustered renderers end to end (issue 10): the manifest keys, the new
# columns of summary.csv and passes.csv, lightgrid.csv for the screenshot frames, the
# plan in meta.yaml, and a frame whose light lists do not fit failing the run as
# failed:overflow with the numbers in its message (the sweep goes on, exit status 1).
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat >tiled.yaml <<'YAML'
shadesweep: 1
name: tiled
scene: shapes
renderers: [forward-plus, clustered, tiled-deferred, forward-spml]
resolution: 64x48
duration: {frames: 3}
clock: fixed
step: 0.25
forward: {light_buffer: storage}
tiles: {size: 8}
clustered: {slices: 16, shading: forward}
lights: {placement: random, count: 900, radius: 4}
outputs: {screenshots: [0.25]}
error: {reference: {renderer: forward-spml}, at: [0.25], max_rmse: 0.004}
YAML
"$SHADESWEEP" run --debug-gl tiled.yaml >run.out 2>run.err || { cat run.err >&2; fail "tiled run exited $?"; }
cat >overflow.yaml <<'YAML'
shadesweep: 1
name: overflow
scene: shapes
renderers: [forward-plus, null]
resolution: 64x48
duration: {frames: 2}
clock: fixed
lights: {placement: random, count: 64, radius: 30}
sweep: {tiles.max_lights_per_tile: [0, 1]}
YAML
if "$SHADESWEEP" run --debug-gl overflow.yaml >ov.out 2>ov.err; then
  fail "a run whose light lists overflow exited 0"
fi
"$PYTHON" - <<'PY'
import csv, glob, os, sys
import yaml
def fail(msg):
    print("FAIL:", msg, file=sys.stderr); sys.exit(1)
def table(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))
plan = {p["run_id"]: p for p in table("out/tiled/plan.csv")}
for s in table("out/tiled/summary.csv"):
    r = s["renderer"]
    if s["status"] != "ok":
        fail(f"{r}: {s['status']} {s['message']}")
    if float(s["image_rmse"] or "nan") > 0.004 and r != "forward-spml":
        fail(f"{r}: rmse {s['image_rmse']}")
    run = os.path.join("out/tiled/runs", s["run_id"])
    meta = yaml.safe_load(open(os.path.join(run, "meta.yaml")))
    passes = {p["name"]: p for p in meta["pass_plan"]["passes"]}
    grid = os.path.join(run, "lightgrid.csv")
    # seed 002's G-buffer traffic: tiled-deferred writes bpp x the G-buffer pass's samples
    # and its one compute pass reads every pixel once (bpp x 64 x 48 = gbuffer_bytes);
    # the forward renderers (clustered shades forward here) have none: empty
    fr, pa = table(os.path.join(run, "frames.csv")), table(os.path.join(run, "passes.csv"))
    for f in fr:
        gb = [f[k] for k in ("gbuffer_bytes_per_frame", "gbuffer_write_bytes", "gbuffer_read_bytes")]
        if r != "tiled-deferred":
            if gb != ["", "", ""]: fail(f"{r}: G-buffer traffic {gb}")
            continue
        bpp = int(s["gbuffer_bytes"]) // (64 * 48)
        w = bpp * sum(int(p["samples"]) for p in pa
                      if (p["trial"], p["frame"], p["pass"]) == (f["trial"], f["frame"], "gbuffer"))
        if bpp <= 0 or [int(x) for x in gb] != [w + int(s["gbuffer_bytes"]), w, int(s["gbuffer_bytes"])]:
            fail(f"tiled-deferred: G-buffer traffic {gb}, {bpp} B per pixel")
    if r == "forward-spml":
        if s["dispatches_mean"] != "0.000" or s["cell_lights_mean"] != "":
            fail(f"forward-spml: dispatches {s['dispatches_mean']} cells {s['cell_lights_mean']}")
        if os.path.exists(grid):
            fail("forward-spml wrote lightgrid.csv")
        continue
    # files.txt vouches for it (a name folder.c did not know was left out, and so
    # survived --force and reruns from an older sweep)
    if "lightgrid.csv" not in open(os.path.join(run, "files.txt")).read():
        fail(f"{r}: files.txt does not list lightgrid.csv")
    if s["dispatches_mean"] != "1.000":
        fail(f"{r}: dispatches_mean {s['dispatches_mean']}")
    if not s["cell_lights_mean"] or not s["cell_lights_max"] or not s["light_evals_per_pixel"]:
        fail(f"{r}: grid columns empty: {s}")
    if float(s["light_evals_per_pixel"]) <= 0:
        fail(f"{r}: evals {s['light_evals_per_pixel']}")
    cull = "tiled" if r == "tiled-deferred" else "cull"
    if not passes.get(cull, {}).get("run"):
        fail(f"{r}: plan {passes}")
    rows = table(os.path.join(run, "passes.csv"))
    built = [p for p in rows if p["cell_lights_mean"] != ""]
    if len(built) != 3 or any(p["pass"] != cull or p["dispatches"] != "1" for p in built):
        fail(f"{r}: passes.csv grid rows {built}")
    g = table(grid)
    cells = sum(int(x["cells"]) for x in g)
    lengths = [int(x["lights"]) for x in g]
    # the screenshot frame's histogram: its longest list is that frame's passes.csv max
    shot = [p for p in built if p["frame"] == g[0]["frame"]] if g else []
    if not g or lengths != sorted(set(lengths)) or len(shot) != 1 or \
            max(lengths) != int(shot[0]["cell_lights_max"]) or \
            int(float(s["cell_lights_max"])) < max(lengths):
        fail(f"{r}: lightgrid.csv {g[:5]}")
    # 64x48 in 8 px tiles: 8 x 6 tiles (clustered: times its slices)
    if r != "clustered" and cells != 48:
        fail(f"{r}: lightgrid.csv covers {cells} cells, want 48")
    if r == "clustered" and (cells % 48 or cells <= 48):
        fail(f"clustered: lightgrid.csv covers {cells} cells")
ov = {(p["renderer"], p["tiles.max_lights_per_tile"]): p["run_id"] for p in table("out/overflow/plan.csv")}
rows = {s["run_id"]: s for s in table("out/overflow/summary.csv")}
bad = rows[ov[("forward-plus", "1")]]
if bad["status"] != "failed:overflow" or "the tiles' light lists need" not in bad["message"] \
        or "the index buffer holds 12; tile " not in bad["message"]:
    fail(f"overflow: {bad['status']} {bad['message']}")
# null reads no tiles.* key: its two points are one run (plan.csv's folded column)
if ("null", "1") in ov or table("out/overflow/plan.csv")[1]["folded"] != "1":
    fail(f"the null runs were not folded: {ov}")
for k in (("forward-plus", "0"), ("null", "0")):
    if rows[ov[k]]["status"] != "ok":
        fail(f"{k}: {rows[ov[k]]['status']} {rows[ov[k]]['message']}")
PY
echo "tiled: ok"
