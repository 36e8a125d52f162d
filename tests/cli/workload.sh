#!/usr/bin/env bash
# The workload shown (issue 36, item 3): the lights that reach each covered pixel of a
# trial's first measured frame (summary.csv's lights_reaching_*, the same for every
# renderer), beside the renderer's light evaluations a pixel and the coverage in
# summary.md; the heat map lights-heat-trial1.png; lights.csv; and the warning when
# the lights reaching a pixel average over half the lights.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"

# a minimal PNG reader (8-bit greyscale, RGB or RGBA, not interlaced), for the checks below
cat >png.py <<'PY'
import struct, zlib
def read_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat = 8, b""
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, lace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and lace == 0, (depth, lace)
            ch = {0: 1, 2: 3, 6: 4}[ctype]
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, stride, rows, prev = zlib.decompress(idat), w * ch, [], bytearray(w * ch)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - ch] if i >= ch else 0
            b, c = prev[i], prev[i - ch] if i >= ch else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * ch:(x + 1) * ch]) for x in range(w)])
        prev = line
    return w, h, rows
PY

# 1. Lights reaching everything: radius 1000 on `shapes`, a growth schedule whose first
# measured frame (t = 0) has 15 of its 45 lights on. Every covered pixel is reached by
# exactly those 15 (mean = p50 = p99 = max = 15), the tiled renderers' lists hold all of
# them (15 evaluations a pixel), the warning is given, and the heat map is white where
# the scene covers the screen and blue elsewhere, as many pixels as `coverage` counts.
cat >all.yaml <<'EOF'
shadesweep: 1
name: all
scene: shapes
renderers: [forward-plus, tiled-deferred, deferred, null]
resolution: 64x48
warmup: {frames: 0}
duration: {frames: 1}
clock: fixed
lights: {count: {start: 15, step: 15, every: 1, max: 45}, radius: 1000}
EOF
"$SHADESWEEP" run -o out/all all.yaml >all.log 2>&1 || { cat all.log; fail "the all-lights run failed"; }
want="every light reaches most pixels: the workload is brute force whatever the renderer (mean 15.0 of 15 lights a pixel)"
[ "$(grep -cF "$want" all.log)" = 3 ] ||
  { cat all.log; fail "expected the brute-force warning on the terminal for the 3 renderers that draw"; }
[ "$(grep -cF "$want" out/all/summary.md)" = 3 ] || fail "summary.md: expected the warning 3 times"
"$PYTHON" - out/all "$want" <<'PY' || fail "all: see above"
import csv, os, sys
sys.path.insert(0, ".")
from png import read_png
out, want = sys.argv[1], sys.argv[2]
def fail(m): print("FAIL:", m); sys.exit(1)
for r in csv.DictReader(open(out + "/summary.csv")):
    run = os.path.join(out, "runs", r["run_id"])
    reach = [r["lights_reaching_" + k] for k in ("mean", "p50", "p99", "max")]
    meta = open(run + "/meta.yaml").read()
    if r["status"] != "ok" or r["lights_count"] != "15":
        fail(f"{r['renderer']}: {r['status']} {r['lights_count']}")
    if r["renderer"] == "null":
        if reach != [""] * 4 or os.path.exists(run + "/lights-heat-trial1.png"):
            fail(f"null draws nothing: no figure, no heat map ({reach})")
        continue
    if reach != ["15.000", "15", "15", "15"]: fail(f"{r['renderer']}: reach {reach}")
    evals = r["light_evals_per_pixel"]
    if evals != ("" if r["renderer"] == "deferred" else "15.000"):
        fail(f"{r['renderer']}: evals {evals!r}")
    if f'warning: "{want}' not in meta: fail(f"{r['renderer']}: meta.yaml has no warning")
    w, h, rows = read_png(run + "/lights-heat-trial1.png")
    if (w, h) != (64, 48): fail(f"heat map {w}x{h}")
    px = [p for row in rows for p in row]
    if set(px) != {(255, 255, 255), (0, 0, 255)}: fail(f"heat map colours {set(px)}")
    if "%.6f" % (px.count((255, 255, 255)) / (w * h)) != r["coverage"]:
        fail(f"heat map covers {px.count((255, 255, 255))} pixels, coverage {r['coverage']}")
    # lights.csv: every light of the schedule, each with the time it turns on
    lights = list(csv.DictReader(open(run + "/lights.csv")))
    on = [l["on_s"] for l in lights]
    if on != ["0"] * 15 + ["1"] * 15 + ["2"] * 15: fail(f"lights.csv on_s {on}")
    if [l["light"] for l in lights] != [str(i) for i in range(45)] or \
            any(l["kind"] != "point" or l["range"] != "1000" or l["cone_rad"] for l in lights):
        fail("lights.csv rows")
# the table shows the figure beside each time
md = open(out + "/summary.md").read()
if "| lights a pixel | evals a pixel | coverage |" not in md: fail("summary.md header")
if md.count("| 15.00 of 15 |") != 3: fail("summary.md: '15.00 of 15' 3 times")
PY

# 2. A light radius of 0.001 (no light reaches a pixel) and 10 (some do): the figures
# are the same for every renderer (the same depth, the same lights), equal to what the
# heat map shows (15 lights: grey = 17 x count, so the counts read back exactly), and no
# more than the tiled renderers' evaluations (culling is conservative); no warning.
cat >mid.yaml <<'EOF'
shadesweep: 1
name: mid
scene: shapes
renderers: [forward-plus, tiled-deferred, deferred]
resolution: 64x48
warmup: {frames: 0}
duration: {frames: 1}
clock: fixed
lights: {count: 15}
sweep:
  lights.radius: [0.001, 10]
