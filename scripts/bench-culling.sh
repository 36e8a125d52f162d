#!/usr/bin/env bash
# Benchmark (not a test): the culling engines since 2016 against forward-plus, clustered,
# tiled-deferred and deferred (experiments/modern-culling.yaml: zbin, 2.5D masks,
# two-level tiles, pruning by samples, stochastic ranges; 16 to 65,536 lights at
# lights.overlap 8 on curtis-scene3, canyon and a glTF file), on EGL + llvmpipe unless a
# device is given, and the markdown tables of docs/results/modern-culling.md:
#   1. per scene and lights, each renderer at its defaults: the ranking metric (mean ±
#      95% CI over trials, named), light evaluations a pixel, the light structures'
#      bytes, dispatches and the RMSE against forward-spml;
#   2. at 4,096 lights, each option against the same renderer at its defaults: the
#      metric's ratio, evaluations a pixel, bytes, RMSE (per scene);
#   3. stochastic ranges: error against time over lights.culling_error.
#   4. at 65,536 lights, each renderer at its defaults against mask + samples;
#   5. the crossovers: per scene, where one renderer at its defaults overtakes another
#      along the light count (the metric's log ratio interpolated in log lights).
#   scripts/bench-culling.sh [OUTDIR] [shadesweep run options, e.g. --smoke]
#   scripts/bench-culling.sh OUTDIR --tables      (the tables of a finished OUTDIR only)
# About 30 minutes on a 2-core machine; the crossovers are in OUTDIR/summary.md.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/out/bench-culling}
shift || true
. "$root/scripts/bench-common.sh"
if [ "${1:-}" != --tables ]; then
  # a failed run (a renderer refusing, a timeout) is a row of the table, not an abort
  "$root/build/runner/shadesweep" run --force "$@" -o "$out" \
    "$root/experiments/modern-culling.yaml" || true
fi
bench_table "$out" <<'PY'
import math, os, sys
from shadesweep_report.bench import grouped, load, mean_ci, print_header, print_machine
out = sys.argv[1]
rows, plans = load(out)
print_machine(out)
DEFAULTS = {"tiles.size": "16", "tiles.levels": "1", "tiles.coarse_size": "64",
            "zbin.bins": "1024", "tiles.depth_culling": "minmax", "tiles.prune": "bounds",
            "clustered.shading": "forward", "zbin.shading": "forward",
            "lights.culling": "exact"}
def options(p):
    """The run's culling options that differ from their defaults, as text."""
    o = []
    for k, d in DEFAULTS.items():
        if p[k] != d and not (k == "tiles.coarse_size" and p["tiles.levels"] == "1"):
            o.append(f"{k.split('.')[1]} {p[k]}")
    if p["lights.culling"] == "stochastic":
        o.append(f"error {p['lights.culling_error']}")
    return ", ".join(o)
def scene(p):
    return "2CylinderEngine.glb" if p["scene"].startswith("file:") else p["scene"]
def num(s, fmt):
    return format(float(s), fmt) if s not in ("", None) else "-"
def rmse(rs):
    v = max((float(r["image_rmse"]) for r in rs if r["image_rmse"]), default=float("nan"))
    return "-" if math.isnan(v) else format(v * 255, ".3f") + "/255"
metric = next((r["metric"] for r in rows if r.get("metric")), "?")
def key(r):
    p = plans[r["run_id"]]
    return (scene(p), int(p["lights.count"]), r["renderer"], options(p))
groups = list(grouped(rows, key))
def ms(rs):
    return mean_ci(float(r["metric_us"]) / 1000 for r in rs if r["metric_us"])

print(f"### 1. Each renderer at its defaults (ranked by {metric} time a frame, ms)")
print()
print_header("scene", "lights", "renderer", f"{metric} ms", "evals/pixel", "light bytes",
             "dispatches", "RMSE vs spml")
for k, rs, status in groups:
    if k[3]:
        continue
    if not rs:
        print(f"| {k[0]} | {k[1]} | {k[2]} | {status} | | | | |")
        continue
    m, ci = ms(rs)
    r0 = rs[0]
    print(f"| {k[0]} | {k[1]} | {k[2]} | {m:.1f} ± {ci:.1f} | "
          f"{num(r0['light_evals_per_pixel'], '.1f')} | "
          f"{num(r0['light_struct_bytes_mean'], '.0f')} | {num(r0['dispatches_mean'], '.0f')} | "
          f"{rmse(rs)} |")
