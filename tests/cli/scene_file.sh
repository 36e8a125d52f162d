#!/usr/bin/env bash
# `scene: {file: PATH}` end to end: PATH relative to the manifest's folder, checked
# by validate and run before anything is written (MANIFEST:LINE:COL: scene.file:
# naming the file and what is wrong), the id following the file's content and not
# its name, a sweep over files, and meta.yaml recording the file.
. "$(dirname "$0")/lib.sh"
cd "$T"
G=/usr/share/assimp/models/glTF2
[ -d "$G" ] || { echo "SKIP: assimp-testmodels is not installed (scripts/setup.sh installs it)" >&2; exit 77; }
mkdir -p scenes
cp -r "$G/BoxTextured-glTF" scenes/box
cp "$G/BoxTextured-glTF-Binary/BoxTextured.glb" scenes/box.glb
cp -r "$G/simple_skin" scenes/skin
manifest() {   # scene block -> m.yaml
  cat >m.yaml <<YAML
shadesweep: 1
name: file-scene
scene: $1
renderers: [forward-spml, deferred]
resolution: 48x32
duration: {frames: 3}
clock: fixed
lights: {placement: random, count: 8, radius: 2}
YAML
}
# timed NAME SCENE RENDERERS SECONDS STEP LIGHTS TIMES: NAME.yaml (64x48, clock fixed,
# screenshots at TIMES) run into NAMEout, its log in NAMErun.txt
timed() {
  cat >"$1.yaml" <<YAML
shadesweep: 1
name: $1
scene: $2
renderers: [$3]
resolution: 64x48
duration: {seconds: $4}
clock: fixed
step: $5
lights: $6
outputs: {screenshots: [$7]}
YAML
  "$SHADESWEEP" run "$1.yaml" -o "$1out" >"$1run.txt" 2>&1 || fail "run $1.yaml: $(tail -5 "$1run.txt")"
}
manifest "{file: scenes/box/BoxTextured.gltf}"
"$SHADESWEEP" validate m.yaml >v.txt || fail "validate: $(cat v.txt)"
grep -qx "m.yaml: ok, 2 runs" v.txt || fail "validate: $(cat v.txt)"
"$SHADESWEEP" list m.yaml >ids1.txt
grep -q "^[0-9a-f]\{12\}  renderer=forward-spml$" ids1.txt || fail "list: $(cat ids1.txt)"

# the same file under another name and folder: the same ids; one changed byte: new ids
mkdir -p elsewhere && cp -r scenes/box elsewhere/copy
mv elsewhere/copy/BoxTextured.gltf elsewhere/copy/renamed.gltf
manifest "{file: elsewhere/copy/renamed.gltf}"
"$SHADESWEEP" list m.yaml >ids2.txt
cmp -s ids1.txt ids2.txt || fail "a renamed copy changed the ids: $(cat ids1.txt ids2.txt)"
$PYTHON - elsewhere/copy/BoxTextured0.bin <<'PY'
import sys
p = sys.argv[1]
b = bytearray(open(p, "rb").read())
b[576] ^= 1   # the lowest mantissa bit of the first texture coordinate
open(p, "wb").write(b)
PY
"$SHADESWEEP" list m.yaml >ids3.txt
[ "$(cut -c1-12 ids1.txt | sort)" != "$(cut -c1-12 ids3.txt | sort)" ] || fail "an edited buffer kept the ids"
# scale, up and camera are part of the id
manifest "{file: scenes/box/BoxTextured.gltf, scale: 2, up: z}"
"$SHADESWEEP" list m.yaml >ids4.txt
[ "$(head -c12 ids4.txt)" != "$(head -c12 ids1.txt)" ] || fail "scale and up did not change the id"

