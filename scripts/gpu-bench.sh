#!/usr/bin/env bash
# A GPU session in one command (issue 15, item 9):
#   scripts/gpu-bench.sh [--smoke] [--resume] OUTDIR
# 1. `shadesweep info` for every EGL device (OUTDIR/info-device-N.txt);
# 2. on the first hardware device (else, saying so, the software one): the culling
#    engines since 2016 (experiments/modern-culling.yaml at 1280x720), the renderer
#    benchmark (experiments/renderers-{deferred,forward}.yaml), the deferred families over
#    resolution and msaa (experiments/families-msaa.yaml) and seed 003's experiments at
#    1280x720, cut to fit 8 minutes (one trial each, experiment 1 at 30 s a run; the cut
#    manifests in OUTDIR/manifests/ under the experiments' names, for the report);
#    First `shadesweep probe` on that device (--smoke: --quick): OUTDIR/device.yaml, and
#    the cached profile that each run's folder copies as its own device.yaml; the GPU
#    clocks of every trial (NVML) are in each run's meta.yaml and summary.csv;
# 3. the report over OUTDIR (OUTDIR/report.md) and each folder's ranked table, and
#    OUTDIR/clocks.txt: each folder's SM clocks over its trials (or why there are none).
# --resume keeps the complete runs of an interrupted OUTDIR; when the budget
# (GPU_BENCH_BUDGET_S, default 480 s) runs out, the run in progress is stopped and the
# script says how to go on. --smoke (GPU_BENCH_SMOKE=1): every manifest's smoke variant.
# GPU_BENCH_SET="KEY=VALUE ..." adds --set to every run. SHADESWEEP names the program
# (default build/runner/shadesweep, built if needed). GPU_BENCH_ONLY="NAME ..." runs only
# those of the manifests (every one is still cut). Exit status: 0 every run ok, 1 some
# run failed or the budget ran out, 2 bad usage.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
smoke=${GPU_BENCH_SMOKE:-0} resume=0 out=""
budget=${GPU_BENCH_BUDGET_S:-480}
usage="usage: scripts/gpu-bench.sh [--smoke] [--resume] OUTDIR"
while [ $# -gt 0 ]; do
  case $1 in
    --smoke) smoke=1; shift ;;
    --resume) resume=1; shift ;;
    -h|--help) echo "$usage"; exit 0 ;;
    -*) echo "gpu-bench: unknown option $1 ($usage)" >&2; exit 2 ;;
    *) [ -z "$out" ] || { echo "gpu-bench: one OUTDIR only ($usage)" >&2; exit 2; }
       out=$1; shift ;;
  esac
done
[ -n "$out" ] || { echo "gpu-bench: $usage" >&2; exit 2; }
if [ -e "$out" ] && [ $resume -eq 0 ] && [ -n "$(ls -A "$out" 2>/dev/null)" ]; then
  echo "gpu-bench: $out exists; --resume finishes it, or name another folder" >&2
  exit 2
fi
exe=${SHADESWEEP:-}
if [ -z "$exe" ]; then
  "$root/scripts/build.sh" "$root/build" >&2
  exe="$root/build/runner/shadesweep"
fi
mkdir -p "$out/manifests"
start=$SECONDS

# 1. every EGL device
ndev=$("$exe" info 2>/dev/null | sed -n 's/^egl_devices: \([0-9][0-9]*\)$/\1/p')
ndev=${ndev:-0}
echo "gpu-bench: $ndev EGL device(s)"
hw=-1 sw=-1
for ((i = 0; i < ndev; i++)); do
  if "$exe" info --device "$i" >"$out/info-device-$i.txt" 2>&1; then
    r=$(sed -n 's/^renderer: //p' "$out/info-device-$i.txt")
    echo "== device $i: $r"
    cat "$out/info-device-$i.txt"
    if grep -qiE 'llvmpipe|softpipe|swrast|lavapipe' <<<"$r"; then
      [ $sw -ge 0 ] || sw=$i
    else
      [ $hw -ge 0 ] || hw=$i
    fi
  else
    echo "== device $i: no context: $(tail -1 "$out/info-device-$i.txt")"
  fi
done
dev=()
if [ $hw -ge 0 ]; then
  echo "gpu-bench: running on device $hw (hardware)"
  dev=(--device "$hw")
elif [ $sw -ge 0 ]; then
  echo "gpu-bench: no hardware EGL device; running on llvmpipe's software device (device $sw)"
  dev=(--device "$sw")
else
  echo "gpu-bench: no usable EGL device; running on Mesa's surfaceless platform"
fi

# The device profile first (issue 38): the bounds' denominators, kept with the results.
# A profile already cached for this device and driver is measured again all the same:
# the budget pays about a minute (--smoke: seconds) for a profile of this very session.
if [ -s "$out/device.yaml" ] && [ $resume -eq 1 ]; then
  echo "gpu-bench: device profile kept: $out/device.yaml"
