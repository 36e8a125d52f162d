#!/usr/bin/env bash
# `shadesweep ratios`: the trial-level statistics (results/verdict.c) that the Python
# report asks for, on hand-made folders with known numbers: a run's mean and interval,
# A / B paired within a sweep point (checked against the formula computed here), Welch on
# logs across points and folders, a crossover along the light count, an error answer for
# a missing run that does not stop the others, and malformed requests refused (exit 2).
# No GL.
. "$(dirname "$0")/lib.sh"
cd "$T"
"$PYTHON" - <<'PY'
import csv, os
def write(path, cols, rows):
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(cols)
        w.writerows(rows)
# per-trial cpu times (us) of forward-plus (fp) and clustered (cl) at 1, 16, 256 lights:
# fp is faster at 1 and 16, slower at 256
vals = {("fp", 1): (1000, 1100, 1200), ("cl", 1): (2000, 2300, 2300),
        ("fp", 16): (3000, 3100, 3300), ("cl", 16): (4000, 4200, 4100),
        ("fp", 256): (9000, 9500, 9300), ("cl", 256): (6000, 6100, 6300)}
plan, summary = [], []
for i, ((ren, c), v) in enumerate(vals.items()):
    rid = f"{ren}{c:010d}"
    plan.append([i, rid, ren, c])
    for k, x in enumerate(v, 1):
        summary.append(["x", rid, ren, k, x * 3, "ok", "cpu", x])
write("a/plan.csv", ["index", "run_id", "renderer", "lights.count"], plan)
write("a/summary.csv", ["experiment", "run_id", "renderer", "trial", "frametime_mean_us",
                        "status", "metric", "metric_us"], summary)
# b: the same 1-light fp run measured again apart, and a wall-time folder (no metric column)
write("b/plan.csv", ["index", "run_id", "renderer", "lights.count"], [[0, "fp0000000001", "fp", 1]])
write("b/summary.csv", ["experiment", "run_id", "renderer", "trial", "frametime_mean_us",
                        "status", "metric", "metric_us"],
      [["x", "fp0000000001", "fp", k, 0, "ok", "cpu", x] for k, x in enumerate((1500, 1600, 1700), 1)])
write("w/summary.csv", ["experiment", "run_id", "renderer", "trial", "frametime_mean_us", "status"],
      [["x", "fp0000000001", "fp", k, x, "ok"] for k, x in enumerate((1000, 1100, 1200), 1)])
PY
t=$(printf '\t')
{
  echo "run${t}a${t}fp0000000001"
  echo "ratio${t}a${t}cl0000000001${t}a${t}fp0000000001"
  echo "ratio${t}a${t}fp0000000001${t}a${t}fp0000000016"
  echo "ratio${t}b${t}fp0000000001${t}a${t}fp0000000001"
  echo "ratio${t}a${t}nope${t}a${t}fp0000000001"
  echo "ratio${t}w${t}fp0000000001${t}a${t}fp0000000001"
  echo "crossover${t}1${t}a${t}fp0000000001${t}a${t}cl0000000001${t}16${t}a${t}fp0000000016${t}a${t}cl0000000016${t}256${t}a${t}fp0000000256${t}a${t}cl0000000256"
  echo "ratio${t}missing-folder${t}x${t}a${t}fp0000000001"
} >req.txt
"$SHADESWEEP" ratios <req.txt >ans.txt 2>ans.err || fail "ratios: $(cat ans.err)"
"$PYTHON" - <<'PY' || fail "ratios answers: $(cat ans.txt)"
import json, math, statistics as st, sys
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
a = [json.loads(l) for l in open("ans.txt")]
if len(a) != 8: fail(f"{len(a)} answers for 8 requests")
T975_2 = 4.302652729911275          # Student t, 97.5%, 2 degrees of freedom
def paired(x, y):
    d = [math.log(p / q) for p, q in zip(x, y)]
    m, h = st.mean(d), T975_2 * st.stdev(d) / math.sqrt(len(d))
    return math.exp(m), math.exp(m - h), math.exp(m + h)
