#!/usr/bin/env bash
# --resume refuses a plan other than its folder's: a file scene's run ids follow the
# file's content, so an edited scene file under the same manifest makes new ids, and
# resuming would orphan every run of the folder ("0 of 2 runs already complete").
# It names the file and both content hashes, exits 2 and deletes nothing; --force
# starts over. An unreadable plan.csv is refused too.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
mkdir scenes
cat >scenes/a.obj <<'OBJ'
v -1 0 -1
v 1 0 -1
v 1 0 1
v -1 0 1
vn 0 1 0
f 1//1 3//1 2//1
f 1//1 4//1 3//1
OBJ
cat >m.yaml <<'YAML'
shadesweep: 1
name: edited
scene: {file: scenes/a.obj}
renderers: [null]
resolution: 16x16
duration: {frames: 2}
clock: fixed
lights: {count: 4, radius: 1}
sweep:
  lights.seed: [1, 2]
YAML
"$SHADESWEEP" run -o out m.yaml >/dev/null 2>run.err || fail "run: $(cat run.err)"
"$SHADESWEEP" run --resume -o out m.yaml >/dev/null 2>again.err || fail "resume: $(cat again.err)"
grep -qx "resuming: 2 of 2 runs already complete" again.err || fail "resume: $(cat again.err)"
old=$(sed -n 2p out/plan.csv | grep -o 'file:[0-9a-f]\{16\}' | cut -c6-)
[ -n "$old" ] || fail "no scene hash in plan.csv: $(cat out/plan.csv)"
ids_before=$(ls out/runs)
snapshot() { find out -type f ! -name lock -printf '%p %s %T@\n' | sort; }
snapshot >before.txt
# the scene file edited: one vertex moved
sed -i 's/^v 1 0 1$/v 1 0.5 1/' scenes/a.obj
set +e
"$SHADESWEEP" run --resume -o out m.yaml >out.txt 2>err.txt; rc=$?
set -e
[ $rc -eq 2 ] && [ ! -s out.txt ] && [ "$(wc -l <err.txt)" -eq 1 ] || fail "edited: exit $rc: $(cat out.txt err.txt)"
grep -qx "shadesweep run: --resume: the plan differs from out's: 2 of its 2 runs are not in this plan (scene file scenes/a.obj changed since: its content hash was $old, is [0-9a-f]\{16\}); use --force to start over (nothing was deleted)" err.txt \
  || fail "edited: $(cat err.txt)"
grep -q "hash was $old, is $old)" err.txt && fail "edited: the same hash twice: $(cat err.txt)"
snapshot | cmp -s - before.txt || fail "edited: the folder changed: $(snapshot | diff - before.txt)"
# --force starts over: the folder holds the new plan's runs only
"$SHADESWEEP" run --force -o out m.yaml >/dev/null 2>force.err || fail "--force: $(cat force.err)"
[ "$(ls out/runs | wc -l)" -eq 2 ] && [ -z "$(comm -12 <(echo "$ids_before") <(ls out/runs))" ] \
  || fail "--force: runs $(ls out/runs), before $ids_before"
"$SHADESWEEP" run --resume -o out m.yaml >/dev/null 2>again.err || fail "resume after --force: $(cat again.err)"
grep -qx "resuming: 2 of 2 runs already complete" again.err || fail "resume after --force: $(cat again.err)"
# a plan.csv that cannot be read: refused, not taken for an empty plan
printf 'index,run_id,shard\n0,abc\n' >out/plan.csv
set +e
"$SHADESWEEP" run --resume -o out m.yaml >out.txt 2>err.txt; rc=$?
set -e
[ $rc -eq 2 ] && [ "$(wc -l <err.txt)" -eq 1 ] \
  && grep -q "^shadesweep run: --resume: cannot tell whether out holds this plan (.*plan.csv.*); use --force to start over$" err.txt \
  || fail "bad plan.csv: exit $rc: $(cat err.txt)"
[ "$(ls out/runs | wc -l)" -eq 2 ] || fail "bad plan.csv: runs deleted"
