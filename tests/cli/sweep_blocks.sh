#!/usr/bin/env bash
# `sweep:` as a list of blocks (runner/manifest/manifest_sweep.c, runner/plan/sweep.c): the
# exact run list of `list` (a run an earlier block made folded into it), validate, --json,
# the --set refusal of sweep.KEY and the whole-sweep replacement, --set of a swept key,
# --smoke; then a run, its resume, shards and their merge.
. "$(dirname "$0")/lib.sh"
cd "$T"
cat >m.yaml <<'YAML'
shadesweep: 1
name: blocks
scene: empty
renderers: [null]
duration: {frames: 2}
clock: fixed
resolution: 8x8
lights: {count: 4, seed: 1}
sweep:
  - {resolution: [8x8, 16x16], lights.seed: [1, 2]}
  - {lights.count: [4, 8]}
YAML
"$SHADESWEEP" list m.yaml >list.txt 2>list.err || fail "list: $(cat list.err)"
cat >want.txt <<'TXT'
2f12d1c3ca99  renderer=null resolution=8x8 lights.seed=1 lights.count=4
ea0ce85a0844  renderer=null resolution=8x8 lights.seed=2 lights.count=4
68e0e46d4db1  renderer=null resolution=16x16 lights.seed=1 lights.count=4
0c32f114efae  renderer=null resolution=16x16 lights.seed=2 lights.count=4
2eea19c3ca76  renderer=null resolution=8x8 lights.seed=1 lights.count=8
# 1 of 6 grid points folded into a run that measures the same (they differ only in keys their renderer does not read):
#   renderer=null resolution=8x8 lights.seed=1 lights.count=4 -> 2f12d1c3ca99
TXT
cmp -s list.txt want.txt || fail "list: $(diff want.txt list.txt)"
"$SHADESWEEP" validate m.yaml >val.txt || fail "validate"
grep -qF "m.yaml: ok, 5 runs (1 of 6 grid points folded" val.txt || fail "validate: $(cat val.txt)"
"$SHADESWEEP" list --json m.yaml >list.json || fail "list --json"
"$PYTHON" - <<'PY' || fail "list --json: $(head -c 600 list.json)"
import json
d = json.load(open("list.json"))
ids = [l.split()[0] for l in open("want.txt") if not l.startswith("#")]
assert [r["run_id"] for r in d["runs"]] == ids, d["runs"]
assert len(d["folded"]) == 1 and d["folded"][0]["into"] == ids[0], d["folded"]
assert d["folded"][0]["parameters"]["lights.count"] == 4
PY

# --set sweep.KEY cannot say which block: refused, naming the whole-sweep form
expect 2 "m.yaml: --set sweep.lights.seed=[3]: sweep: expected --set 'sweep=[...]' (the whole list of blocks) on a sweep of blocks, found --set sweep.lights.seed" \
  "$SHADESWEEP" list --set 'sweep.lights.seed=[3]' m.yaml
# an empty block written in --set is an error, as in the file (a block --set empties is not)
expect 2 "m.yaml: --set sweep=[{}]: sweep[0]: expected a block with at least one parameter, found an empty mapping" \
  "$SHADESWEEP" list --set 'sweep=[{}]' m.yaml
# same FILE ARGS...: `list ARGS m.yaml` is `list FILE`
same() {
  local file=$1; shift
  "$SHADESWEEP" list "$@" m.yaml >a.txt 2>a.err || fail "list $*: $(cat a.err)"
  "$SHADESWEEP" list "$file" >b.txt 2>b.err || fail "list $file: $(cat b.err)"
  [ -s a.txt ] && cmp -s a.txt b.txt || fail "list $* != $file: $(diff a.txt b.txt)"
}
# the whole sweep replaced by blocks (the keys in place stay, the base) or by a mapping
# (its keys leave their place)
sed -e '/^sweep:/,$d' m.yaml >w1.yaml
printf 'sweep:\n  - {lights.seed: [5]}\n  - {resolution: [16x16]}\n' >>w1.yaml
same w1.yaml --set 'sweep=[{lights.seed: [5]}, {resolution: [16x16]}]'
[ "$(wc -l <a.txt)" -eq 2 ] || fail "sweep=[...]: $(cat a.txt)"
sed -e '/^sweep:/,$d' -e 's/^lights: .*/lights: {count: 4}/' m.yaml >w2.yaml
printf 'sweep:\n  lights.seed: [5, 6]\n' >>w2.yaml
same w2.yaml --set 'sweep={lights.seed: [5, 6]}'
# --set KEY on a key a block sweeps: fixed in every block; block 1, left with no key, is
# the base point once (and that is block 0's first run)
sed -e 's/^lights: .*/lights: {count: 8, seed: 1}/' -e '/^  - {lights.count/d' m.yaml >w3.yaml
"$SHADESWEEP" list --set lights.count=8 m.yaml >set.txt || fail "--set lights.count=8"
[ "$(grep -vc '^#' set.txt)" -eq 4 ] && grep -q "^# 1 of 5 grid points folded" set.txt &&
  cmp -s <(grep -v '^#' set.txt) <("$SHADESWEEP" list w3.yaml) || fail "--set lights.count=8: $(cat set.txt)"
# --smoke: resolution leaves block 0 (lights.seed 1, 2 at 160x120), block 1 as it was
"$SHADESWEEP" list --smoke m.yaml >smoke.txt || fail "--smoke"
[ "$(grep -vc '^#' smoke.txt)" -eq 3 ] && ! grep -q 'resolution=' smoke.txt \
  || fail "list --smoke: $(cat smoke.txt)"

need_gl
"$SHADESWEEP" run -o out m.yaml 2>run.err || fail "run: $(cat run.err)"
[ "$(cut -d, -f2 out/plan.csv | tail -n +2)" = "$(grep -v '^#' want.txt | cut -d' ' -f1)" ] \
  || fail "plan.csv: $(cut -d, -f1-4 out/plan.csv)"
[ "$(tail -n +2 out/summary.csv | wc -l)" -eq 5 ] || fail "summary.csv: $(cat out/summary.csv)"
grep -q "resolution=16x16, lights.seed=2, lights.count=4" out/summary.md || fail "summary.md"
"$SHADESWEEP" run --resume -o out m.yaml 2>resume.err || fail "resume: $(cat resume.err)"
grep -q "5 of 5 runs already complete" resume.err || fail "resume: $(cat resume.err)"
for i in 1 2; do "$SHADESWEEP" run --shard $i/2 -o s$i m.yaml 2>/dev/null || fail "shard $i"; done
"$SHADESWEEP" merge -o merged s1 s2 2>merge.err || fail "merge: $(cat merge.err)"
grep -q "merged 5 of 5 runs from 2 folders" merge.err || fail "merge: $(cat merge.err)"