# bad files: exit 2 from validate and run, the position and the file named, nothing written
refuse() {   # scene block, message part
  manifest "$1"
  local cmd rc
  for cmd in validate run; do
    set +e
    "$SHADESWEEP" $cmd m.yaml >out.txt 2>err.txt; rc=$?
    set -e
    [ $rc -eq 2 ] || fail "$cmd with $1: exit $rc: $(cat err.txt)"
    grep -q "^m.yaml:3:[0-9]*: scene.file: .*$2" err.txt || fail "$cmd with $1: want '$2' in: $(cat err.txt)"
    [ ! -e out ] || fail "$cmd with $1 wrote out/"
  done
}
refuse "{file: scenes/nothere.glb}" "nothere.glb"
printf 'not a model at all\n' >scenes/garbage.glb
refuse "{file: scenes/garbage.glb}" "garbage.glb"
head -c 2000 scenes/box.glb >scenes/cut.glb
refuse "{file: scenes/cut.glb}" "cut.glb"
refuse "{file: $G/MissingBin/BoxTextured.gltf}" "MissingBin"
# a glTF extension the file uses and shadesweep does not implement is named: validate
# warns and accepts the file
manifest "{file: $G/ClearCoat-glTF/ClearCoatTest.gltf}"
"$SHADESWEEP" validate m.yaml >v.txt 2>w.txt || fail "validate ClearCoat: $(cat v.txt w.txt)"
# (its metallic-roughness materials and map are rendered: a file's shading.model is pbr)
grep -qxF "m.yaml: warning: scene.file: $G/ClearCoat-glTF/ClearCoatTest.gltf: read but not rendered: glTF extension KHR_materials_clearcoat" w.txt ||
  fail "the clearcoat warning: $(cat w.txt)"

refuse "{file: $G/RecursiveNodes/RecursiveNodes.gltf}" "RecursiveNodes"
refuse "{file: $G/IndexOutOfRange/IndexOutOfRange.gltf}" "IndexOutOfRange"
manifest "{file: scenes/box.glb, up: x}"
set +e; "$SHADESWEEP" validate m.yaml >out.txt 2>err.txt; rc=$?; set -e
[ $rc -eq 2 ] && grep -q "scene.up: expected one of y, z, found 'x'" err.txt || fail "up: x: $(cat err.txt)"

# a sweep over three files, rendered: each run's meta.yaml names its file and counts, and
# lists what the file has that is not rendered (here nothing: simple_skin's skin is drawn
# and its animation plays, and every material is shaded by its own model), which the run
# would also warn of on stderr, once
cat >s.yaml <<'YAML'
shadesweep: 1
name: file-sweep
renderers: [forward-spml]
resolution: 48x32
duration: {frames: 3}
clock: fixed
lights: {placement: random, count: 4, radius: 2}
sweep:
  scene: [{file: scenes/box.glb}, {file: scenes/box/BoxTextured.gltf}, {file: scenes/skin/simple_skin.gltf}, shapes]
YAML
need_gl
"$SHADESWEEP" run s.yaml -o out >run.txt 2>&1 || fail "run s.yaml: $(tail -5 run.txt)"
# a glTF material is shaded by its own metallic-roughness model (shading.model: scene),
# which is listed as not rendered under phong only (cli-pbr_files), and skins are drawn:
# none of the three files warns
[ "$(grep -c "warning: scene.file" run.txt)" = 0 ] ||
  fail "the not-rendered warnings: $(grep warning run.txt)"
$PYTHON - out <<'PY'
import csv, sys, yaml, glob
d = sys.argv[1]
summ = list(csv.DictReader(open(f"{d}/summary.csv")))
if [r["scene"] for r in summ] != ["box.glb", "BoxTextured.gltf", "simple_skin.gltf", "shapes"]:
    sys.exit(f"FAIL: scenes {[r['scene'] for r in summ]}")
if any(r["status"] != "ok" for r in summ): sys.exit(f"FAIL: {summ}")
for r, files in zip(summ[:2], (1, 3)):   # the .glb alone; the .gltf, its .bin and its .png
    m = yaml.safe_load(open(f"{d}/runs/{r['run_id']}/meta.yaml"))
    sf = m["scene_file"]
    # scale fit (the default): the unit box made 20 across its diagonal
    half = 10 / 3 ** 0.5
    if (sf["triangles"] != 12 or sf["textures"] != 1 or sf["files"] != files
            or len(sf["hash"]) != 16 or not sf["fit"] or sf["light_bounds"] != "around"
            or abs(sf["scale"] - 2 * half) > 1e-5
            or any(abs(b - half) > 1e-5 for b in sf["bounds_max"])):
        sys.exit(f"FAIL: meta scene_file {sf}")
    # the id text names the content, and the defaults that came after scale 1, orbit
    # and the model's light bounds
    if m["parameters"]["scene"] != f"file:{sf['hash']},scale:fit,camera:auto,light_bounds:around":
        sys.exit(f"FAIL: the id text: {m['parameters']['scene']}")
    if sf.get("not_rendered", []) != []:
        sys.exit(f"FAIL: the box leaves nothing out: {sf}")