else
  probe=()
  [ "$smoke" -eq 1 ] && probe+=(--quick)
  if "$exe" probe "${dev[@]}" "${probe[@]}" >"$out/device.yaml.tmp" 2>"$out/probe.log"; then
    mv "$out/device.yaml.tmp" "$out/device.yaml"
    echo "gpu-bench: device profile: $out/device.yaml ($((SECONDS - start)) s)"
  else
    rm -f "$out/device.yaml.tmp"
    echo "gpu-bench: the probe failed, the runs go on without a device profile: $(tail -1 "$out/probe.log")" >&2
  fi
fi

# 2. the manifests, cut to the budget
cut() {  # cut NAME SED-SCRIPT: OUTDIR/manifests/NAME.yaml from experiments/NAME.yaml
  sed -e "$2" "$root/experiments/$1.yaml" >"$out/manifests/$1.yaml"
}
cut modern-culling 's/^trials: 3$/trials: 1/; s/^resolution: 160x90$/resolution: 1280x720/'
cut renderers-deferred 's/^trials: 3$/trials: 1/'
cut renderers-forward 's/^trials: 3$/trials: 1/'
cut families-msaa ''
cut s003-exp2 's/^trials: 3$/trials: 1/'
cut s003-exp1 's/^trials: 3$/trials: 1/; s/^duration: {seconds: 60}$/duration: {seconds: 30}/'
opts=()
[ "$smoke" -eq 1 ] && opts+=(--smoke)
sets=()
for kv in ${GPU_BENCH_SET:-}; do sets+=(--set "$kv"); done
status=0
ms=(modern-culling renderers-deferred renderers-forward families-msaa s003-exp2 s003-exp1)
if [ -n "${GPU_BENCH_ONLY:-}" ]; then
  for m in $GPU_BENCH_ONLY; do
    [ -f "$out/manifests/$m.yaml" ] || { echo "gpu-bench: GPU_BENCH_ONLY: no manifest $m (${ms[*]})" >&2; exit 2; }
  done
  read -r -a ms <<<"$GPU_BENCH_ONLY"
fi
for m in "${ms[@]}"; do
  left=$((budget - (SECONDS - start)))
  if [ $left -le 0 ]; then
    echo "gpu-bench: the ${budget} s budget is spent before $m" >&2
    status=1
    break
  fi
  r=()
  [ -f "$out/$m/plan.csv" ] && r=(--resume)
  echo "== $m (${left} s of the budget left)"
  set +e
  timeout -s INT -k 30 "$left" "$exe" run "${opts[@]}" "${sets[@]}" "${dev[@]}" "${r[@]}" -o "$out/$m" \
    "$out/manifests/$m.yaml"
  rc=$?
  set -e
  case $rc in
    0) ;;
    1) status=1 ;;
    124|130) echo "gpu-bench: the ${budget} s budget ran out during $m" >&2; status=1; break ;;
    *) echo "gpu-bench: $m: shadesweep run exited $rc" >&2; status=1 ;;
  esac
done
if [ $status -ne 0 ] && [ $((SECONDS - start)) -ge "$budget" ]; then
  echo "gpu-bench: to finish: ${GPU_BENCH_SET:+GPU_BENCH_SET='$GPU_BENCH_SET' }${GPU_BENCH_ONLY:+GPU_BENCH_ONLY='$GPU_BENCH_ONLY' }scripts/gpu-bench.sh --resume${opts:+ ${opts[*]}} $out" >&2
fi

# 3. the report, and the clocks of each folder's trials (summary.csv's sm_clock_mhz)
"$exe" report "$out" || status=1
python3 - "$out" "${ms[@]}" >"$out/clocks.txt" <<'PY' || echo "gpu-bench: no clocks.txt" >&2
import csv, os, statistics, sys
out = sys.argv[1]
for m in sys.argv[2:]:
    path = os.path.join(out, m, "summary.csv")
    if not os.path.exists(path):
        continue
    with open(path, newline="") as f:
        mhz = [float(r["sm_clock_mhz"]) for r in csv.DictReader(f)
               if r.get("trial") and r.get("sm_clock_mhz")]
    if mhz:
        print(f"{m}: SM clock median {statistics.median(mhz):.0f} MHz, {min(mhz):.0f} .. "
              f"{max(mhz):.0f} over {len(mhz)} trials (NVML; each run's meta.yaml has the rest)")
    else:
        print(f"{m}: no GPU clocks (no NVIDIA device through NVML)")
PY
cat "$out/clocks.txt" 2>/dev/null || true
echo "gpu-bench: $out/report.md; $((SECONDS - start)) s"
exit $status
