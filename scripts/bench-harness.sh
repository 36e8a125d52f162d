#!/usr/bin/env bash
# Benchmark of the harness itself (not a test): runs experiments/bench-harness.yaml
# on EGL + llvmpipe and prints a markdown table for the README: FPS of the null
# renderer at 64x64 and the runner's bookkeeping per frame (timing, CSV rows,
# queries read back, per-second binning and statistics), each as mean and 95% CI
# over trials.  Usage: scripts/bench-harness.sh [OUTDIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/out/bench-harness}
. "$root/scripts/bench-common.sh"
"$root/build/runner/shadesweep" run --force -o "$out" "$root/experiments/bench-harness.yaml"
bench_table "$out" <<'PY'
import sys
from shadesweep_report.bench import load, mean_ci, print_header, print_machine
out = sys.argv[1]
rows, plan = load(out)
print_machine(out)
print_header("sync", "trials", "FPS (mean ± 95% CI)", "frame time us", "bookkeeping us/frame")
for rid in dict.fromkeys(r["run_id"] for r in rows):
    rs = [r for r in rows if r["run_id"] == rid and r["status"] == "ok"]
    fps = mean_ci(r["fps_mean"] for r in rs)
    ft = mean_ci(r["frametime_mean_us"] for r in rs)
    hk = mean_ci(r["harness_us_mean"] for r in rs)
    print(f"| {plan[rid]['sync']} | {len(rs)} | {fps[0]:.0f} ± {fps[1]:.0f} | "
          f"{ft[0]:.1f} ± {ft[1]:.1f} | {hk[0]:.2f} ± {hk[1]:.2f} |")
PY
