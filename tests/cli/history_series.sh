#!/usr/bin/env bash
# The issue's check of `history check` over a synthetic series of 30 sweeps built from
# real runs (16x16, 3 frames, 2 trials): sweep A of six renderers, and sweep B of
# forward-plus alone slowed by debug.busy_us (20 ms of CPU a frame: several times its
# frame). Sweep s of the 30 is A's values, forward-plus's B's from sweep 10 on and
# deferred's x 1.10 from sweep 20 on, every run times a common drift of the whole sweep
# (the machine 12% faster from sweep 12, 5% slower from 24, +-2% jitter) and its own
# noise (1%). check finds both steps, each within two sweeps of where it was put, and
# no change point on the four unchanged runs; without the drift removed (--no-drift)
# the machine's steps show on unchanged runs.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat > m.yaml <<'YAML'
shadesweep: 1
name: hseries
scene: shapes
renderers: [null, deferred, forward-spml, forward-mpml, forward-plus, clustered]
resolution: 16x16
trials: 2
warmup: {frames: 1}
duration: {frames: 3}
clock: fixed
lights: {count: 4, radius: 4}
outputs: {frames: false, seconds: false}
YAML
"$SHADESWEEP" run -o a m.yaml >a.out 2>a.err || fail "run a: $(cat a.err)"
"$SHADESWEEP" run -o b --renderer forward-plus --set debug.busy_us=20000 \
  --set debug.busy_renderer=forward-plus m.yaml >b.out 2>b.err || fail "run b: $(cat b.err)"

"$PYTHON" - <<'PY'
import csv, glob, random, re, shutil
random.seed(4141)
cols = ("frametime_mean_us", "cpu_mean_us", "gpu_mean_us", "metric_us")
def rows(d):
    with open(f"{d}/summary.csv", newline="") as f:
        return list(csv.DictReader(f))
a, b = rows("a"), rows("b")
slow = {(r["run_id"], r["trial"]): r for r in b}
assert len(a) == 12 and len(b) == 2 and all(r["status"] == "ok" for r in a + b), (a, b)
for s in range(30):
    d = "s%02d" % s
    shutil.copytree("a", d)
    drift = (1 if s < 12 else 0.88 if s < 24 else 1.05) * random.gauss(1, 0.02)
    out = []
    for r in a:
        r = dict(r)
        if r["renderer"] == "forward-plus" and s >= 10:
            r.update({c: slow[(r["run_id"], r["trial"])][c] for c in cols})
        f = drift * random.gauss(1, 0.01) * (1.10 if r["renderer"] == "deferred" and s >= 20 else 1)
        for c in cols:
            if r[c]:
                r[c] = "%.3f" % (float(r[c]) * f)
        out.append(r)
    with open(f"{d}/summary.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(a[0].keys()), lineterminator="\n")
        w.writeheader()
        w.writerows(out)
    for m in glob.glob(f"{d}/runs/*/meta.yaml"):
        t = open(m).read()
        t = re.sub(r'(started: ")\d{4}-\d\d-\d\d', r"\g<1>2027-01-%02d" % (s + 1), t)
        open(m, "w").write(t)
PY
"$SHADESWEEP" history add --db h.sqlite s?? >add.out 2>add.err || fail "add: $(cat add.err)"
[ "$(grep -c ': 6 runs and 12 trials added to h.sqlite$' add.out)" -eq 30 ] || fail "add: $(cat add.out)"
rc=0
"$SHADESWEEP" history check --db h.sqlite --json cp.json >check.out 2>check.err || rc=$?
[ $rc -eq 1 ] || fail "check: exit $rc, want 1: $(cat check.out check.err)"
"$PYTHON" - cp.json <<'PY'
import json, sys
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
j = json.load(open(sys.argv[1]))
cps = j["change_points"]
if j["sweeps"] != 30 or j["runs"] != 6: fail(f"sweeps/runs {j}")
got = sorted((c["renderer"], c["index"]) for c in cps)
if [g[0] for g in got] != ["deferred", "forward-plus"]: fail(f"change points {cps}")
for c in cps:
    at = 20 if c["renderer"] == "deferred" else 10
    if abs(c["index"] - at) > 2 or not c["is_regression"]:
        fail(f"{c['renderer']}: at {c['index']}, put at {at}: {c}")
    if c["time"] != "2027-01-%02dT" % (c["index"] + 1) + c["time"][11:]:
        fail(f"time {c}")
d = [c for c in cps if c["renderer"] == "deferred"][0]
if not 7 < d["forward_change_percent"] < 13: fail(f"deferred's step {d}")
PY
# without the drift removed, the machine's 12% moves the unchanged runs too
"$SHADESWEEP" history show --db h.sqlite --no-drift --json raw.json >/dev/null 2>&1 ||
  fail "show --no-drift"
"$PYTHON" - raw.json <<'PY'
import json, sys
cps = json.load(open(sys.argv[1]))["change_points"]
moved = {c["renderer"] for c in cps} - {"deferred", "forward-plus"}
assert moved, cps
PY
echo ok
