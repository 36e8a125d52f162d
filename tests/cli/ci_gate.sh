#!/usr/bin/env bash
# scripts/ci-gate.sh, the CI recipe of issue 41: a gate on an empty history passes and
# leaves its folder, its check JSON and the database. Over a history of 12 sweeps at one
# speed and 3 with forward-plus slowed by debug.busy_us (synthetic copies of real 16x16
# smoke runs, 1% noise, deferred's rows A's throughout), a gate whose manifest keeps the
# slowdown fails with exit 1 and names the regression; the unchanged manifest on the 12
# unchanged sweeps passes (--min-change 100%: one smoke trial of a 16x16 frame on a loaded
# machine is noisy, the step is +600%). A manifest that cannot run fails the gate with
# exit 2 and adds nothing.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
export SHADESWEEP
G="$SOURCE_ROOT/scripts/ci-gate.sh"
cat > m.yaml <<'YAML'
shadesweep: 1
name: gate
scene: shapes
renderers: [deferred, forward-plus]
resolution: 16x16
duration: {frames: 3}
clock: fixed
lights: {count: 4, radius: 4}
outputs: {frames: false, seconds: false}
YAML
{ cat m.yaml; echo "debug: {busy_us: 20000, busy_renderer: forward-plus}"; } > slow.yaml

# 1. the first gate: nothing to compare with, so it passes
"$G" --db first.sqlite --out g1 m.yaml >g1.out 2>g1.err || fail "first gate: rc $? $(tail -3 g1.err)"
a=$(ls -d g1/*/ | head -1); a=${a%/}
[ -f "$a/summary.csv" ] && [ -f "$a.check.json" ] && [ -f first.sqlite ] ||
  fail "first gate left: $(ls -R g1 | head)"
"$PYTHON" - "$a.check.json" <<'PY' || fail "first check.json"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["sweeps"] == 1 and j["runs"] == 2 and j["change_points"] == [], j
PY

# 2. a history: A (the first gate's folder) 12 times, then the slowed sweep 3 times
"$SHADESWEEP" run --smoke -o b slow.yaml >b.out 2>b.err || fail "run b: $(cat b.err)"
"$PYTHON" - "$a" <<'PY'
import csv, glob, random, re, shutil, sys
random.seed(4242)
cols = ("frametime_mean_us", "cpu_mean_us", "gpu_mean_us", "metric_us")
def rows(d):
    with open(f"{d}/summary.csv", newline="") as f:
        return list(csv.DictReader(f))
a, b = rows(sys.argv[1]), rows("b")
assert [r["run_id"] for r in a] == [r["run_id"] for r in b], (a, b)
for s in range(15):
    dst = "h%02d" % s
    shutil.copytree(sys.argv[1], dst)
    out = []
    for r, rb in zip(a, b):
        r = dict(rb if s >= 12 and r["renderer"] == "forward-plus" else r)
        f = random.gauss(1, 0.01)
        for c in cols:
            if r[c]:
                r[c] = "%.3f" % (float(r[c]) * f)
        out.append(r)
    with open(f"{dst}/summary.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(a[0].keys()), lineterminator="\n")
        w.writeheader()
        w.writerows(out)
    for m in glob.glob(f"{dst}/runs/*/meta.yaml"):
        t = open(m).read()
        t = re.sub(r'(started: ")\d{4}-\d\d-\d\d', r"\g<1>2026-11-%02d" % (s + 1), t)
        open(m, "w").write(t)
PY
"$SHADESWEEP" history add --db h.sqlite h?? >add.out 2>add.err || fail "add: $(cat add.err)"
# the unchanged history: the 12 sweeps before the step
"$SHADESWEEP" history add --db clean.sqlite h0? h10 h11 >/dev/null 2>add2.err || fail "add clean: $(cat add2.err)"

# 3. the slowed manifest gated on the history with the step: exit 1, forward-plus named
rc=0
"$G" --db h.sqlite --out g2 slow.yaml --min-change 100% >g2.out 2>g2.err || rc=$?
[ $rc -eq 1 ] || fail "slowed gate: exit $rc, want 1: $(tail -5 g2.err)"
grep -q "^ci-gate: a regression in the history: g2/.*\.check\.json$" g2.err || fail "message: $(cat g2.err)"
"$PYTHON" - g2/*.check.json <<'PY' || fail "slowed check.json"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["sweeps"] == 16, j["sweeps"]
cps = j["change_points"]
assert [c["renderer"] for c in cps] == ["forward-plus"], cps
assert abs(cps[0]["index"] - 12) <= 2 and cps[0]["is_regression"], cps
PY

# 4. the unchanged manifest on the unchanged history: passes
"$G" --db clean.sqlite --out g3 m.yaml --min-change 100% >g3.out 2>g3.err || fail "clean gate: rc $? $(tail -5 g3.err)"

# 5. a manifest that cannot run: exit 2, nothing added
echo "shadesweep: 1" > bad.yaml
before=$("$PYTHON" -c "import sqlite3; print(sqlite3.connect('h.sqlite').execute('SELECT count(*) FROM trials').fetchone()[0])")
rc=0
"$G" --db h.sqlite --out g4 bad.yaml >g4.out 2>g4.err || rc=$?
[ $rc -eq 2 ] && grep -qx "ci-gate: run failed (exit 2)" g4.err || fail "bad manifest: rc $rc $(cat g4.err)"
after=$("$PYTHON" -c "import sqlite3; print(sqlite3.connect('h.sqlite').execute('SELECT count(*) FROM trials').fetchone()[0])")
[ "$before" = "$after" ] || fail "bad manifest added trials: $before -> $after"
echo "ci-gate: ok"
