#!/usr/bin/env bash
# A frame that shows nothing ranks nothing (issue 25, part 4): the covered fraction of
# the screen is summary.csv's `coverage`, the same for every renderer (any sample nearer
# than the far plane, counted on the GPU between frames); a scene with objects whose
# first measured frame covers no pixel, or is black, ends the trial as failed:empty with
# a message, unless the manifest says allow_empty: true.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
# rows FOLDER: "renderer,msaa,status,coverage" of each trial row of its summary.csv
# (msaa from plan.csv)
rows() {
  "$PYTHON" - "$1" <<'PY'
import csv, sys
msaa = {r["run_id"]: r["msaa"] for r in csv.DictReader(open(sys.argv[1] + "/plan.csv"))}
for r in csv.DictReader(open(sys.argv[1] + "/summary.csv")):
    if r["trial"]:
        print(r["renderer"], msaa[r["run_id"]], r["status"], r["coverage"], sep=",")
PY
}

# 1. coverage: every renderer the same count at 1 and 4 samples, null none
cat >cov.yaml <<'EOF'
shadesweep: 1
name: cov
scene: shapes
renderers: [null, deferred, forward-mpml, forward-spml, forward-plus, clustered, tiled-deferred,
            deferred-lighting, visibility]
resolution: 64x48
warmup: {frames: 0}
duration: {frames: 1}
clock: fixed
sweep:
  msaa: [1, 4]
EOF
"$SHADESWEEP" run -o out/cov cov.yaml >cov.log 2>&1 || { cat cov.log; fail "the coverage sweep failed"; }
rows out/cov >cov.txt
[ "$(grep -c ',ok,' cov.txt)" = 17 ] || { cat cov.txt; fail "expected 17 ok trials (null reads no msaa: one run)"; }
grep -q '^null,[0-9]*,ok,$' cov.txt || { cat cov.txt; fail "null has no depth target: coverage empty"; }
for m in 1 4; do
  vals=$(grep -v '^null,' cov.txt | awk -F, -v m="$m" '$2 == m {print $4}' | sort -u)
  [ "$(echo "$vals" | wc -l)" = 1 ] || { cat cov.txt; fail "msaa $m: the renderers' coverage differs"; }
  awk -v v="$vals" 'BEGIN {exit !(v > 0.3 && v < 1)}' || fail "msaa $m: coverage $vals out of (0.3, 1)"
  eval "cov$m=$vals"
done
# a pixel is covered when any of its samples is: never fewer at 4x
awk -v a="$cov1" -v b="$cov4" 'BEGIN {exit !(b >= a)}' || fail "coverage at 4x ($cov4) below 1x ($cov1)"

# 2. a camera that looks away from every object: failed:empty, with the message
cat >away.yaml <<'EOF'
shadesweep: 1
name: away
scene: shapes
renderers: [deferred, forward-spml]
resolution: 64x48
trials: 2
warmup: {frames: 0}
duration: {frames: 2}
clock: fixed
camera: {target: [0, 1000, 0]}
EOF
rc=0
"$SHADESWEEP" run -o out/away away.yaml >away.log 2>&1 || rc=$?
[ "$rc" = 1 ] || { cat away.log; fail "expected exit 1 when every run is empty, got $rc"; }
want="the scene covers no pixel of the first measured frame (schedule time 0 s): the camera sees none of its 10 objects; allow_empty: true measures it anyway"
[ "$(grep -cF "$want" away.log)" = 2 ] || { cat away.log; fail "expected the message once per run"; }
rows out/away >away.txt
# the first trial measured coverage 0; the run ends there, and its second trial is
# failed:not-run, with no coverage
[ "$(cat away.txt)" = "$(printf 'deferred,1,failed:empty,0.000000\ndeferred,1,failed:not-run,\nforward-spml,1,failed:empty,0.000000\nforward-spml,1,failed:not-run,')" ] ||
  { cat away.txt; fail "expected failed:empty, coverage 0, and the run ended after its first trial"; }

# 3. the same with allow_empty: measured, coverage 0
sed 's/^name: away$/name: away-allowed\nallow_empty: true/' away.yaml >allowed.yaml
"$SHADESWEEP" run -o out/allowed allowed.yaml >allowed.log 2>&1 || { cat allowed.log; fail "allow_empty: the run failed"; }
rows out/allowed >allowed.txt
[ "$(grep -c ',ok,0.000000$' allowed.txt)" = 4 ] || { cat allowed.txt; fail "allow_empty: expected 4 ok trials, coverage 0"; }

# 4. covered but black (a closed box of a black material, no sky): failed:empty
"$PYTHON" - <<'PY'
v = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
faces = [(1, 3, 4, 2), (5, 6, 8, 7), (1, 2, 6, 5), (3, 7, 8, 4), (1, 5, 7, 3), (2, 4, 8, 6)]
with open("black.obj", "w") as f:
    f.write("mtllib black.mtl\n" + "".join("v %d %d %d\n" % p for p in v) + "usemtl black\n")
    f.write("".join("f %d %d %d %d\n" % q for q in faces))
open("black.mtl", "w").write("newmtl black\nKd 0 0 0\nKa 0 0 0\nKs 0 0 0\n")
PY
cat >black.yaml <<'EOF'
shadesweep: 1
name: black
scene: {file: black.obj}
renderers: [forward-spml]
resolution: 32x24
warmup: {frames: 0}
duration: {frames: 1}
clock: fixed
EOF
rc=0
"$SHADESWEEP" run -o out/black black.yaml >black.log 2>&1 || rc=$?
[ "$rc" = 1 ] || { cat black.log; fail "a black frame: expected exit 1, got $rc"; }
grep -qE 'the first measured frame \(schedule time 0 s\) is black: no channel of any pixel above 1 of 255, with [0-9.]+% of the screen covered; allow_empty: true measures it anyway' black.log ||
  { cat black.log; fail "a black frame: expected its message"; }
grep -q ',failed:empty,0\.[0-9]*[1-9]' <(rows out/black) ||
  { rows out/black; fail "a black frame: expected failed:empty with some coverage"; }
echo "empty_frame: ok"
