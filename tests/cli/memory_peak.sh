#!/usr/bin/env bash
# Memory measured (issue 42), README "Memory", docs/reliability.md:
#  A. a trial killed by its timeout records its peak resident size (the parent's wait4
#     ru_maxrss of the child it killed) in meta.yaml memory.peak_rss_mb and
#     timing.vm_hwm_kb, not -1. One trial, so `timeout` means the same per run or per
#     trial; debug.busy_us makes each frame take a second.
#  B. the estimate against the measured peak of the heaviest cases a CI run affords, one
#     frame each: the largest built-in scene (canyon), thousands of lights drawn one by
#     one (deferred) and in light lists (clustered), the biggest G-buffer (reference) at
#     4x MSAA (llvmpipe's most), a textured file scene of the assimp corpus: every
#     peak within 1/1.5 .. 1.5 of its estimate (skipped in the sanitizer build).
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"

# --- A. a killed trial's peak --------------------------------------------------------
cat > killed.yaml <<'YAML'
shadesweep: 1
name: killed
scene: shapes
renderers: [forward-spml]
resolution: 32x32
trials: 1
warmup: {frames: 0}
duration: {frames: 100}
clock: fixed
timeout: 2
debug: {busy_us: 1000000}
YAML
set +e
"$SHADESWEEP" run killed.yaml >out.txt 2>err.txt; rc=$?
set -e
[ $rc -eq 1 ] || fail "A: a timed-out run exits 1, got $rc: $(cat err.txt)"
"$PYTHON" - <<'PY'
import csv, sys, yaml
def fail(m): print("FAIL: A:", m, file=sys.stderr); sys.exit(1)
rows = list(csv.DictReader(open("out/killed/summary.csv")))
if [r["status"] for r in rows] != ["failed:timeout"]: fail(f"statuses {[r['status'] for r in rows]}")
meta = yaml.safe_load(open(f"out/killed/runs/{rows[0]['run_id']}/meta.yaml"))
mem, hwm = meta["memory"], meta["timing"]["vm_hwm_kb"]
# a GL context on llvmpipe keeps some 90 MiB resident; nothing here needs 4 GiB
if not 40 <= mem["peak_rss_mb"] <= 4096: fail(f"peak_rss_mb {mem}")
if abs(hwm / 1024 - mem["peak_rss_mb"]) > 1: fail(f"vm_hwm_kb {hwm} is not peak_rss_mb {mem}")
if not mem["estimate_mb"] > 0: fail(f"estimate {mem}")
PY

# --- B. the estimate against the peak ------------------------------------------------
# (not in the sanitizer build: ASan's shadow memory and quarantine double every peak)
if grep -qa __asan_init "$SHADESWEEP"; then
  echo "memory_peak: sanitizer build: B is skipped" >&2
  echo ok
  exit 0
fi
truck=/usr/share/assimp/models/glTF/CesiumMilkTruck/CesiumMilkTruck.gltf
[ -f "$truck" ] || fail "B: assimp-testmodels is not installed (scripts/setup.sh installs it)"
# case: name, then the manifest's lines that differ
cases=(
  "baseline|scene: shapes|renderers: [null]|resolution: 16x16"
  "canyon|scene: canyon|renderers: [deferred]|resolution: 256x256"
  "lights-deferred|scene: shapes|renderers: [deferred]|resolution: 128x128|lights: {count: 4096}"
  "lights-clustered|scene: shapes|renderers: [clustered]|resolution: 256x256|lights: {count: 4096}"
  "lights-multipass|scene: shapes|renderers: [forward-mpml]|resolution: 128x128|lights: {count: 1024}"
  "gbuffer-msaa|scene: shapes|renderers: [deferred]|resolution: 512x512|gbuffer: reference|msaa: 4"
  "textured-file|scene: {file: \"$truck\"}|renderers: [forward-spml]|resolution: 128x128"
)
for c in "${cases[@]}"; do
  name=${c%%|*}
  { printf 'shadesweep: 1\nname: %s\ntrials: 1\nwarmup: {frames: 0}\nduration: {frames: 1}\nclock: fixed\n' "$name"
    tr '|' '\n' <<<"${c#*|}"; } >"$name.yaml"
  "$SHADESWEEP" run "$name.yaml" >/dev/null 2>"$name.err" || fail "B: $name: $(cat "$name.err")"
done
"$PYTHON" - "${cases[@]%%|*}" <<'PY'
import csv, sys, yaml
bad = []
print("case | estimate MiB | peak MiB | peak/estimate")
for name in sys.argv[1:]:
    rows = list(csv.DictReader(open(f"out/{name}/summary.csv")))
    mem = yaml.safe_load(open(f"out/{name}/runs/{rows[0]['run_id']}/meta.yaml"))["memory"]
    r = mem["peak_rss_mb"] / mem["estimate_mb"]
    print(f"{name} | {mem['estimate_mb']} | {mem['peak_rss_mb']} | {r:.2f}")
    if not 1 / 1.5 <= r <= 1.5: bad.append(name)
if bad: print("FAIL: B: peak/estimate outside 1/1.5..1.5:", bad, file=sys.stderr); sys.exit(1)
PY
echo ok