skin = yaml.safe_load(open(f"{d}/runs/{summ[2]['run_id']}/meta.yaml"))["scene_file"]
if skin["not_rendered"] != []:
    sys.exit(f"FAIL: simple_skin's not_rendered: {skin['not_rendered']}")
m = yaml.safe_load(open(f"{d}/runs/{summ[3]['run_id']}/meta.yaml"))
if "scene_file" in m: sys.exit("FAIL: a catalog scene has no scene_file block")
PY

# KHR_materials_emissive_strength: a quad with a black base colour and an emissive factor
# of (0.2, 0.1, 0.05), without lights, drawn with emissiveStrength 3 and without the
# extension: the strength scales the emissive (the centre pixel 3x, within rounding), the
# extension is not listed as not rendered; a negative strength is refused by name.
$PYTHON - <<'PY'
import base64, json, struct
pos = [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0]
nrm = [0, 0, 1] * 4
idx = [0, 1, 2, 0, 2, 3]
blob = struct.pack("<12f", *pos) + struct.pack("<12f", *nrm) + struct.pack("<6H", *idx) + b"\0\0"
def quad(strength):
    mat = {"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0},
           "emissiveFactor": [0.2, 0.1, 0.05]}
    g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
         "nodes": [{"mesh": 0}], "materials": [mat],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2,
                                     "material": 0}]}],
         "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64,"
                      + base64.b64encode(blob).decode()}],
         "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                         {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                         {"buffer": 0, "byteOffset": 96, "byteLength": 12}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                        "min": [-1, -1, 0], "max": [1, 1, 0]},
                       {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                       {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]}
    if strength is not None:
        mat["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
        g["extensionsUsed"] = ["KHR_materials_emissive_strength"]
    return json.dumps(g)
open("scenes/quad1.gltf", "w").write(quad(None))
open("scenes/quad3.gltf", "w").write(quad(3))
open("scenes/quadbad.gltf", "w").write(quad(-2))
PY
cat >e.yaml <<'YAML'
shadesweep: 1
name: emissive-strength
renderers: [forward-spml, deferred]
resolution: 48x32
duration: {frames: 1}
clock: fixed
lights: {placement: none, count: 0}
outputs: {screenshots: [0]}
sweep:
  scene: [{file: scenes/quad1.gltf}, {file: scenes/quad3.gltf}]
YAML
"$SHADESWEEP" run e.yaml -o eout >erun.txt 2>&1 || fail "run e.yaml: $(tail -5 erun.txt)"
grep -q "KHR_materials_emissive_strength" erun.txt && fail "listed as not rendered: $(grep warning erun.txt)"
$PYTHON - eout "$SOURCE_ROOT/tests/cli" <<'PY'
import csv, sys, glob
sys.path.insert(0, sys.argv[2])
from shading_model import read_png
d = sys.argv[1]
summ = list(csv.DictReader(open(f"{d}/summary.csv")))
if [r["status"] for r in summ] != ["ok"] * 4: sys.exit(f"FAIL: {summ}")
px = {}
for r in summ:
    img = read_png(glob.glob(f"{d}/runs/{r['run_id']}/screenshot-*.png")[0])
    px[(r["scene"], r["renderer"])] = [int(v) for v in img[img.shape[0] // 2, img.shape[1] // 2, :3]]
for ren in ("forward-spml", "deferred"):
    one, three = px[("quad1.gltf", ren)], px[("quad3.gltf", ren)]
    # 0.2, 0.1, 0.05 and three times that, in 8 bits
    if any(abs(a - round(255 * v)) > 1 for a, v in zip(one, (0.2, 0.1, 0.05))) or \
       any(abs(a - round(255 * v)) > 1 for a, v in zip(three, (0.6, 0.3, 0.15))):
        sys.exit(f"FAIL: {ren}: emissive {one} and with strength 3 {three}")
PY
cat >eb.yaml <<'YAML'
shadesweep: 1
name: emissive-strength-bad
scene: {file: scenes/quadbad.gltf}
renderers: [forward-spml]
resolution: 48x32
duration: {frames: 1}
lights: {placement: none, count: 0}
YAML
set +e; "$SHADESWEEP" validate eb.yaml >out.txt 2>err.txt; rc=$?; set -e
[ $rc -eq 2 ] && grep -qF "scenes/quadbad.gltf: KHR_materials_emissive_strength: emissiveStrength -2 is not a finite number >= 0" err.txt ||
  fail "a negative emissiveStrength: rc $rc $(cat err.txt out.txt)"

# glTF's COLOR_0: a grey quad lit by four surface lights, with vertex colours (1, 0.5,
# 0.25) and without, in every renderer: the centre pixel's red stays, green and blue
# take about a half and a quarter (a near-black specular apart), the same in each, and
# the colours are not listed as not rendered.
$PYTHON - <<'PY'
import base64, json, struct
pos = [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0]
blob = (struct.pack("<12f", *pos) + struct.pack("<12f", *([0, 0, 1] * 4)) +
        struct.pack("<16f", *([1, 0.5, 0.25, 1] * 4)) + struct.pack("<6H", 0, 1, 2, 0, 2, 3) +
        b"\0\0")
def quad(colours):
    attrs = {"POSITION": 0, "NORMAL": 1}
    if colours:
        attrs["COLOR_0"] = 3
    return json.dumps({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1],
                                                "metallicFactor": 0, "roughnessFactor": 1}}],
        "meshes": [{"primitives": [{"attributes": attrs, "indices": 2, "material": 0}]}],
        "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64,"
                     + base64.b64encode(blob).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 160, "byteLength": 12},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 64}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [-1, -1, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"},
                      {"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC4"}]})
