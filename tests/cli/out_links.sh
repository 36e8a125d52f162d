#!/usr/bin/env bash
# Every write stays inside its folder (issue 39, items 1, 4 and 5): a symbolic link below
# the output folder is refused by name before anything is written (run --force,
# --resume, merge, report), and nothing outside the folder changes (checksums); OUT
# itself may be a link. The lock is held on the folder's descriptor: deleting the lock
# file lets no second writer in. merge refuses folders of another output format and runs
# of different builds (unless --allow-mixed-builds). Names from result files are escaped
# in summary.md and report.md.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat > t.yaml <<'YAML'
shadesweep: 1
name: t
scene: empty
renderers: [null]
resolution: 8x8
duration: {frames: 1}
clock: fixed
sweep:
  lights.seed: [1, 2]
YAML
# refile RUN_DIR: files.txt again after a test edited the run's files (what a hostile
# or another build's folder would hold, complete by its own list)
refile() {
  "$PYTHON" - "$1" <<'PY'
import os, sys
d = sys.argv[1]
lines = open(f"{d}/files.txt").read().splitlines()
out = [lines[0]]
for line in lines[1:]:
    name = line.split()[0]
    data = open(f"{d}/{name}", "rb").read()
    h = 0xcbf29ce484222325
    for b in data:
        h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    out.append(f"{name} {len(data)} {h:016x}")
open(f"{d}/files.txt", "w").write("\n".join(out) + "\n")
PY
}
LINKMSG="is a symbolic link"
"$SHADESWEEP" run -o other t.yaml 2>/dev/null || fail "run other"
"$SHADESWEEP" run -o a t.yaml 2>/dev/null || fail "run a"
id=$(ls a/runs | head -1)
before=$(tree other)

# --- 1. Links below OUT ----------------------------------------------------------
# runs/<id> linked to another sweep's run folder: --force and --resume refuse it
# before any run (they overwrote other/'s frames.csv, meta.yaml and summary.csv)
mv "a/runs/$id" a/moved
ln -s "../../other/runs/$id" "a/runs/$id"
a_before=$(tree a)
for mode in --force --resume; do
  expect 2 "a/runs/$id $LINKMSG (to ../../other/runs/$id): shadesweep never writes through a link below its output folder" \
    "$SHADESWEEP" run $mode -o a t.yaml
  [ "$(tree other)" = "$before" ] || fail "run $mode wrote through a/runs/$id"
  [ "$(tree a)" = "$a_before" ] || fail "run $mode changed a before refusing"
done
# merge --force into it: the same
"$SHADESWEEP" run --shard 1/2 -o s1 t.yaml 2>/dev/null || fail "shard 1"
"$SHADESWEEP" run --shard 2/2 -o s2 t.yaml 2>/dev/null || fail "shard 2"
"$SHADESWEEP" merge -o m s1 s2 2>/dev/null || fail "merge m"
mid=$(ls m/runs | head -1)
rm -r "m/runs/$mid"; ln -s "../../other/runs/$mid" "m/runs/$mid"
expect 2 "m/runs/$mid $LINKMSG" "$SHADESWEEP" merge --force -o m s1 s2
[ "$(tree other)" = "$before" ] || fail "merge --force wrote through m/runs/$mid"
rm "a/runs/$id"; mv a/moved "a/runs/$id"
# runs/ itself a link
mv a/runs a/runs.real; ln -s ../other/runs a/runs
expect 2 "a/runs $LINKMSG (to ../other/runs)" "$SHADESWEEP" run --force -o a t.yaml
[ "$(tree other)" = "$before" ] || fail "run --force wrote through a/runs"
rm a/runs; mv a/runs.real a/runs
# a file of ours linked out (the top-level summary.csv, a run's frames.csv), and a trial
# folder: refused, the target untouched
ln -sf ../other/summary.csv a/summary.md
expect 2 "a/summary.md $LINKMSG" "$SHADESWEEP" run --force -o a t.yaml
rm a/summary.md
ln -s "../../../other/runs/$id/frames.csv" "a/runs/$id/errors.csv"
expect 2 "a/runs/$id/errors.csv $LINKMSG" "$SHADESWEEP" run --resume -o a t.yaml
rm "a/runs/$id/errors.csv"
ln -s "../../../other/runs/$id" "a/runs/$id/trial-1"
expect 2 "a/runs/$id/trial-1 $LINKMSG" "$SHADESWEEP" run --force -o a t.yaml
rm "a/runs/$id/trial-1"
[ "$(tree other)" = "$before" ] || fail "a link of a file was written through"
# --force removes a folder's contents without following links: a link of the user's
# under another name stays, its target too
ln -s ../other mylink_kept
mv mylink_kept a/
"$SHADESWEEP" run --force -o a t.yaml 2>/dev/null || fail "run --force with a link of the user's"
[ -L a/mylink_kept ] && [ "$(tree other)" = "$before" ] || fail "--force followed or removed a/mylink_kept"
rm a/mylink_kept
# OUT itself may be a link (a results disk linked into a checkout)
mkdir disk; ln -s disk linked
"$SHADESWEEP" run -o linked t.yaml 2>/dev/null || fail "run into a linked OUT"
"$SHADESWEEP" run --force -o linked t.yaml 2>/dev/null || fail "run --force into a linked OUT"
[ -f disk/summary.csv ] && [ "$(ls disk/runs | wc -l)" -eq 2 ] || fail "linked OUT: no runs in disk/"

