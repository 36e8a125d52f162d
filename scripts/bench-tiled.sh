#!/usr/bin/env bash
# Benchmark (not a test): every renderer and light-volume mode as lights grow, on
# curtis-scene3 and shapes at 640x360 with 1 to 16,384 radius-3 point lights
# (experiments/renderers-tiled*.yaml), on EGL + llvmpipe unless a device is given, and
# a markdown table for the README: frame time (mean ± 95% CI over trials), draw calls,
# compute dispatches, mean lights per tile/cluster, light evaluations per shaded pixel
# and the image RMSE against forward-spml, per scene, lights and renderer.
#   scripts/bench-tiled.sh [OUTDIR] [shadesweep run options, e.g. --smoke]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/out/bench-tiled}
shift || true
. "$root/scripts/bench-common.sh"
for m in tiled tiled-volumes; do
  # a failed run (a renderer refusing, a timeout) is a row of the table, not an abort
  "$root/build/runner/shadesweep" run --force "$@" -o "$out/$m" \
    "$root/experiments/renderers-$m.yaml" || true
done
bench_table "$out" <<'PY'
import math, sys
from shadesweep_report.bench import grouped, load, mean_ci, print_header, print_machine
out = sys.argv[1]
rows, plans = load(out, ("tiled", "tiled-volumes"))
print_machine(out)
print_header("scene", "lights", "renderer", "frame time ms", "draws", "dispatches",
             "lights/cell", "evals/pixel", "RMSE vs spml")
def key(r):
    p = plans[r["run_id"]]
    name = r["renderer"]
    if name == "deferred":
        name += " " + p["deferred.light_volumes"]
    return (p["scene"], int(p["lights.count"]), name)
def num(s, fmt):
    return format(float(s), fmt) if s not in ("", None) else "-"
for k, rs, status in grouped(rows, key):
    if not rs:
        print(f"| {k[0]} | {k[1]} | {k[2]} | {status} | | | | | |")
        continue
    m, ci = mean_ci(float(r["frametime_mean_us"]) / 1000 for r in rs)
    r0 = rs[0]
    rmse = max((float(r["image_rmse"]) for r in rs if r["image_rmse"]), default=float("nan"))
    print(f"| {k[0]} | {k[1]} | {k[2]} | {m:.1f} ± {ci:.1f} | {num(r0['draw_calls_mean'], '.0f')} | "
          f"{num(r0['dispatches_mean'], '.0f')} | {num(r0['cell_lights_mean'], '.2f')} | "
          f"{num(r0['light_evals_per_pixel'], '.2f')} | "
          f"{'-' if math.isnan(rmse) else format(rmse * 255, '.3f') + '/255'} |")
PY
