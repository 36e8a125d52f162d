#!/usr/bin/env bash
# Why does CPU time a frame move with load on a 2-core machine, and which measure holds?
# (issue 41, item 3). experiments/noise-aa.yaml (six renderers, curtis-scene3 at 160x120,
# 128 lights, 5 interleaved trials of 120 fixed-step frames) run under each way of
# running llvmpipe, each on a quiet machine and under two busy loops (one per core, for
# the whole run), REPEAT times:
#   threads   llvmpipe's default: as many rasterizer threads as CPUs, beside the main one
#   lp0       LP_NUM_THREADS=0: the main thread rasterizes, no worker threads
#   pinned    the default threads, the process pinned to one CPU (taskset -c 1)
# Per renderer and way: the trials' CPU time a frame (mean and coefficient of variation),
# the loaded mean over the quiet one, and the user/system split of each whole sweep
# (/usr/bin/time over its trial processes). Not part of CI (about 25 minutes).
#   scripts/bench-measure.sh [OUT] [REPEAT]      (default out/bench-measure, 2)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/out/bench-measure}
repeat=${2:-2}
. "$root/scripts/bench-common.sh"
export MESA_DEBUG=silent
exe=$root/build/runner/shadesweep
manifest=$root/experiments/noise-aa.yaml
mkdir -p "$out"
busy=()
load_on() { for _ in 1 2; do (while :; do :; done) & busy+=($!); done; }
load_off() { [ ${#busy[@]} -eq 0 ] || { kill "${busy[@]}" 2>/dev/null; wait "${busy[@]}" 2>/dev/null || true; }; busy=(); }
trap load_off EXIT
for r in $(seq "$repeat"); do
  for way in threads lp0 pinned; do
    for load in quiet loaded; do
      d=$out/$way-$load-$r
      rm -rf "$d"
      pre=(env)
      case $way in
        lp0) pre=(env LP_NUM_THREADS=0) ;;
        pinned) pre=(taskset -c 1 env) ;;
      esac
      [ $load = loaded ] && load_on
      /usr/bin/time -f "%U %S %e" -o "$d.time" "${pre[@]}" "$exe" run -o "$d" "$manifest" \
        >"$d.out" 2>"$d.err" || true
      load_off
      echo "$way $load $r: $(cat "$d.time")"
    done
  done
done
bench_table "$out" <<'PY'
import csv, glob, os, statistics, sys
out = sys.argv[1]
ways, rows = ("threads", "lp0", "pinned"), {}
for path in glob.glob(os.path.join(out, "*-*-*", "summary.csv")):
    way, load, rep = os.path.basename(os.path.dirname(path)).split("-")
    for r in csv.DictReader(open(path)):
        if r["status"] == "ok" and r["cpu_mean_us"]:
            rows.setdefault((way, r["renderer"], load), []).append(float(r["cpu_mean_us"]))
def cv(xs):
    return statistics.stdev(xs) / statistics.mean(xs) * 100 if len(xs) > 1 else float("nan")
print("| way | renderer | quiet ms (CV %) | loaded ms (CV %) | loaded / quiet |")
print("|---|---|---|---|---|")
for way in ways:
    for ren in sorted({k[1] for k in rows if k[0] == way}):
        q, l = rows.get((way, ren, "quiet"), []), rows.get((way, ren, "loaded"), [])
        if not q or not l:
            continue
        print(f"| {way} | {ren} | {statistics.mean(q) / 1000:.2f} ({cv(q):.1f}) | "
              f"{statistics.mean(l) / 1000:.2f} ({cv(l):.1f}) | "
              f"{statistics.mean(l) / statistics.mean(q):.3f} |")
print()
print("| sweep | user s | sys s | wall s |")
print("|---|---|---|---|")
for t in sorted(glob.glob(os.path.join(out, "*.time"))):
    u, s, e = open(t).read().split()[-3:]
    print(f"| {os.path.basename(t)[:-5]} | {u} | {s} | {e} |")
PY