print()
base = {(k[0], k[1], k[2]): rs for k, rs, _ in groups if not k[3] and rs}
print(f"### 2. One option at a time at 4,096 lights (ratio: its {metric} time over the same "
      "renderer's at its defaults)")
print()
print_header("scene", "renderer", "option", "ratio", "evals/pixel (defaults)",
             "light bytes (defaults)", "RMSE vs spml")
for k, rs, status in groups:
    if not k[3] or k[1] != 4096 or "stochastic" in k[3]:
        continue
    b = base.get((k[0], k[1], k[2]))
    if not rs or not b:
        print(f"| {k[0]} | {k[2]} | {k[3]} | {status} | | | |")
        continue
    ratio = ms(rs)[0] / ms(b)[0]
    print(f"| {k[0]} | {k[2]} | {k[3]} | {ratio:.2f} | "
          f"{num(rs[0]['light_evals_per_pixel'], '.1f')} ({num(b[0]['light_evals_per_pixel'], '.1f')}) | "
          f"{num(rs[0]['light_struct_bytes_mean'], '.0f')} ({num(b[0]['light_struct_bytes_mean'], '.0f')}) | "
          f"{rmse(rs)} |")
print()
print(f"### 3. Stochastic ranges: image error against {metric} time, 4,096 lights")
print()
print_header("scene", "renderer", "culling_error", f"{metric} ms", "ratio to exact",
             "evals/pixel", "RMSE vs spml")
for k, rs, status in groups:
    if "stochastic" not in k[3] or not rs:
        continue
    b = base.get((k[0], k[1], k[2]))
    m, ci = ms(rs)
    ratio = f"{m / ms(b)[0]:.2f}" if b else "-"
    err = plans[rs[0]["run_id"]]["lights.culling_error"]
    print(f"| {k[0]} | {k[2]} | {err} | {m:.1f} ± {ci:.1f} | {ratio} | "
          f"{num(rs[0]['light_evals_per_pixel'], '.1f')} | {rmse(rs)} |")
print()
print(f"### 4. 65,536 lights: defaults against mask + samples ({metric} ms, 2 trials)")
print()
print_header("scene", "renderer", f"defaults {metric} ms", "evals/pixel",
             f"mask + samples {metric} ms", "evals/pixel", "ratio")
for k, rs, status in groups:
    if k[1] != 65536 or k[3] != "depth_culling mask, prune samples" or not rs:
        continue
    b = base.get((k[0], k[1], k[2]))
    if not b:
        continue
    m, ci = ms(rs)
    mb, cib = ms(b)
    print(f"| {k[0]} | {k[2]} | {mb:.0f} ± {cib:.0f} | {num(b[0]['light_evals_per_pixel'], '.1f')} | "
          f"{m:.0f} ± {ci:.0f} | {num(rs[0]['light_evals_per_pixel'], '.1f')} | {m / mb:.2f} |")
print()
print(f"### 5. Crossovers of the renderers at their defaults ({metric} time)")
print()
print_header("scene", "order at 16 / 256 / 4,096 / 65,536 lights (fastest first)",
             "crossovers (lights, interpolated)")
for sc in sorted({k[0] for k in base}):
    counts = sorted({k[1] for k in base if k[0] == sc})
    rens = sorted({k[2] for k in base if k[0] == sc})
    t = {(n, r): ms(base[(sc, n, r)])[0] for n in counts for r in rens if (sc, n, r) in base}
    orders = " / ".join(", ".join(r for r in sorted(rens, key=lambda r: t.get((n, r), 1e30)))
                        for n in counts)
    cross = []
    for i, a in enumerate(rens):
        for b in rens[i + 1:]:
            for n0, n1 in zip(counts, counts[1:]):
                if not all(k in t for k in ((n0, a), (n0, b), (n1, a), (n1, b))):
                    continue
                l0 = math.log(t[(n0, a)] / t[(n0, b)])
                l1 = math.log(t[(n1, a)] / t[(n1, b)])
                if l0 * l1 < 0:
                    x = math.log(n0) + (math.log(n1) - math.log(n0)) * l0 / (l0 - l1)
                    after = a if l1 < 0 else b
                    before = b if after == a else a
                    cross.append(f"{after} passes {before} at ~{math.exp(x):,.0f}")
    print(f"| {sc} | {orders} | {'; '.join(cross) or 'none'} |")
PY