open("scenes/cquad0.gltf", "w").write(quad(False))
open("scenes/cquad1.gltf", "w").write(quad(True))
PY
cat >c.yaml <<'YAML'
shadesweep: 1
name: vertex-colours
renderers: [forward-spml, forward-mpml, forward-plus, clustered, deferred, tiled-deferred,
            deferred-lighting, visibility]
resolution: 48x32
duration: {frames: 1}
clock: fixed
lights: {placement: surface, count: 4, overlap: 2}
outputs: {screenshots: [0]}
sweep:
  scene: [{file: scenes/cquad0.gltf}, {file: scenes/cquad1.gltf}]
YAML
"$SHADESWEEP" run c.yaml -o cout >crun.txt 2>&1 || fail "run c.yaml: $(tail -5 crun.txt)"
grep -q "vertex colours" crun.txt && fail "listed as not rendered: $(grep warning crun.txt)"
$PYTHON - cout "$SOURCE_ROOT/tests/cli" <<'PY'
import csv, sys, glob
sys.path.insert(0, sys.argv[2])
from shading_model import read_png
d = sys.argv[1]
summ = list(csv.DictReader(open(f"{d}/summary.csv")))
if len(summ) != 16 or any(r["status"] != "ok" for r in summ): sys.exit(f"FAIL: {summ}")
px = {}
for r in summ:
    img = read_png(glob.glob(f"{d}/runs/{r['run_id']}/screenshot-*.png")[0])
    px[(r["scene"], r["renderer"])] = [int(v) for v in img[img.shape[0] // 2, img.shape[1] // 2, :3]]
first = None
for (scene, ren), p in px.items():
    if scene != "cquad1.gltf":
        continue
    plain = px[("cquad0.gltf", ren)]
    want = [plain[0], plain[1] * 0.5, plain[2] * 0.25]
    if plain[2] < 20 or any(abs(a - w) > 3 for a, w in zip(p, want)):
        sys.exit(f"FAIL: {ren}: {p} with vertex colours, {plain} without")
    if first is not None and any(abs(a - b) > 1 for a, b in zip(p, first)):
        sys.exit(f"FAIL: {ren}: {p}, the first renderer {first}")
    first = first or p
PY

# The file's animation plays (scene_anim.h): a quad whose node moves from x = -0.5 to
# +0.5 over 1 s, and a second animation that is not played; clock fixed, screenshots at
# 0, 0.5 and 1.5 s (1.5 s loops to 0.5): the lit pixels' centre moves right by about 10
# of the view's 64 pixels, the images at 0.5 and 1.5 s are the same, and so are those of
# forward-spml, deferred and visibility; meta.yaml names only the second animation as
# not played.
$PYTHON - <<'PY'
import base64, json, struct
pos = [-0.5, -0.5, 0, 0.5, -0.5, 0, 0.5, 0.5, 0, -0.5, 0.5, 0]
blob = (struct.pack("<12f", *pos) + struct.pack("<12f", *([0, 0, 1] * 4)) +
        struct.pack("<6H", 0, 1, 2, 0, 2, 3) +   # 108 bytes so far: aligned for floats
        struct.pack("<2f", 0, 1) + struct.pack("<6f", -0.5, 0, 0, 0.5, 0, 0))
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
     "nodes": [{"mesh": 0, "translation": [-0.5, 0, 0]},
               {"translation": [0, 0, 4], "camera": 0}],
     "cameras": [{"type": "perspective", "perspective": {"yfov": 0.6, "znear": 0.1,
                                                         "zfar": 100}}],
     "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]},
                    "emissiveFactor": [1, 1, 1]}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2,
                                 "material": 0}]}],
     "animations": [{"samplers": [{"input": 3, "output": 4}],
                     "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]},
                    {"samplers": [{"input": 3, "output": 4}],
                     "channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}}]}],
     "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64,"
                  + base64.b64encode(blob).decode()}],
     "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                     {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                     {"buffer": 0, "byteOffset": 96, "byteLength": 12},
                     {"buffer": 0, "byteOffset": 108, "byteLength": 8},
                     {"buffer": 0, "byteOffset": 116, "byteLength": 24}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                    "min": [-0.5, -0.5, 0], "max": [0.5, 0.5, 0]},
                   {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                   {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"},
                   {"bufferView": 3, "componentType": 5126, "count": 2, "type": "SCALAR",
                    "min": [0], "max": [1]},
                   {"bufferView": 4, "componentType": 5126, "count": 2, "type": "VEC3"}]}