EOF
"$SHADESWEEP" run -o out/mid mid.yaml >mid.log 2>&1 || { cat mid.log; fail "the mid run failed"; }
if grep -q "brute force" mid.log; then fail "mid: a warning without brute force"; fi
if grep -q "the workload is brute force" out/mid/summary.md; then fail "mid: summary.md warns"; fi
"$PYTHON" - out/mid <<'PY' || fail "mid: see above"
import csv, math, os, sys
sys.path.insert(0, ".")
from png import read_png
out = sys.argv[1]
def fail(m): print("FAIL:", m); sys.exit(1)
by_radius = {}
for r in csv.DictReader(open(out + "/summary.csv")):
    run = os.path.join(out, "runs", r["run_id"])
    w, h, rows = read_png(run + "/lights-heat-trial1.png")
    counts = []
    for row in rows:
        for p in row:
            if p == (0, 0, 255): continue
            if p[0] != p[1] or p[1] != p[2] or p[0] % 17: fail(f"heat map pixel {p}")
            counts.append(p[0] // 17)
    counts.sort()
    n = len(counts)
    rank = lambda q: counts[max(1, math.ceil(q * n)) - 1]   # nearest rank
    mine = ["%.3f" % (sum(counts) / n), str(rank(0.5)), str(rank(0.99)), str(counts[-1])]
    reach = [r["lights_reaching_" + k] for k in ("mean", "p50", "p99", "max")]
    if reach != mine: fail(f"{r['renderer']} radius {r['lights_radius']}: {reach}, heat map {mine}")
    if "%.6f" % (n / (w * h)) != r["coverage"]: fail("heat map against coverage")
    if r["light_evals_per_pixel"] and float(r["light_evals_per_pixel"]) < float(reach[0]):
        fail(f"{r['renderer']}: evaluates {r['light_evals_per_pixel']} < {reach[0]} reaching")
    by_radius.setdefault(r["lights_radius"], set()).add((tuple(reach), tuple(map(tuple, rows))))
if sorted(by_radius) != ["0.001", "10"]: fail(f"radii {sorted(by_radius)}")
for radius, seen in by_radius.items():
    if len(seen) != 1: fail(f"radius {radius}: the renderers' figures or heat maps differ")
(tiny,), (some,) = by_radius["0.001"], by_radius["10"]
if tiny[0] != ("0.000", "0", "0", "0"): fail(f"radius 0.001: {tiny[0]}")
if not (0 < float(some[0][0]) < 7.5 and int(some[0][2]) > int(some[0][1])):
    fail(f"radius 10: expected some lights, spread: {some[0]}")
PY

# 3. lights.csv reads back as the scene's lights: seed 1337 msvc's first five on
# `empty`, as tests/unit/test_scene_lights.c pins them (recorded by an independent
# script); each value parses to exactly that float. No pixel covered: the figures empty.
cat >csv.yaml <<'EOF'
shadesweep: 1
name: lightscsv
scene: empty
renderers: [forward-spml]
resolution: 64x48
warmup: {frames: 0}
duration: {frames: 1}
clock: fixed
lights: {count: 5, seed: 1337, rng: msvc, color_max: 0.3, radius: 2.5}
EOF
"$SHADESWEEP" run -o out/csv csv.yaml >csv.log 2>&1 || { cat csv.log; fail "the lights.csv run failed"; }
"$PYTHON" - out/csv <<'PY' || fail "lights.csv: see above"
import csv, glob, struct, sys
def fail(m): print("FAIL:", m); sys.exit(1)
f32 = lambda v: struct.unpack("f", struct.pack("f", v))[0]
pinned = [  # position, colour
    ((-36.5596466, 15.8415489, 4.2100296), (0.271727681, 0.0376567915, 0.173543513)),
    ((-25.0480671, 10.9323406, -47.5157928), (0.0242164396, 0.0431318097, 0.196432397)),
    ((-15.4683037, 2.63618898, -38.8607445), (0.274410248, 0.150233462, 0.176454976)),
    ((28.8476257, 6.0328989, -8.43989182), (0.187954351, 0.088763088, 6.40888757e-05)),
    ((-10.612812, 5.21561337, -18.7215805), (0.0927823782, 0.00889919791, 0.220960125)),
]
(path,) = glob.glob(sys.argv[1] + "/runs/*/lights.csv")
rows = list(csv.DictReader(open(path)))
if len(rows) != 5: fail(f"{len(rows)} rows")
for i, (row, (pos, col)) in enumerate(zip(rows, pinned)):
    got = [f32(float(row[k])) for k in ("x", "y", "z", "r", "g", "b")]
    if got != [f32(v) for v in pos + col]: fail(f"light {i}: {row}")
    if (row["light"], row["kind"], row["range"], row["on_s"]) != (str(i), "point", "2.5", "0"):
        fail(f"light {i}: {row}")
    if any(row[k] for k in ("dir_x", "dir_y", "dir_z", "cone_rad")):
        fail(f"light {i}: a point with a direction")
(r,) = csv.DictReader(open(sys.argv[1] + "/summary.csv"))
if [r["lights_reaching_" + k] for k in ("mean", "p50", "p99", "max")] != [""] * 4:
    fail("no pixel covered: the figures are empty")
PY
echo "ok"
