#!/usr/bin/env bash
# A file's own camera in every renderer (issue 36): 2CylinderEngine's camera gives near
# 0.05 and far 1e6 (0.0012 and 23,922 once fit), which cut into 1,282 depth slices made
# every clustered run fail. Its planes are fitted to the model in front of it (27.97 to
# 49.92: 45 slices), every renderer's run ends ok, and meta.yaml records the file's
# planes and the planes used. 64x48, one frame, four lights: the smallest run that
# builds every renderer's passes over the file's camera.
. "$(dirname "$0")/lib.sh"
G=/usr/share/assimp/models/glTF2
[ -d "$G" ] || { echo "SKIP: assimp-testmodels is not installed (scripts/setup.sh installs it)" >&2; exit 77; }
need_gl
cd "$T"
cat >engine.yaml <<YAML
shadesweep: 1
name: file-camera
scene: {file: $G/2CylinderEngine-glTF-Binary/2CylinderEngine.glb}
renderers: [deferred, forward-mpml, forward-spml, forward-plus, tiled-deferred, clustered,
            deferred-lighting, visibility]
resolution: 64x48
trials: 1
warmup: {frames: 0}
duration: {frames: 1}
clock: fixed
lights: {placement: random, count: 4}
sweep: {clustered.shading: [forward, deferred]}
YAML
"$SHADESWEEP" run engine.yaml -o out >run.txt 2>&1 || fail "run engine.yaml: $(tail -5 run.txt)"
$PYTHON - out <<'PY'
import csv, sys, yaml
d = sys.argv[1]
runs = []
for r in csv.DictReader(open(f"{d}/summary.csv")):
    m = yaml.safe_load(open(f"{d}/runs/{r['run_id']}/meta.yaml"))
    runs.append((m["parameters"]["renderer"], m["parameters"]["clustered.shading"], m))
want = {("deferred", "forward"), ("forward-mpml", "forward"), ("forward-spml", "forward"),
        ("forward-plus", "forward"), ("tiled-deferred", "forward"), ("clustered", "forward"),
        ("clustered", "deferred"), ("deferred-lighting", "forward"), ("visibility", "forward")}
if {(r, s) for r, s, _ in runs} != want or len(runs) != len(want):
    sys.exit(f"FAIL: runs {sorted((r, s) for r, s, _ in runs)}")
for r, s, m in runs:
    if m["status"] != "ok":
        log = open(f"{d}/runs/{m['run_id']}/log.txt").read()
        sys.exit(f"FAIL: {r} ({s}): {m['status']}: {log}")
    sf = m["scene_file"]
    # the file's planes times fit's scale; those used hold the model 28 to 47.5 in front
    planes = sf["camera_planes"]
    if (sf["view"] != "the file's camera 'nodes[81]'"
            or planes["file"] != [0.0011960997944697738, 23921.998046875]
            or planes["used"] != [27.971445083618164, 49.921260833740234]):
        sys.exit(f"FAIL: {r}: {sf['view']}, planes {planes}")
    if r == "clustered":   # 45 slices of 4x3 tiles of 16 px, in its cull (or tiled) pass
        if not any("4x3x45 clusters" in p["reason"] for p in m["pass_plan"]["passes"]):
            sys.exit(f"FAIL: clustered ({s}): {m['pass_plan']['passes']}")
PY
# camera.near and camera.far still decide where a manifest gives them
"$SHADESWEEP" run engine.yaml -o near --renderer clustered --set clustered.shading=forward \
  --set camera.near=30 --set camera.far=40 >run.txt 2>&1 || fail "run with camera.near: $(tail -5 run.txt)"
$PYTHON - near <<'PY' || fail "camera.near and far are not the planes used"
import glob, sys, yaml
(f,) = glob.glob(f"{sys.argv[1]}/runs/*/meta.yaml")
m = yaml.safe_load(open(f))
if m["status"] != "ok" or m["scene_file"]["camera_planes"]["used"] != [30, 40]:
    sys.exit(f"FAIL: {m['status']}, {m['scene_file']['camera_planes']}")
PY
