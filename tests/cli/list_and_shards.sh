#!/usr/bin/env bash
# `list` and `--shard I/N`: shards partition the plan, and a sharded run writes only its runs.
. "$(dirname "$0")/lib.sh"
M="$SOURCE_ROOT/experiments/smoke.yaml"
cd "$T"
"$SHADESWEEP" list "$M" >all.txt
[ "$(wc -l <all.txt)" -eq 16 ] || fail "list: want 16 lines: $(cat all.txt)"
grep -q "renderer=null resolution=64x64 sync=fence" all.txt || fail "list line format: $(cat all.txt)"
for n in 1 2 3 5; do
  : >union.txt
  for i in $(seq 1 $n); do "$SHADESWEEP" list --shard "$i/$n" "$M" >>union.txt; done
  sort all.txt >a.sorted; sort union.txt >u.sorted
  cmp -s a.sorted u.sorted || fail "shards of $n: union != plan"
  [ "$(sort -u union.txt | wc -l)" -eq "$(wc -l <union.txt)" ] || fail "shards of $n overlap"
done
# --json: the same runs, each with every parameter typed (numbers as numbers), and a shard
# of them the same way
"$SHADESWEEP" list --json "$M" >all.json || fail "list --json"
"$SHADESWEEP" list --json --shard 2/3 "$M" >s2.json || fail "list --json --shard"
"$SHADESWEEP" list --shard 2/3 "$M" >s2.txt
"$PYTHON" - <<'PY' || fail "list --json: $(head -c 400 all.json)"
import json
d = json.load(open("all.json"))
ids = [l.split()[0] for l in open("all.txt")]
assert d["experiment"] == "smoke" and [r["run_id"] for r in d["runs"]] == ids, d["runs"][:2]
assert [r["index"] for r in d["runs"]] == list(range(16))
p = d["runs"][0]["parameters"]
assert p["resolution"] == "64x64" and p["trials"] == 2 and isinstance(p["lights.seed"], (int, float)), p
assert all(set(r["parameters"]) == set(p) for r in d["runs"])   # every key, every run
assert d["folded"] == []
s2 = json.load(open("s2.json"))
assert [r["run_id"] for r in s2["runs"]] == [l.split()[0] for l in open("s2.txt")]
assert all(r["shard"] == 2 for r in s2["runs"])
PY
# Same manifest, same ids: a second listing is identical.
"$SHADESWEEP" list "$M" | cmp -s - all.txt || fail "ids not stable"
# --scale and --smoke change the listed resolutions and the ids; a bad scale is refused
# with one line and exit 2.
"$SHADESWEEP" list --scale 0.5 "$M" >half.txt
[ "$(wc -l <half.txt)" -eq 16 ] && grep -q "resolution=32x32" half.txt && ! grep -q "resolution=64x64" half.txt \
  || fail "list --scale 0.5: $(cat half.txt)"
[ -z "$(comm -12 <(cut -d' ' -f1 all.txt | sort) <(cut -d' ' -f1 half.txt | sort))" ] \
  || fail "scaled runs keep the unscaled ids"
for bad in 0 -1 17 abc; do
  set +e
  "$SHADESWEEP" list --scale "$bad" "$M" >out.txt 2>err.txt; rc=$?
  set -e
  [ $rc -eq 2 ] && [ ! -s out.txt ] && grep -q "^shadesweep: --scale: expected a number > 0 and <= 16, found '$bad'$" err.txt \
    || fail "list --scale $bad: exit $rc: $(cat err.txt)"
done
"$SHADESWEEP" list --smoke "$SOURCE_ROOT/experiments/s000-resolution.yaml" >smoke.txt
# the resolution axis collapses (no longer a swept parameter): 2 scenes x 2 renderers
[ "$(wc -l <smoke.txt)" -eq 4 ] && ! grep -q 'resolution=' smoke.txt \
  || fail "list --smoke: $(cat smoke.txt)"

need_gl
"$SHADESWEEP" run --shard 2/2 -o shard2 "$M" 2>run.err || { cat run.err >&2; fail "sharded run"; }
"$PYTHON" - shard2 all.txt <<'PY'
import csv, os, sys
out, listing = sys.argv[1], sys.argv[2]
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
plan = list(csv.DictReader(open(os.path.join(out, "plan.csv"))))
if len(plan) != 16: fail("plan.csv lists every run of the manifest")
mine = [p["run_id"] for p in plan if p["shard"] == "2"]
# whole sweep points (4 renderers each, plan order) dealt round-robin: the runs ranked
# together are measured together
if [p["shard"] for p in plan] != [str(i // 4 % 2 + 1) for i in range(16)]: fail("shards by sweep point")
if sorted(os.listdir(os.path.join(out, "runs"))) != sorted(mine): fail("runs of other shards ran")
summ = list(csv.DictReader(open(os.path.join(out, "summary.csv"))))
if sorted({s["run_id"] for s in summ}) != sorted(mine) or len(summ) != 16: fail("summary rows")
ids = [l.split()[0] for l in open(listing)]
if ids != [p["run_id"] for p in plan]: fail("list and plan.csv disagree on ids")
PY
echo ok
