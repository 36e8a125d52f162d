#!/usr/bin/env bash
# A file scene's defaults show the model whatever units it was authored in (issue 25,
# part 4). scale fit (the default) makes a cube in millimetres and the same cube in
# metres one scene: the same bounds after scaling and the same picture under the same
# random lights, where scale 1 leaves the millimetre cube as dark as with no lights
# (lights.radius 10 reaches 10 mm, and an inverse-square light 5 mm away is 1/25 of
# its colour). light_bounds around (the default) keeps the random lights out of the
# closed cube; light_bounds model puts every one inside it, where it lights no face:
# the frame is the one without lights, to the bit. Under shadesweep: 2 (issue 36) the
# two cubes give the same picture too, and it shows the cube.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
# a closed cube of outward faces with flat normals (smooth ones would lean towards a
# light inside near an edge), side 1 m, written in metres and in millimetres
"$PYTHON" - <<'PY'
faces = (((1, 2, 4, 3), "-1 0 0"), ((5, 7, 8, 6), "1 0 0"), ((1, 5, 6, 2), "0 -1 0"),
         ((3, 4, 8, 7), "0 1 0"), ((1, 3, 7, 5), "0 0 -1"), ((2, 6, 8, 4), "0 0 1"))
for name, s in (("m", 1.0), ("mm", 1000.0)):
    with open(f"cube_{name}.obj", "w") as f:
        for x in (-0.5, 0.5):          # vertex 1 + 4 (x > 0) + 2 (y > 0) + (z > 0)
            for y in (-0.5, 0.5):
                for z in (-0.5, 0.5):
                    f.write(f"v {x * s} {y * s} {z * s}\n")
        for _, n in faces:
            f.write(f"vn {n}\n")
        for i, (q, _) in enumerate(faces):
            f.write("f " + " ".join(f"{v}//{i + 1}" for v in q) + "\n")
PY
run() {   # name, scene block, lights count[, schema]
  cat >"$1.yaml" <<Y
shadesweep: ${4:-1}
name: $1
scene: $2
renderers: [forward-spml]
resolution: 64x48
warmup: {frames: 0}
duration: {frames: 1}
clock: fixed
lights: {count: $3}
outputs: {screenshots: [0]}
Y
  "$SHADESWEEP" run -o "out-$1" "$1.yaml" >"$1.log" 2>&1 || { tail -5 "$1.log"; fail "run $1"; }
  cp out-"$1"/runs/*/screenshot-trial1-t0.png "$1.png"
  cp out-"$1"/runs/*/meta.yaml "$1.meta.yaml"
  cp out-"$1"/runs/*/lights-heat-trial1.png "$1.heat.png"
}
run m "{file: cube_m.obj}" 32
run mm "{file: cube_mm.obj}" 32
run mm1 "{file: cube_mm.obj, scale: 1}" 32
run dark "{file: cube_m.obj}" 0
run inside "{file: cube_m.obj, light_bounds: model}" 32
# schema 2's defaults (issue 36): ranges from the lights' intensities and an exposure
# metered from the frame, both in the fitted units, so the same picture again
run m2 "{file: cube_m.obj}" 32 2
run mm2 "{file: cube_mm.obj}" 32 2
"$PYTHON" - "$SOURCE_ROOT/tests/cli" <<'PY'
import sys, yaml
import numpy as np
sys.path.insert(0, sys.argv[1])
from shading_model import read_png
img = {n: read_png(f"{n}.png")[..., :3].astype(float)
       for n in ("m", "mm", "mm1", "dark", "inside", "m2", "mm2")}
meta = {n: yaml.safe_load(open(f"{n}.meta.yaml"))["scene_file"] for n in ("m", "mm", "mm1")}
fails = []
# fit: 20 / sqrt(3) for the metre cube, a thousandth of it for the millimetre one
half = 10 / 3 ** 0.5
for n, k in (("m", 1.0), ("mm", 1e-3)):
    sf = meta[n]
    if not (sf["fit"] and abs(sf["scale"] / k - 2 * half) < 1e-4 * half
            and all(abs(b - half) < 1e-4 for b in sf["bounds_max"])):
        fails.append(f"{n}: fit {sf['fit']} scale {sf['scale']} bounds {sf['bounds_max']}")
if meta["mm1"]["fit"] or meta["mm1"]["scale"] != 1 or meta["mm1"]["bounds_max"] != [500, 500, 500]:
    fails.append(f"mm at scale 1: {meta['mm1']}")
# lit: brighter than the frame without lights by more than 4/255 in some channel
def lit(n):
    return float(((img[n] - img["dark"]).max(axis=-1) > 4).mean())
d = np.abs(img["m"] - img["mm"]) / 255
print(f"m against mm: max {d.max() * 255:.3f}/255 rmse {np.sqrt((d ** 2).mean()) * 255:.3f}/255")
print("lit: " + ", ".join(f"{n} {lit(n):.3f}" for n in ("m", "mm", "mm1", "inside")))
if d.max() > 1 / 255 or np.sqrt((d ** 2).mean()) > 0.25 / 255:
    fails.append("the cube in millimetres and in metres differ under scale fit")
d2 = np.abs(img["m2"] - img["mm2"]) / 255
print(f"schema 2, m against mm: max {d2.max() * 255:.3f}/255 rmse "
      f"{np.sqrt((d2 ** 2).mean()) * 255:.3f}/255")
if d2.max() > 1 / 255 or np.sqrt((d2 ** 2).mean()) > 0.25 / 255:
    fails.append("schema 2: the cube in millimetres and in metres differ")
# the cube's pixels: the heat map of the lights reaching them is pure blue on the sky
hm = read_png("m2.heat.png")[..., :3].astype(int)
cube = ~((hm[..., 0] == 0) & (hm[..., 1] == 0) & (hm[..., 2] == 255))
if ((img["m2"].max(axis=-1) > 40) & cube).mean() < 0.02:
    fails.append("schema 2: the cube is not shown (under 2% of the pixels its and above 40/255)")
if lit("m") < 0.01:
    fails.append(f"32 random lights light {lit('m'):.3f} of the frame (want 0.01 or more)")
if lit("mm1") > 0.001:
    fails.append(f"the millimetre cube at scale 1 is lit on {lit('mm1'):.3f} of the frame")
if not np.array_equal(img["inside"], img["dark"]):
    fails.append("light_bounds model: the lights inside the cube changed the frame")
for f in fails:
    print("FAIL:", f)
sys.exit(1 if fails else 0)
PY