# report: report.md, plots/ and a plot linked out are refused, nothing written
mkdir elsewhere; echo "user's" > elsewhere/r.md; cp elsewhere/r.md elsewhere/s000-drawcalls.png
e_before=$(tree elsewhere)
ln -s ../elsewhere a/plots
expect 2 "report: a/plots $LINKMSG (to ../elsewhere): shadesweep report never writes through a link below its output folder" \
  "$SHADESWEEP" report a
rm a/plots; mkdir a/plots; ln -s ../../elsewhere/s000-drawcalls.png a/plots/s000-drawcalls.png
expect 2 "report: a/plots/s000-drawcalls.png $LINKMSG" "$SHADESWEEP" report a
rm -r a/plots; ln -s ../elsewhere/r.md a/report.md
expect 2 "report: a/report.md $LINKMSG" "$SHADESWEEP" report a
[ "$(tree elsewhere)" = "$e_before" ] || fail "report wrote through a link"
[ -L a/report.md ] && [ ! -e a/plots ] || fail "report changed a before refusing"
rm a/report.md
"$SHADESWEEP" report a >/dev/null || fail "report a"
[ -f a/report.md ] && [ ! -L a/report.md ] || fail "no report.md"
ls a/report.md.tmp.* 2>/dev/null && fail "a temporary report.md left"

# --- 2. The lock is held on the folder, not by the file --------------------------
cat > slow.yaml <<'YAML'
shadesweep: 1
name: slow
scene: empty
renderers: [null]
resolution: 8x8
duration: {seconds: 120}
YAML
# the holder measures for two minutes and is stopped by SIGINT once the checks are done,
# so a loaded machine cannot end it before them (a 6 s run once did, under ASan in CI)
"$SHADESWEEP" run -o busy slow.yaml >busy.out 2>busy.err &
pid=$!
for _ in $(seq 1 200); do [ -d busy/runs ] && [ "$(cat busy/lock 2>/dev/null)" = "$pid" ] && break; sleep 0.05; done
[ "$(cat busy/lock 2>/dev/null)" = "$pid" ] || fail "the lock does not name the sweep's pid"
rm busy/lock
expect 2 "busy is in use by shadesweep process $pid (it holds the lock on busy)" \
  "$SHADESWEEP" run --force -o busy slow.yaml
