#!/usr/bin/env bash
# issue 5's extremes as manifests, end to end in a debug context:
#   experiments/extremes.yaml: 0, 1, 4096 and 65536 lights x radius 1e-4 and 1e5 at 1x1
#     on every shading renderer: exactly the four forward-spml runs beyond its uniform
#     block end failed:renderer, with the limit in the message; the other 68 are ok,
#     the sweep goes on and the exit status is 1
#   experiments/extremes-camera.yaml: near 0.01 / far 1e6 and the eye inside none, some
#     or all light volumes: every run ok, no non-finite value, within the stated error
#     of the reference
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
set +e
"$SHADESWEEP" run --debug-gl --out ext "$SOURCE_ROOT/experiments/extremes.yaml" >ext.out 2>ext.err
rc=$?
"$SHADESWEEP" run --debug-gl --out cam "$SOURCE_ROOT/experiments/extremes-camera.yaml" >cam.out 2>cam.err
rc_cam=$?
set -e
[ $rc -eq 1 ] || { tail -20 ext.err >&2; fail "extremes.yaml: exit $rc, expected 1 (some runs failed)"; }
[ $rc_cam -eq 0 ] || { tail -20 cam.err >&2; fail "extremes-camera.yaml: exit $rc_cam"; }
grep -q "72 runs, 4 failed" ext.err || fail "extremes.yaml: $(tail -3 ext.err)"

"$PYTHON" - <<'PY'
import csv, re, sys
def fail(msg):
    print("FAIL:", msg, file=sys.stderr); sys.exit(1)
def table(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))
rows = table("ext/summary.csv")
if len(rows) != 72:
    fail(f"extremes: {len(rows)} rows")
for r in rows:
    n = int(r["lights_count"])
    beyond = r["renderer"] == "forward-spml" and n >= 4096
    if beyond:
        m = re.search(r"forward-spml: (\d+) lights requested, this context allows at most (\d+)",
                      r["message"])
        if r["status"] != "failed:renderer" or not m or m.group(1) != str(n) or int(m.group(2)) >= n:
            fail(f"extremes: forward-spml with {n} lights: {r['status']} {r['message']}")
        if r["frames"] not in ("", "0"):
            fail(f"extremes: a refused run rendered {r['frames']} frames")
    elif r["status"] != "ok" or r["frames"] != "1":
        fail(f"extremes: {r['renderer']} {n} lights radius {r['lights_radius']}: "
             f"{r['status']} {r['message']} ({r['frames']} frames)")
rows = table("cam/summary.csv")
if len(rows) != 24:
    fail(f"extremes-camera: {len(rows)} rows")
for r in rows:
    what = f"extremes-camera {r['renderer']} radius {r['lights_radius']}"
    if r["status"] != "ok":
        fail(f"{what}: {r['status']} {r['message']}")
    if r["nonfinite_pixels"] != "0":
        fail(f"{what}: {r['nonfinite_pixels']} non-finite values")
    rmse, mx = float(r["image_rmse"]), float(r["image_max_abs"])
    if not (rmse <= 2 / 255 and mx <= 6 / 255 + 1e-9):
        fail(f"{what}: RMSE {rmse}, max {mx} against forward-spml")
    if r["renderer"] == "forward-spml" and (rmse != 0 or r["image_psnr_db"] != "inf"):
        fail(f"{what}: the reference against itself: RMSE {rmse} PSNR {r['image_psnr_db']}")
print("extremes: ok")
PY
echo "extremes: ok"
