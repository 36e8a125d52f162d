#!/usr/bin/env bash
# Benchmark (not a test): the renderers on the shapes scene at 640x360 with 1, 16 and
# 256 point lights (experiments/renderers-*.yaml), on EGL + llvmpipe, and a markdown
# table for the README: frame time (mean ± 95% CI over trials), draw calls, state
# changes and fragment-shader invocations per frame, per renderer and light-volume mode.
#   scripts/bench-renderers.sh [OUTDIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/out/bench-renderers}
. "$root/scripts/bench-common.sh"
for m in deferred forward; do
  "$root/build/runner/shadesweep" run --force -o "$out/$m" "$root/experiments/renderers-$m.yaml"
done
bench_table "$out" <<'PY'
import sys
from shadesweep_report.bench import grouped, load, mean_ci, print_header, print_machine
out = sys.argv[1]
rows, plans = load(out, ("deferred", "forward"))
print_machine(out)
print_header("lights", "renderer", "light volumes", "frame time ms", "draw calls",
             "state changes", "fragments (M)")
def key(r):
    p = plans[r["run_id"]]
    mode = p["deferred.light_volumes"] if r["renderer"] == "deferred" else ""
    return (int(p["lights.count"]), r["renderer"], mode)
for k, rs, status in grouped(rows, key):
    if not rs:
        print(f"| {k[0]} | {k[1]} | {k[2]} | failed: {status} | | | |")
        continue
    m, ci = mean_ci(float(r["frametime_mean_us"]) / 1000 for r in rs)
    frag = float(rs[0]["fragments_mean"]) / 1e6 if rs[0]["fragments_mean"] else float("nan")
    print(f"| {k[0]} | {k[1]} | {k[2] or '-'} | {m:.1f} ± {ci:.1f} | {float(rs[0]['draw_calls_mean']):.0f} | "
          f"{float(rs[0]['state_changes_mean']):.0f} | {frag:.2f} |")
PY