open("scenes/moving.gltf", "w").write(json.dumps(g))
PY
timed a "{file: scenes/moving.gltf}" "forward-spml, deferred, visibility" 1.6 0.1 \
  "{placement: none, count: 0}" "0, 0.5, 1.5"
$PYTHON - aout "$SOURCE_ROOT/tests/cli" <<'PY'
import sys
import numpy as np
sys.path.insert(0, sys.argv[2])
from shots import runs_with_shots
times = ("0", "0.5", "1.5")
runs = runs_with_shots(sys.argv[1], times)
if len(runs) != 3: sys.exit(f"FAIL: {len(runs)} runs")
shots = {}
for r, m, images in runs:
    if m["scene_file"]["not_rendered"][:1] != ["animations after the first (1, not played)"]:
        sys.exit(f"FAIL: not_rendered {m['scene_file']['not_rendered']}")
    for t, img in zip(times, images):
        img = img[..., :3]
        lit = img.sum(axis=2) > 384
        if lit.sum() < 50: sys.exit(f"FAIL: {r['renderer']} t={t}: {lit.sum()} lit pixels")
        shots[(r["renderer"], t)] = (img, np.nonzero(lit)[1].mean())
for ren in ("forward-spml", "deferred", "visibility"):
    x0, x5, x15 = (shots[(ren, t)][1] for t in ("0", "0.5", "1.5"))
    # the node moves by 0.5 at 4 units with yfov 0.6 (64x48): about 0.5 / (4 tan 0.3)
    # of half the height, 24 px: 9.7 px
    if not 8.0 < x5 - x0 < 11.5 or not np.array_equal(shots[(ren, "0.5")][0], shots[(ren, "1.5")][0]):
        sys.exit(f"FAIL: {ren}: lit centre x {x0:.2f} at 0, {x5:.2f} at 0.5, {x15:.2f} at 1.5")
for ren in ("deferred", "visibility"):
    diff = np.abs(shots[("forward-spml", "0.5")][0] - shots[(ren, "0.5")][0]).max()
    if diff > 1: sys.exit(f"FAIL: forward-spml and {ren} differ by {diff} at 0.5 s")
PY

# Morph targets play: the Khronos AnimatedMorphCube (its weights animated over 4.2 s) at
# 0 and 1 s in forward-spml, deferred and visibility: the two frames differ on more than
# a tenth of the view, and the three renderers draw the same frame at 1 s (within 2/255).
surface4="{placement: surface, count: 4, overlap: 2}"
timed mc "{file: \"$G/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf\"}" \
  "forward-spml, deferred, visibility" 1.1 0.1 "$surface4" "0, 1"
