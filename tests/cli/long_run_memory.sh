#!/usr/bin/env bash
# Long runs without growing memory (issue 15, item 8): the statistics take each frame
# as it ends, in memory fixed at the start of the run (results/stream_stats.h: about
# 0.6 MB), so the peak resident size of a run's process (meta.yaml timing.vm_hwm_kb)
# of 200000 tiny frames is that of one of 20000 to within 2 MiB. Keeping every frame
# (72 bytes each, as the run loop did) would add about 16 MiB.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
for n in 20000 200000; do
  cat > m$n.yaml <<YAML
shadesweep: 1
name: m$n
scene: empty
renderers: [null]
resolution: 8x8
duration: {frames: $n}
outputs: {frames: false}
YAML
  "$SHADESWEEP" run -o out/$n m$n.yaml >out.txt 2>err.txt || fail "$n frames: $(cat err.txt)"
done
"$PYTHON" - <<'PY'
import csv, glob, math, sys, yaml
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
hwm = {}
for n in (20000, 200000):
    [d] = glob.glob(f"out/{n}/runs/*/")
    [s] = list(csv.DictReader(open(d + "summary.csv")))
    if s["status"] != "ok" or int(s["frames"]) != n: fail(f"{n}: {s}")
    bins = list(csv.DictReader(open(d + "seconds.csv")))
    if sum(int(b["frames"]) for b in bins) != n: fail(f"{n}: seconds.csv does not hold every frame")
    conv = list(csv.DictReader(open(d + "convergence.csv")))
    m = float(s["measured_s"])
    want = math.floor(m) + (0 if m == math.floor(m) and m >= 1 else 1)
    if len(conv) != want or int(conv[-1]["frames"]) != n: fail(f"{n}: {len(conv)} convergence rows")
    hwm[n] = yaml.safe_load(open(d + "meta.yaml"))["timing"]["vm_hwm_kb"]
    if not hwm[n] > 0: fail(f"{n}: vm_hwm_kb {hwm[n]}")
if abs(hwm[200000] - hwm[20000]) > 2048:
    fail(f"peak resident size {hwm[20000]} kB at 20000 frames, {hwm[200000]} kB at 200000")
print(f"VmHWM {hwm[20000]} kB / {hwm[200000]} kB")
PY