def close(u, v): return u is not None and abs(u - v) <= 1e-6 * abs(v)
run, r1, r2, r3, err, wall, cross, gone = a
fp1, cl1 = (1000, 1100, 1200), (2000, 2300, 2300)
if run["metric"] != "cpu" or not close(run["mean_us"], 1100) or run["trials"] != 3 \
        or not close(run["ci95_us"], T975_2 * 100 / math.sqrt(3)):
    fail(f"run: {run}")
# one point: paired, the geometric mean of the per-round ratios and its t interval
want = paired(cl1, fp1)
if not r1["paired"] or r1["n"] != 3 or r1["differs"] != "yes" or \
        not all(close(r1[k], w) for k, w in zip(("ratio", "lo", "hi"), want)):
    fail(f"paired ratio {r1}, want {want}")
if not close(r1["a_mean_us"], st.mean(cl1)) or r1["b_trials"] != 3: fail(f"sides {r1}")
# two points of one folder, one run in two folders: unpaired (Welch on logs), the ratio
# of geometric means
for r, x, y in ((r2, fp1, (3000, 3100, 3300)), (r3, (1500, 1600, 1700), fp1)):
    g = math.exp(st.mean(map(math.log, x)) - st.mean(map(math.log, y)))
    if r["paired"] or not close(r["ratio"], g) or not r["lo"] < g < r["hi"]:
        fail(f"unpaired {r}, want ratio {g}")
if r2["differs"] != "yes": fail(f"fp at 1 vs 16 lights: {r2}")
if "no run nope" not in err.get("error", ""): fail(f"missing run: {err}")
if "different metrics (wall, cpu)" not in wall.get("error", ""): fail(f"metrics: {wall}")
if "missing-folder/summary.csv" not in gone.get("error", ""): fail(f"missing folder: {gone}")
# fp / cl: below 1 at 1 and 16 lights, above at 256: one crossing between 16 and 256,
# rising, where the log ratio interpolated linearly in log lights reaches 0
c = cross["crossings"]
if len(c) != 1 or (c[0]["i"], c[0]["j"], c[0]["dir"]) != (1, 2, 1): fail(f"crossings {c}")
l16 = math.log(paired((3000, 3100, 3300), (4000, 4200, 4100))[0])
l256 = math.log(paired((9000, 9500, 9300), (6000, 6100, 6300))[0])
x = math.exp(math.log(16) + l16 / (l16 - l256) * (math.log(256) - math.log(16)))
if not close(c[0]["x"], x) or not 16 < c[0]["lo"] < c[0]["x"] < c[0]["hi"] < 256:
    fail(f"crossing {c[0]}, want x {x}")
if [r["differs"] for r in cross["ratios"]] != ["yes", "yes", "yes"]: fail(f"ratios {cross}")
PY
# malformed requests and arguments: one line, exit 2
bad() {   # stdin-text expected-message [args]
  set +e
  printf '%b' "$1" | "$SHADESWEEP" ratios ${3:-} >bad.out 2>bad.err; rc=$?
  set -e
  [ $rc -eq 2 ] && grep -q -- "$2" bad.err || fail "ratios '$1' ${3:-}: rc $rc $(cat bad.err)"
}
bad 'ratio a b\n' "line 1: want 'run' and 2 fields"
bad 'run\ta\tfp0000000001\ncrossover\t1\ta\tx\ta\ty\n' "line 2: want"
# an axis that does not ascend: an error answer, exit 0
printf 'crossover\t16\ta\tfp0000000001\ta\tcl0000000001\t1\ta\tfp0000000016\ta\tcl0000000016\n' |
  "$SHADESWEEP" ratios >desc.out || fail "descending axis: rc $?"
grep -q '^{"error": "crossover: point 2: .1. is not a number above the point before"}$' desc.out ||
  fail "descending axis: $(cat desc.out)"
bad '' "unexpected argument 'x'" x
echo "ratios: ok"
