#!/usr/bin/env bash
# Benchmark (not a test): the renderers on the shapes scene at 640x360 with 1, 16 and
# 256 point lights (experiments/renderers-*.yaml), on EGL + llvmpipe, and a markdown
# table for the README: frame time (mean ± 95% CI over trials), draw calls, state
# changes and fragment-shader invocations per frame, per renderer and light-volume mode.
#   scripts/bench-renderers.sh [OUTDIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/out/bench-renderers}
"$root/scripts/setup.sh"
"$root/scripts/build.sh" "$root/build"
export LIBGL_ALWAYS_SOFTWARE=1
for m in deferred forward; do
  "$root/build/runner/shadesweep" run --force -o "$out/$m" "$root/experiments/renderers-$m.yaml"
done
/usr/bin/python3 - "$out" <<'PY'
import csv, glob, math, os, statistics, sys
import yaml
out = sys.argv[1]
T975 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776}
rows, plans = [], {}
for m in ("deferred", "forward"):
    rows += list(csv.DictReader(open(os.path.join(out, m, "summary.csv"))))
    plans.update({p["run_id"]: p for p in csv.DictReader(open(os.path.join(out, m, "plan.csv")))})
meta = yaml.safe_load(open(glob.glob(os.path.join(out, "*", "runs", "*", "meta.yaml"))[0]))
print(f"GL renderer: {meta['gl']['renderer']}; CPU: {meta['host']['cpu']}, "
      f"{meta['host']['threads']} threads; shadesweep {meta['shadesweep']['commit']}")
print()
print("| lights | renderer | light volumes | frame time ms | draw calls | state changes | fragments (M) |")
print("|---|---|---|---|---|---|---|")
def key(r):
    p = plans[r["run_id"]]
    mode = p["deferred.light_volumes"] if r["renderer"] == "deferred" else ""
    return (int(p["lights.count"]), r["renderer"], mode)
groups = {}
for r in rows:
    groups.setdefault(key(r), []).append(r)
for k in sorted(groups):
    rs = [r for r in groups[k] if r["status"] == "ok"]
    if not rs:
        print(f"| {k[0]} | {k[1]} | {k[2]} | failed: {groups[k][0]['status']} | | | |")
        continue
    ft = [float(r["frametime_mean_us"]) / 1000 for r in rs]
    m = statistics.mean(ft)
    ci = T975.get(len(ft) - 1, 2.0) * statistics.stdev(ft) / math.sqrt(len(ft)) if len(ft) > 1 else float("nan")
    frag = float(rs[0]["fragments_mean"]) / 1e6 if rs[0]["fragments_mean"] else float("nan")
    print(f"| {k[0]} | {k[1]} | {k[2] or '-'} | {m:.1f} ± {ci:.1f} | {float(rs[0]['draw_calls_mean']):.0f} | "
          f"{float(rs[0]['state_changes_mean']):.0f} | {frag:.2f} |")
PY