grep -q "read but not rendered:.*morph" mcrun.txt && fail "morph targets listed as not rendered: $(grep warning mcrun.txt)"
$PYTHON - mcout "$SOURCE_ROOT/tests/cli" <<'PY'
import sys
import numpy as np
sys.path.insert(0, sys.argv[2])
from shots import runs_with_shots
at1 = {}
for r, _, (a, b) in runs_with_shots(sys.argv[1], ("0", "1")):
    moved = (np.abs(a - b).max(axis=2) > 2).mean()
    if moved < 0.1: sys.exit(f"FAIL: {r['renderer']}: {moved:.3f} of the view changes from 0 to 1 s")
    at1[r["renderer"]] = b
for ren in ("deferred", "visibility"):
    diff = np.abs(at1[ren] - at1["forward-spml"]).max()
    if diff > 2: sys.exit(f"FAIL: {ren} differs from forward-spml by {diff}/255 at 1 s")
PY

# Skins are drawn: simple_skin (two joints, the second turned by the animation over 5.5 s)
# at 0 and 2 s in every renderer: the frames differ (the bent part of the strip moves),
# every renderer draws the same frame as forward-spml at each time (within 4/255, under
# 0.5 % of the pixels beyond 2/255: visibility skins its refetched triangles as mesh.vert
# does), the pass plan names the
# define, and meta.yaml lists no skin as not rendered.
timed sk "{file: scenes/skin/simple_skin.gltf}" "forward-spml, forward-mpml, forward-plus, \
clustered, deferred, tiled-deferred, deferred-lighting, visibility" 2.5 1 "$surface4" "0, 2"
grep -q "read but not rendered:.*skin" skrun.txt && fail "skins listed as not rendered: $(grep warning skrun.txt)"
$PYTHON - skout "$SOURCE_ROOT/tests/cli" <<'PY'
import sys
import numpy as np
sys.path.insert(0, sys.argv[2])
from shots import runs_with_shots
shots = {}
for r, m, (a, b) in runs_with_shots(sys.argv[1], ("0", "2")):
    if any("skin" in x for x in m["scene_file"]["not_rendered"]):
        sys.exit(f"FAIL: not_rendered {m['scene_file']['not_rendered']}")
    if "skins" not in m["pass_plan"]["lighting"]:
        sys.exit(f"FAIL: {r['renderer']}: the plan's lighting: {m['pass_plan']['lighting']}")
    covered = (a[..., :3].max(axis=2) > 0).mean()
    moved = (np.abs(a - b).max(axis=2) > 8).mean()
    # the strip covers about a tenth of the view; its bent half moves: 4 % of it changes
    if covered < 0.04 or moved < 0.02:
        sys.exit(f"FAIL: {r['renderer']}: {covered:.3f} covered, {moved:.3f} of the view "
                 "changes from 0 to 2 s")
    shots[r["renderer"]] = (a, b)
for ren, (a, b) in shots.items():
    for t, x, y in (("0", a, shots["forward-spml"][0]), ("2", b, shots["forward-spml"][1])):
        diff = np.abs(x - y).max(axis=2)
        # the G-buffer renderers round a highlight's saturated pixel by up to 3/255
        if diff.max() > 4 or (diff > 2).mean() > 0.005:
            sys.exit(f"FAIL: {ren} differs from forward-spml by {diff.max()}/255 at {t} s "
                     f"({(diff > 2).mean():.4f} of the pixels by more than 2/255)")
PY

# A hostile skin: a vertex whose weights are all 0 (it follows the first joint), one with
# a NaN weight (counted as none), one with weights of 1e38 (no overflow when normalised):
# drawn, in forward-spml and visibility alike, nothing refused or crashed.
$PYTHON - <<'PY'
import base64, json, struct
pos = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
joints = [(0, 1, 0, 0), (0, 0, 0, 0), (1, 0, 0, 0), (1, 0, 0, 0)]
weights = [(0.5, 0.5, 0, 0), (0, 0, 0, 0), (float("nan"), 1, 0, 0), (1e38, 1e38, 0, 0)]
blob = b"".join(struct.pack("<3f", *p) for p in pos) + struct.pack("<6H", 0, 1, 2, 0, 2, 3)
blob += b"".join(struct.pack("<4H", *j) for j in joints)
blob += b"".join(struct.pack("<4f", *w) for w in weights)
blob += struct.pack("<32f", *([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] * 2))
o = [0, 48, 60, 92, 156, 284]
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
     "nodes": [{"mesh": 0, "skin": 0}, {"children": [2]}, {"translation": [0, 1, 0]}],
     "skins": [{"joints": [1, 2], "inverseBindMatrices": 4}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "JOINTS_0": 2, "WEIGHTS_0": 3},
                                 "indices": 1}]}],
     "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64,"
                  + base64.b64encode(blob).decode()}],
     "bufferViews": [{"buffer": 0, "byteOffset": o[i], "byteLength": o[i + 1] - o[i]}
                     for i in range(5)],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                    "min": [0, 0, 0], "max": [1, 1, 0]},
                   {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
                   {"bufferView": 2, "componentType": 5123, "count": 4, "type": "VEC4"},
                   {"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC4"},
                   {"bufferView": 4, "componentType": 5126, "count": 2, "type": "MAT4"}]}
