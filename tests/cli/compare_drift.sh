#!/usr/bin/env bash
# compare's common change (results/drift.c) on hand-made folders with known numbers, no
# GL: six runs, NEW = BASE x 0.88 (a 12% faster machine) except one run x 0.88 x 1.10.
# compare flags exactly that run slower, prints the common change (0.88), the warning and
# the raw ratios (which alone would flag the five others faster); with no drift every
# run is `same`, no correction, no warning; with 4 runs no estimate, one line says why.
. "$(dirname "$0")/lib.sh"
cd "$T"
"$PYTHON" - <<'PY'
import csv, os
def write(d, runs):
    os.makedirs(d, exist_ok=True)
    with open(f"{d}/plan.csv", "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["index", "run_id", "renderer", "lights.seed"])
        w.writerows([i, rid, "r%d" % i, i] for i, rid in enumerate(runs))
    with open(f"{d}/summary.csv", "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["experiment", "run_id", "renderer", "trial", "frametime_mean_us",
                    "status", "metric", "metric_us"])
        for i, (rid, vals) in enumerate(runs.items()):
            for k, x in enumerate(vals, 1):
                w.writerow(["x", rid, "r%d" % i, k, x, "ok", "cpu", x])
trial = (1000, 1010, 990, 1005, 995)
base = {"run%08d" % i: [x * (i + 1) for x in trial] for i in range(6)}
write("base", base)
write("drift", {rid: [x * 0.88 * (1.10 if rid == "run00000003" else 1) for x in v]
                for rid, v in base.items()})
# no drift, no change: the same values, trials in another order
write("still", {rid: v[::-1] for rid, v in base.items()})
write("few", {rid: [x * 0.88 for x in v] for rid, v in list(base.items())[:4]})
PY
rc=0
"$SHADESWEEP" compare base drift >drift.md 2>drift.err || rc=$?
[ "$rc" -eq 1 ] || fail "drift: exit $rc, want 1 (one run slower): $(cat drift.err)"
grep -q "^6 runs in common: 1 slower, 0 faster, 5 same, 0 undecided, " drift.md ||
  fail "drift counts: $(cat drift.md)"
grep -q "^| run00000003 | r3 | .* | 1\.1000 | .* | 0\.9680 | .* | \*\*slower\*\* |$" drift.md ||
  fail "drift: run 3 not slower with raw 0.9680: $(cat drift.md)"
[ "$(grep -c '| 0\.8800 | 0\.8[0-9]* \.\. 0\.8[0-9]* | 5 | same |$' drift.md)" -eq 5 ] ||
  fail "drift: want five runs same with raw ratio 0.8800: $(cat drift.md)"
grep -q "^Common change between the folders (median of the 6 runs' NEW / BASE, robust to a few changed runs): 0\.8800 (0\.8[0-9]* \.\. 0\.8[0-9]*): verdicts on the ratios divided by it" drift.md ||
  fail "drift: no common change line: $(cat drift.md)"
grep -qF "**Warning:** the machine moved by -12% between the folders: verdicts are on ratios corrected for it." drift.md ||
  fail "drift: no warning: $(cat drift.md)"
"$SHADESWEEP" compare --json --csv drift.csv base drift >drift.json 2>/dev/null || true
"$PYTHON" - drift.json drift.csv <<'PY'
import csv, json, sys
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
j = json.load(open(sys.argv[1]))
c = j["common_change"]
if not (abs(c["ratio"] - 0.88) < 1e-9 and c["ratio_lo"] < 0.88 < c["ratio_hi"] < 0.89
        and c["runs"] == 6 and c["applied"] and c["beyond_threshold"]):
    fail(f"common_change {c}")
for r in j["runs"]:
    changed = r["run_id"] == "run00000003"
    raw = 0.968 if changed else 0.88
    if abs(r["raw_ratio"] - raw) > 1e-9 or abs(r["ratio"] - raw / 0.88) > 1e-9:
        fail(f"ratios {r}")
    # on the raw ratios the five unchanged runs would be `faster`
    if not changed and not r["raw_ratio_hi"] < 1 / 1.05:
        fail(f"raw interval not below 1/1.05: {r}")
    if r["verdict"] != ("slower" if changed else "same"):
        fail(f"verdict {r}")
    # the corrected interval is wider than the raw one (the common change's own)
    if not (r["ratio_hi"] / r["ratio_lo"] > r["raw_ratio_hi"] / r["raw_ratio_lo"]):
        fail(f"interval not widened {r}")
rows = list(csv.DictReader(open(sys.argv[2])))
if [r["verdict"] for r in rows] != ["same"] * 3 + ["slower"] + ["same"] * 2:
    fail(f"csv verdicts {rows}")
PY

# no drift, no change: the interval of the common change holds 1, nothing corrected
"$SHADESWEEP" compare base still >still.md 2>still.err || fail "still: $(cat still.err)"
grep -q "^6 runs in common: 0 slower, 0 faster, 6 same, 0 undecided, " still.md ||
  fail "still counts: $(cat still.md)"
grep -q "): its interval holds 1, no correction\.$" still.md || fail "still: $(cat still.md)"
! grep -q "Warning\|raw NEW / BASE" still.md || fail "still: warning or raw column: $(cat still.md)"
"$SHADESWEEP" compare --json base still >still.json 2>/dev/null || fail "still --json"
"$PYTHON" - still.json <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
assert not j["common_change"]["applied"], j["common_change"]
for r in j["runs"]:
    assert (r["ratio"], r["ratio_lo"], r["ratio_hi"]) == (
        r["raw_ratio"], r["raw_ratio_lo"], r["raw_ratio_hi"]), r
    assert r["verdict"] == "same", r
PY

# four runs: no estimate, one line why, the raw verdicts (all four faster)
"$SHADESWEEP" compare --allow-missing base few >few.md 2>few.err || fail "few: $(cat few.err)"
[ "$(grep -c '^Common change' few.md)" -eq 1 ] || fail "few: $(cat few.md)"
grep -q "^Common change: not estimated: 4 runs with an interval, the median needs 5 (with fewer, one changed run would move it); verdicts on the raw ratios\.$" few.md ||
  fail "few: no line why: $(cat few.md)"
grep -q "^4 runs in common: 0 slower, 4 faster, " few.md || fail "few counts: $(cat few.md)"
! grep -q "Warning" few.md || fail "few: warning: $(cat few.md)"
echo ok