expect 2 "busy is in use by shadesweep process $pid" "$SHADESWEEP" merge --force -o busy s1 s2
expect 2 "busy is in use by shadesweep process $pid" "$SHADESWEEP" run --resume -o busy slow.yaml
kill -0 $pid 2>/dev/null || fail "the first sweep ended before the checks: $(cat busy.err)"
[ -e busy/lock ] && fail "a refused writer made a lock file"
kill -INT $pid
set +e
wait $pid; rc=$?
set -e
# the holder was not disturbed by the refused writers: it stops as any interrupted sweep
[ $rc -eq 130 ] || fail "the first sweep's exit status $rc: $(cat busy.err)"
grep -q "interrupted by SIGINT" busy.err || fail "the first sweep's end: $(cat busy.err)"
grep -qi "write" busy.err && fail "the first sweep reports a write failure: $(cat busy.err)"
# the lock ends with its holder: the next --force takes the folder
"$SHADESWEEP" run --force -o busy t.yaml 2>/dev/null || fail "run --force after the holder ended"

# --- 3. merge: output format and builds ------------------------------------------
cp -r s1 f1
sed -i 's/^format: .*/format: shadesweep-output 0/' f1/sweep.yaml
expect 2 "shadesweep merge: f1 is not a shadesweep output folder (its sweep.yaml says format: shadesweep-output 0, this version writes shadesweep-output 1): not merging it" \
  "$SHADESWEEP" merge -o fm f1 s2
[ -e fm ] && fail "merge of a foreign format made its output"
# a run of another build (its meta.yaml's commit changed, files.txt made to match)
cp -r s2 b2
bid=$(ls b2/runs | head -1)
sed -i 's/^  commit: .*/  commit: 0123456789ab/' "b2/runs/$bid/meta.yaml"
refile "b2/runs/$bid"
sid=$(ls s1/runs | head -1)
version=$(sed -n 's/^  version: //p' "s1/runs/$sid/meta.yaml" | head -1 | tr -d '"')
s1_before=$(tree s1); b2_before=$(tree b2)
expect 2 "shadesweep merge: refusing runs of different builds: run $sid in s1 is version $version, commit " \
  "$SHADESWEEP" merge -o bm s1 b2
grep -qF "run $bid in b2 is version $version, commit 0123456789ab; --allow-mixed-builds merges them anyway" cmd.err ||
  fail "the second build not named: $(cat cmd.err)"
[ -e bm ] && fail "a refused merge made its output"
expect 0 "shadesweep merge: warning: merging runs of different builds: run $sid in s1" \
  "$SHADESWEEP" merge --allow-mixed-builds -o bm s1 b2
[ "$(ls bm/runs | wc -l)" -eq 2 ] || fail "--allow-mixed-builds did not merge both runs"
[ "$(tree s1)" = "$s1_before" ] && [ "$(tree b2)" = "$b2_before" ] || fail "merge changed an input"

# --- 4. Names from result files are escaped in summary.md and report.md ----------
cp -r s1 h1; cp -r s2 h2
for run in h1/runs/* h2/runs/*; do
  "$PYTHON" - "$run/summary.csv" <<'PY'
import csv, sys
p = sys.argv[1]
rows = list(csv.reader(open(p, newline="")))
for r in rows[1:]:
    r[0], r[2] = "t|<b>x</b>&`y`", "nu|ll<i>"
csv.writer(open(p, "w", newline=""), lineterminator="\n").writerows(rows)
PY
  refile "$run"
done
"$SHADESWEEP" merge -o hm h1 h2 2>/dev/null || fail "merge of the hostile names"
grep -qF 'nu\|ll&lt;i&gt;' hm/summary.md || fail "summary.md: the renderer not escaped: $(grep -F 'nu' hm/summary.md)"
grep -qF '<i>' hm/summary.md && fail "summary.md passes HTML through"
"$SHADESWEEP" report hm >/dev/null 2>&1 || fail "report hm"
grep -qF 't\|&lt;b&gt;x&lt;/b&gt;&amp;\`y\`' hm/report.md || fail "report.md: the experiment not escaped: $(grep -n 't|' hm/report.md)"
grep -qF '<b>' hm/report.md && fail "report.md passes HTML through"
echo "PASS"