open("scenes/hostile_skin.gltf", "w").write(json.dumps(g))
PY
cat >hs.yaml <<'YAML'
shadesweep: 1
name: hostile-skin
scene: {file: scenes/hostile_skin.gltf}
renderers: [forward-spml, visibility]
resolution: 32x24
duration: {frames: 2}
clock: fixed
lights: {placement: none, count: 0}
outputs: {screenshots: [0]}
YAML
"$SHADESWEEP" run hs.yaml -o hsout >hsrun.txt 2>&1 || fail "run hs.yaml: $(tail -5 hsrun.txt)"
$PYTHON - hsout "$SOURCE_ROOT/tests/cli" <<'PY'
import csv, sys, glob
import numpy as np
sys.path.insert(0, sys.argv[2])
from shading_model import read_png
d = sys.argv[1]
img = {}
for r in csv.DictReader(open(f"{d}/summary.csv")):
    if r["status"] != "ok": sys.exit(f"FAIL: {r['renderer']}: {r['status']}")
    img[r["renderer"]] = read_png(glob.glob(f"{d}/runs/{r['run_id']}/screenshot-*.png")[0]).astype(int)
    if (img[r["renderer"]][..., :3].max(axis=2) > 0).mean() < 0.05:
        sys.exit(f"FAIL: {r['renderer']}: the hostile skin is not drawn")
if np.abs(img["forward-spml"] - img["visibility"]).max() > 2:
    sys.exit("FAIL: forward-spml and visibility draw the hostile skin apart")
PY
# More joints than the palette holds (16384 in all: 4 texels each in a texture buffer of
# GL's minimum size) refuse the file by name, in validate and in run, before any run.
$PYTHON - <<'PY'
import base64, json, struct
n = 16385
blob = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 1, 1, 0) + struct.pack("<4H", 0, 1, 2, 0)
blob += struct.pack("<4H", 0, 0, 0, 0) * 3 + struct.pack("<4f", 1, 0, 0, 0) * 3
blob += struct.pack("<16f", 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1) * n
views = [(0, 36), (36, 6), (44, 24), (68, 48), (116, 64 * n)]
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
     "nodes": [{"mesh": 0, "skin": 0}, {"children": list(range(2, n + 1))}] + [{}] * n,
     "skins": [{"joints": list(range(1, n + 1)), "inverseBindMatrices": 4}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "JOINTS_0": 2, "WEIGHTS_0": 3},
                                 "indices": 1}]}],
     "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64,"
                  + base64.b64encode(blob).decode()}],
     "bufferViews": [{"buffer": 0, "byteOffset": o, "byteLength": l} for o, l in views],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                    "min": [0, 0, 0], "max": [1, 1, 0]},
                   {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
                   {"bufferView": 2, "componentType": 5123, "count": 3, "type": "VEC4"},
                   {"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC4"},
                   {"bufferView": 4, "componentType": 5126, "count": n, "type": "MAT4"}]}
open("scenes/many_joints.gltf", "w").write(json.dumps(g))
PY
sed 's/hostile_skin.gltf/many_joints.gltf/' hs.yaml >mj.yaml
for cmd in validate "run -o mjout"; do
  set +e; "$SHADESWEEP" $cmd mj.yaml >mj.txt 2>&1; rc=$?; set -e
  [ $rc -eq 2 ] && grep -q "many_joints.gltf: its skins have 16385 joints in all; at most 16384 are drawn" mj.txt ||
    fail "$cmd with 16385 joints: exit $rc: $(cat mj.txt)"
done
[ ! -e mjout ] || fail "a refused skin wrote mjout/"
