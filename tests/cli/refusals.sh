#!/usr/bin/env bash
# Conditions that would make every run fail or mean nothing are refused by
# `validate` and `run` before anything is written (exit 2, the reason named):
# times past the run's end, placement scene without authored lights, near not
# below far, quadratic attenuation with a = b = c = 0, an empty name, more depth slices
# than clustered's light grid holds. What fails on some
# GL only (forward-spml's uniform block, 8 samples, a side past 16384) is a warning that
# validate, list and run print.
. "$(dirname "$0")/lib.sh"
cd "$T"
base='shadesweep: 1
name: refused
scene: shapes
renderers: [null]
resolution: 32x32'
check() {   # name, the message stderr must hold
  local f=$1 want=$2 rc
  for cmd in validate run; do
    set +e
    "$SHADESWEEP" $cmd "$f.yaml" >out.txt 2>err.txt; rc=$?
    set -e
    [ $rc -eq 2 ] || fail "$cmd $f.yaml: exit $rc, want 2: $(cat err.txt)"
    grep -qF -- "$want" err.txt || fail "$cmd $f.yaml: want '$want' in: $(cat err.txt)"
    [ ! -e out ] || fail "$cmd $f.yaml wrote out/"
  done
}
printf '%s\nduration: {seconds: 2}\noutputs: {screenshots: [1, 2.5]}\n' "$base" >shot.yaml
check shot "shot.yaml: outputs.screenshots: expected a time the run reaches (duration {seconds: 2}: frames start before 2 s), found 2.5"
printf '%s\nduration: {frames: 10}\nclock: fixed\nstep: 0.1\nerror: {reference: {renderer: forward-spml}, at: [0.9, 1]}\n' "$base" >at.yaml
check at "at.yaml: error.at: expected a time the run reaches (duration {frames: 10} at step 0.1 s: the last frame is at 0.9 s), found 1 in run"
printf '%s\nduration: {frames: 2}\nlights: {count: 4, attenuation: quadratic, quadratic: {a: 0, b: 0, c: 0}}\n' "$base" >quad.yaml
check quad "quad.yaml: lights.quadratic: expected a, b and c not all 0"
printf '%s\nduration: {frames: 2}\nlights: {placement: scene}\n' "$base" >scene.yaml
check scene "scene.yaml: scene: expected a scene the runs can render, found: scene 'shapes' has no authored lights"
printf '%s\nduration: {frames: 2}\nsweep: {camera.near: [1, 10]}\ncamera: {far: 5}\n' "$base" >near.yaml
check near "near.yaml: scene: expected a scene the runs can render, found: camera.far: expected a finite number > near (10), found 5"
# clustered's depth slices past the 1024 its light grid holds: near 0.01 and far 1e6 at
# clustered.slices 64 make 1031 (at the default 24, experiments/extremes-camera.yaml's,
# 393), refused in either design with the message the renderer would fail with
slices="${base/\[null\]/[clustered]}"
msg="clustered.slices: expected depth slices the light grid holds, found: clustered: 1031 depth slices from near 0.01 to far 1e+06 (each 1.018 times deeper, clustered.slices 64): at most 1024; raise near or lower clustered.slices (run"
printf '%s\nduration: {frames: 2}\ncamera: {near: 0.01, far: 1000000}\nclustered: {slices: 64}\n' "$slices" >slices.yaml
check slices "slices.yaml: $msg"
printf '%s\nduration: {frames: 2}\ncamera: {near: 0.01, far: 1000000}\nclustered: {slices: 64, shading: deferred}\n' "$slices" >slices_d.yaml
check slices_d "slices_d.yaml: $msg"
"$SHADESWEEP" validate --set clustered.slices=24 slices.yaml >/dev/null || fail "393 slices are valid"
printf 'shadesweep: 1\nname: ""\nscene: shapes\nrenderers: [null]\nduration: {frames: 2}\n' >name.yaml
check name "name.yaml:2:7: name: expected a name of 1..63 characters from a-z, 0-9 and -, found ''"
# the boundary is accepted: the last frame of {frames: 10} at step 0.1 is at 0.9 s
printf '%s\nduration: {frames: 10}\nclock: fixed\nstep: 0.125\noutputs: {screenshots: [1.125]}\n' "$base" >edge.yaml
"$SHADESWEEP" validate edge.yaml >/dev/null || fail "a screenshot at the last frame is valid"

