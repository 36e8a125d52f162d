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
"$root/scripts/setup.sh"
"$root/scripts/build.sh" "$root/build"
export LIBGL_ALWAYS_SOFTWARE=${LIBGL_ALWAYS_SOFTWARE-1}
for m in tiled tiled-volumes; do
  # a failed run (a renderer refusing, a timeout) is a row of the table, not an abort
  "$root/build/runner/shadesweep" run --force "$@" -o "$out/$m" \
    "$root/experiments/renderers-$m.yaml" || true
done
/usr/bin/python3 - "$out" <<'PY'
import csv, glob, math, os, statistics, sys
import yaml
out = sys.argv[1]
T975 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776}
rows, plans = [], {}
for m in ("tiled", "tiled-volumes"):
    p = os.path.join(out, m, "summary.csv")
    if not os.path.exists(p):
        continue
    rows += list(csv.DictReader(open(p)))
    plans.update({r["run_id"]: r for r in csv.DictReader(open(os.path.join(out, m, "plan.csv")))})
metas = glob.glob(os.path.join(out, "*", "runs", "*", "meta.yaml"))
if metas:
    meta = yaml.safe_load(open(metas[0]))
    print(f"GL renderer: {meta['gl']['renderer']}; CPU: {meta['host']['cpu']}, "
          f"{meta['host']['threads']} threads; shadesweep {meta['shadesweep']['commit']}")
    print()
print("| scene | lights | renderer | frame time ms | draws | dispatches | lights/cell | evals/pixel | RMSE vs spml |")
print("|---|---|---|---|---|---|---|---|---|")
def key(r):
    p = plans[r["run_id"]]
    name = r["renderer"]
    if name == "deferred":
        name += " " + p["deferred.light_volumes"]
    return (p["scene"], int(p["lights.count"]), name)
groups = {}
for r in rows:
    groups.setdefault(key(r), []).append(r)
def num(s, fmt):
    return format(float(s), fmt) if s not in ("", None) else "-"
for k in sorted(groups):
    rs = [r for r in groups[k] if r["status"] == "ok"]
    if not rs:
        print(f"| {k[0]} | {k[1]} | {k[2]} | {groups[k][0]['status']} | | | | | |")
        continue
    ft = [float(r["frametime_mean_us"]) / 1000 for r in rs]
    m = statistics.mean(ft)
    ci = T975.get(len(ft) - 1, 2.0) * statistics.stdev(ft) / math.sqrt(len(ft)) if len(ft) > 1 else float("nan")
    r0 = rs[0]
    rmse = max((float(r["image_rmse"]) for r in rs if r["image_rmse"]), default=float("nan"))
    print(f"| {k[0]} | {k[1]} | {k[2]} | {m:.1f} ± {ci:.1f} | {num(r0['draw_calls_mean'], '.0f')} | "
          f"{num(r0['dispatches_mean'], '.0f')} | {num(r0['cell_lights_mean'], '.2f')} | "
          f"{num(r0['light_evals_per_pixel'], '.2f')} | "
          f"{'-' if math.isnan(rmse) else format(rmse * 255, '.3f') + '/255'} |")
PY
