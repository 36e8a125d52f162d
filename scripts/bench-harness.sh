#!/usr/bin/env bash
# Benchmark of the harness itself (not a test): runs experiments/bench-harness.yaml
# on EGL + llvmpipe and prints a markdown table for the README: FPS of the null
# renderer at 64x64 and the runner's bookkeeping per frame (timing, CSV rows,
# queries read back, per-second binning and statistics), each as mean and 95% CI
# over trials.  Usage: scripts/bench-harness.sh [OUTDIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/out/bench-harness}
"$root/scripts/setup.sh"
"$root/scripts/build.sh" "$root/build"
export LIBGL_ALWAYS_SOFTWARE=1
"$root/build/runner/shadesweep" run --force -o "$out" "$root/experiments/bench-harness.yaml"
/usr/bin/python3 - "$out" <<'PY'
import csv, glob, math, os, statistics, sys
import yaml
out = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(out, "summary.csv"))))
plan = {p["run_id"]: p for p in csv.DictReader(open(os.path.join(out, "plan.csv")))}
meta = yaml.safe_load(open(glob.glob(os.path.join(out, "runs", "*", "meta.yaml"))[0]))
T975 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571}
def mean_ci(xs):
    m = statistics.mean(xs)
    if len(xs) < 2: return m, float("nan")
    return m, T975.get(len(xs) - 1, 2.0) * statistics.stdev(xs) / math.sqrt(len(xs))
print(f"GL renderer: {meta['gl']['renderer']}; CPU: {meta['host']['cpu']}, "
      f"{meta['host']['threads']} threads; shadesweep {meta['shadesweep']['commit']}")
print()
print("| sync | trials | FPS (mean ± 95% CI) | frame time us | bookkeeping us/frame |")
print("|---|---|---|---|---|")
for rid in dict.fromkeys(r["run_id"] for r in rows):
    rs = [r for r in rows if r["run_id"] == rid and r["status"] == "ok"]
    fps = mean_ci([float(r["fps_mean"]) for r in rs])
    ft = mean_ci([float(r["frametime_mean_us"]) for r in rs])
    hk = mean_ci([float(r["harness_us_mean"]) for r in rs])
    print(f"| {plan[rid]['sync']} | {len(rs)} | {fps[0]:.0f} ± {fps[1]:.0f} | "
          f"{ft[0]:.1f} ± {ft[1]:.1f} | {hk[0]:.2f} ± {hk[1]:.2f} |")
PY
