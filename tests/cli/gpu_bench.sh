#!/usr/bin/env bash
# scripts/gpu-bench.sh at smoke size on whatever EGL devices this machine has (here
# llvmpipe's software device): info for every device, the probe's device.yaml (kept on
# --resume, copied into every folder), the renderer benchmark, the deferred families over
# resolution and msaa, and seed 003's experiments cut to the budget, the report and
# clocks.txt; --resume runs nothing again; an existing folder without --resume and a
# spent budget are refused with a message.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
export SHADESWEEP
# draw_limit 0.1 s a run, for the first run and the resume alike (the checks read no frame
# count; the smoke default of 2 s a run was most of this test's time)
export GPU_BENCH_SET="draw_limit=0.1"
# modern-culling's ~200 runs are the GPU's to measure: here only its cut is checked
export GPU_BENCH_ONLY="renderers-deferred renderers-forward families-msaa s003-exp2 s003-exp1"
B="$SOURCE_ROOT/scripts/gpu-bench.sh"
"$B" --smoke gb >gb.out 2>gb.err || fail "gpu-bench: rc $? $(tail -5 gb.err)"
n=$(sed -n 's/^gpu-bench: \([0-9]*\) EGL device(s)$/\1/p' gb.out)
[ -n "$n" ] || fail "no device count: $(head -3 gb.out)"
[ "$n" -eq "$("$SHADESWEEP" info | sed -n 's/^egl_devices: //p')" ] || fail "device count $n"
for ((i = 0; i < n; i++)); do
  grep -q "^renderer: " "gb/info-device-$i.txt" || fail "info-device-$i.txt: $(cat "gb/info-device-$i.txt")"
  grep -q "^== device $i: " gb.out || fail "device $i not printed"
done
if grep -qiE 'renderer: .*(llvmpipe|softpipe)' gb/info-device-*.txt && \
   ! grep -qviE 'renderer: .*(llvmpipe|softpipe)|^[^r]' gb/info-device-*.txt; then
  grep -qE "^gpu-bench: no hardware EGL device; running on llvmpipe's software device \(device [0-9]+\)$" gb.out ||
    fail "no fallback message: $(grep '^gpu-bench' gb.out)"
fi
# the cut manifests: one trial, experiment 1 at 30 s a run, names kept
grep -qx "trials: 1" gb/manifests/s003-exp1.yaml || fail "exp1 trials"
grep -qx "duration: {seconds: 30}" gb/manifests/s003-exp1.yaml || fail "exp1 duration"
grep -qx "name: s003-exp2" gb/manifests/s003-exp2.yaml || fail "exp2 name"
grep -qx "resolution: 1280x720" gb/manifests/modern-culling.yaml || fail "modern-culling resolution"
grep -qx "trials: 1" gb/manifests/modern-culling.yaml || fail "modern-culling trials"
"$SHADESWEEP" validate gb/manifests/modern-culling.yaml >/dev/null || fail "modern-culling cut invalid"
[ -d gb/modern-culling ] && fail "GPU_BENCH_ONLY ran modern-culling"
# every run ok, one smoke trial each
check() {  # check NAME RUNS
  local rows ok
  rows=$(tail -n +2 "gb/$1/summary.csv" | wc -l)
  ok=$(tail -n +2 "gb/$1/summary.csv" | grep -c ',ok,' || true)
  [ "$rows" -eq "$2" ] && [ "$ok" -eq "$2" ] || fail "$1: $rows rows, $ok ok, want $2"
  [ -s "gb/$1/summary.md" ] || fail "$1: no summary.md"
  grep -q "^$1-smoke: $2 runs," gb.out || fail "$1: no end-of-run table"
}
# the probe first: OUTDIR/device.yaml, read back as YAML, and each folder's copy of it
grep -q "^gpu-bench: device profile: gb/device.yaml (" gb.out || fail "no probe: $(grep -i probe gb.out gb.err)"
"$PYTHON" - <<'PY' || fail "device.yaml"
import yaml
d = yaml.safe_load(open("gb/device.yaml"))
for m in ("renderers-deferred", "renderers-forward", "families-msaa", "s003-exp2", "s003-exp1"):
    assert yaml.safe_load(open(f"gb/{m}/device.yaml"))["key"] == d["key"], m
PY
[ "$(grep -c ': no GPU clocks (no NVIDIA device through NVML)$' gb/clocks.txt)" -eq 5 ] ||
  fail "clocks.txt: $(cat gb/clocks.txt)"
check renderers-deferred 12
check renderers-forward 6
check families-msaa 10
check s003-exp2 2
check s003-exp1 6
grep -q "^| s003-exp1 | run | 6 |" gb/report.md || fail "report: s003-exp1"
grep -q "^| s003-exp2 | run | 2 |" gb/report.md || fail "report: s003-exp2"
grep -qF "gb/renderers-forward/summary.md" gb/report.md || fail "report does not point at the bench's table"
# --resume: every run kept, nothing run again
"$B" --smoke --resume gb >re.out 2>re.err || fail "resume: $(tail -3 re.err)"
for k in "12 of 12" "6 of 6" "2 of 2" "6 of 6"; do
  grep -q "resuming: $k runs already complete" re.err || fail "resume: $(grep resuming re.err)"
done
grep -q "^run " re.err && fail "resume ran a run: $(grep '^run ' re.err | head -1)"
grep -qx "gpu-bench: device profile kept: gb/device.yaml" re.out || fail "resume probed again: $(cat re.out | head -5)"
# an existing folder without --resume; a spent budget
set +e
"$B" --smoke gb >x.out 2>x.err; rc=$?
set -e
[ $rc -eq 2 ] && grep -qx "gpu-bench: gb exists; --resume finishes it, or name another folder" x.err ||
  fail "existing folder: rc $rc $(cat x.err)"
set +e
GPU_BENCH_BUDGET_S=0 "$B" --smoke --resume gb >y.out 2>y.err; rc=$?
set -e
[ $rc -eq 1 ] || fail "spent budget: rc $rc"
grep -qx "gpu-bench: the 0 s budget is spent before renderers-deferred" y.err || fail "budget: $(cat y.err)"
set +e
GPU_BENCH_ONLY="nope" "$B" --smoke --resume gb >z.out 2>z.err; rc=$?
set -e
[ $rc -eq 2 ] && grep -q "^gpu-bench: GPU_BENCH_ONLY: no manifest nope (modern-culling renderers-deferred" z.err ||
  fail "GPU_BENCH_ONLY nope: rc $rc $(cat z.err)"
grep -qx "gpu-bench: to finish: GPU_BENCH_SET='draw_limit=0.1' GPU_BENCH_ONLY='$GPU_BENCH_ONLY' scripts/gpu-bench.sh --resume --smoke gb" y.err ||
  fail "budget: $(cat y.err)"
echo "gpu-bench: ok"