# forward-spml's uniform block past the 16 KiB every GL guarantees (204 lights): named
# by validate --no-gl and list as a warning, never for storage or 204 (against the GL,
# llvmpipe's 819: tests/cli/validate_gl.sh)
spml='shadesweep: 1
name: spml
scene: shapes
renderers: [forward-spml, deferred]
resolution: 32x32
duration: {frames: 2}'
printf '%s\nsweep: {lights.count: [204, 205, 300]}\n' "$spml" >spml.yaml
"$SHADESWEEP" validate --no-gl spml.yaml >out.txt 2>err.txt || fail "validate spml.yaml: $(cat err.txt)"
grep -qF "spml.yaml: warning: forward.light_buffer: 2 runs (" err.txt &&
  grep -qF "ask for up to 300 lights in forward-spml's uniform block, past the 204 lights of the 16384 bytes every GL has; they fail where" err.txt ||
  fail "validate spml.yaml: no warning: $(cat err.txt)"
"$SHADESWEEP" list spml.yaml >/dev/null 2>err.txt && grep -qF "warning: forward.light_buffer" err.txt ||
  fail "list spml.yaml: no warning"
# 8 samples and a 20000-pixel side (or 5000 with a 4x supersampled reference): past the
# 4 samples and 16384 pixels every GL has, named the same way
"$SHADESWEEP" validate --no-gl --set msaa=8 spml.yaml >/dev/null 2>err.txt &&
  grep -qF "spml.yaml: warning: msaa: 6 runs (" err.txt &&
  grep -qF "ask for 8 samples a pixel (or their error reference does), past the 4 samples every GL has" err.txt ||
  fail "msaa 8: $(cat err.txt)"
"$SHADESWEEP" validate --no-gl --set resolution=5000x16 --set 'error={reference: {renderer: forward-spml, supersample: 4}, at: [0]}' \
  spml.yaml >/dev/null 2>err.txt &&
  grep -qF "ask for a framebuffer 20000 pixels a side (error.reference.supersample included), past the 16384 pixels every GL has" err.txt ||
  fail "20000 pixels: $(cat err.txt)"
printf '%s\nsweep: {lights.count: [204, 300]}\nforward: {light_buffer: storage}\n' "$spml" >st.yaml
printf '%s\nlights: {count: 204}\n' "$spml" >fits.yaml
for f in st fits; do
  "$SHADESWEEP" validate $f.yaml >/dev/null 2>err.txt || fail "validate $f.yaml"
  [ ! -s err.txt ] || fail "$f.yaml: want no warning: $(cat err.txt)"
done

# where only the run knows its end (a wall clock counting frames), a time it never
# reaches fails the run instead of letting an error gate pass on nothing compared
need_gl
printf '%s\nduration: {frames: 3}\nerror: {reference: {renderer: forward-spml}, at: [0, 100], max_rmse: 0.5}\n' "$base" >late.yaml
"$SHADESWEEP" validate late.yaml >/dev/null || fail "late.yaml is valid: only the run can tell"
set +e; "$SHADESWEEP" run late.yaml -o out >run.txt 2>&1; rc=$?; set -e
[ $rc -eq 1 ] || fail "run late.yaml: exit $rc, want 1: $(cat run.txt)"
grep -q "^refused,.*,failed:error,error.at time 100 s never reached: the trial's last frame was at schedule time" out/summary.csv \
  || fail "summary of late.yaml: $(cat out/summary.csv)"
# the run checks against its GL too: on llvmpipe (819 lights) its 300-light run
# succeeds with no warning (the warning against every GL only when no context came
# within 1 s, after a note that says so)
printf '%s\nlights: {count: 300}\n' "$spml" >spml300.yaml
"$SHADESWEEP" run spml300.yaml -o spml >/dev/null 2>err.txt || fail "run spml300.yaml: $(cat err.txt)"
if grep -qF "spml300.yaml: note: not checked against this GL (" err.txt; then
  grep -qF "warning: forward.light_buffer: 1 run (" err.txt || fail "run: no warning: $(cat err.txt)"
else
  ! grep -q "warning" err.txt || fail "run: a warning on a GL that holds 300 lights: $(cat err.txt)"
fi
