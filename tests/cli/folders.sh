#!/usr/bin/env bash
# Output folders that cannot lose anyone's data (issue 14): ownership, one writer per
# folder, runs complete only when their files.txt proves it, resume of the same sweep
# only, the exit status of the whole folder, up-front refusals, a closed stderr.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat > t.yaml <<'YAML'
shadesweep: 1
name: t
scene: empty
renderers: [null]
resolution: 32x32
trials: 2
duration: {frames: 3}
clock: fixed
sweep:
  lights.seed: [1, 2, 3, 4]
YAML
# check_summary DIR N: DIR/summary.csv has exactly N rows, each with the header's
# number of fields, no (run, trial) twice, every run id one of the plan's
check_summary() {
  "$PYTHON" - "$1" "$2" <<'PY'
import csv, sys
d, n = sys.argv[1], int(sys.argv[2])
def fail(m): print("FAIL:", d, m, file=sys.stderr); sys.exit(1)
plan = {r["run_id"] for r in csv.DictReader(open(f"{d}/plan.csv"))}
rows = list(csv.reader(open(f"{d}/summary.csv", newline="")))
if any(len(r) != len(rows[0]) for r in rows): fail(f"a row of another width: {[len(r) for r in rows]}")
keys = [(r[1], r[12]) for r in rows[1:]]
if len(keys) != n or len(set(keys)) != n: fail(f"{len(keys)} rows ({len(set(keys))} distinct), want {n}")
if not {k[0] for k in keys} <= plan: fail("rows of runs not in the plan")
PY
}

# --- 1. Ownership --------------------------------------------------------------
# A folder of the user's that merely has a plan.csv: --force and --resume refuse it
# and touch nothing (today --force deleted it whole, --resume overwrote its files).
mkdir thesis
echo "my plan" > thesis/plan.csv
echo "my numbers" > thesis/summary.csv
echo "draft" > thesis/notes.tmp.1
echo '\documentclass{article}' > thesis/thesis.tex
before=$(tree thesis)
expect 2 "thesis exists and is not a shadesweep output folder (no sweep.yaml)" \
  "$SHADESWEEP" run --force -o thesis t.yaml
expect 2 "thesis exists and is not a shadesweep output folder (no sweep.yaml)" \
  "$SHADESWEEP" run --resume -o thesis t.yaml
expect 2 "not a shadesweep output folder" "$SHADESWEEP" run -o thesis t.yaml
# A folder shadesweep had just made when it was killed (only its lock and the temporary
# file of its first sweep.yaml) is its own, fresh: --resume takes it and clears the
# leftover; a name outside that pattern still makes a folder the user's.
mkdir killed
echo 4242 > killed/lock
echo "format: half-writ" > killed/sweep.yaml.tmp.4242
"$SHADESWEEP" run --resume -o killed t.yaml >/dev/null 2>"$T/cmd.err" ||
  fail "resume of a folder killed before its sweep.yaml: $(cat "$T/cmd.err")"
[ -f killed/sweep.yaml ] && [ ! -e killed/sweep.yaml.tmp.4242 ] ||
  fail "killed folder: $(ls killed)"
check_summary killed 8
mkdir notours
echo "mine" > notours/sweep.yaml.tmp.draft
expect 2 "notours exists and is not a shadesweep output folder (no sweep.yaml)" \
  "$SHADESWEEP" run --resume -o notours t.yaml
[ "$(cat notours/sweep.yaml.tmp.draft)" = mine ] || fail "notours: its file was touched"
[ "$(tree thesis)" = "$before" ] && [ ! -e thesis/lock ] || fail "the user's folder was touched"
# a sweep.yaml of someone else's (or an older shadesweep's: no format marker)
mkdir old && printf 'experiment: t\nmanifest_hash: "0123456789abcdef"\n' > old/sweep.yaml
echo data > old/plan.csv
before=$(tree old)
expect 2 "lacks format: shadesweep-output 1" "$SHADESWEEP" run --force -o old t.yaml
[ "$(tree old)" = "$before" ] || fail "a folder without the format marker was touched"

# sweep.yaml comes first and says the folder is ours
"$SHADESWEEP" run -o a t.yaml 2>/dev/null || fail "first sweep"
[ "$(head -1 a/sweep.yaml)" = "format: shadesweep-output 1" ] || fail "sweep.yaml: $(head -1 a/sweep.yaml)"
grep -q '^manifest_hash: ' a/sweep.yaml || fail "no manifest hash in sweep.yaml"
# --force on our folder deletes only what shadesweep wrote
run1=$(ls a/runs | head -1)
echo mine > a/notes.txt
echo mine > a/draft.tmp.7
echo mine > a/runs/$run1/annotations.txt
echo mine > a/runs/$run1/x.tmp.3
mkdir a/runs/figures && echo mine > a/runs/figures/f.txt
mine="a/notes.txt a/draft.tmp.7 a/runs/$run1/annotations.txt a/runs/$run1/x.tmp.3 a/runs/figures/f.txt"
"$SHADESWEEP" run --force -o a t.yaml 2>/dev/null || fail "--force"
for f in $mine; do [ "$(cat $f)" = mine ] || fail "--force deleted $f"; done
"$SHADESWEEP" run --resume -o a t.yaml 2>/dev/null || fail "--resume"
for f in $mine; do [ "$(cat $f)" = mine ] || fail "--resume deleted $f"; done
check_summary a 8
# summary.md is shadesweep's: a write of it killed half-way is swept by the next resume
# (cli-signals once found summary.md.tmp.<pid> left for good)
echo half > a/summary.md.tmp.99
"$SHADESWEEP" run --resume -o a t.yaml 2>/dev/null || fail "--resume over a temporary"
[ ! -e a/summary.md.tmp.99 ] || fail "--resume left summary.md.tmp.99"
[ -f a/summary.md ] || fail "no summary.md"

# Empty output folders: -o "" is an error, and nothing is written (today: into /).
mkdir empty-o && cd empty-o
expect 2 'the output folder is empty (-o "" or an empty name)' "$SHADESWEEP" run -o "" ../t.yaml
expect 2 'the output folder is empty' "$SHADESWEEP" merge -o "" ../a
[ -z "$(ls -A)" ] || fail "-o '' wrote here: $(ls -A)"
cd ..
[ ! -e /plan.csv ] || [ /plan.csv -ot t.yaml ] || fail "-o '' wrote /plan.csv"

# merge: an output that is one of its inputs, or inside one, is refused; inputs untouched
"$SHADESWEEP" run --shard 1/2 -o s1 t.yaml 2>/dev/null || fail "shard 1"
"$SHADESWEEP" run --shard 2/2 -o s2 t.yaml 2>/dev/null || fail "shard 2"
b1=$(tree s1); b2=$(tree s2)
expect 2 "merge never writes into its inputs" "$SHADESWEEP" merge -o s1 --force s1 s2
expect 2 "merge never writes into its inputs" "$SHADESWEEP" merge -o ./s2/ --force s1 s2
expect 2 "merge never writes into its inputs" "$SHADESWEEP" merge -o s1/merged s1 s2
ln -s s1 s1link
expect 2 "merge never writes into its inputs" "$SHADESWEEP" merge --force -o s1link s1 s2
[ "$(tree s1)" = "$b1" ] && [ "$(tree s2)" = "$b2" ] || fail "merge touched an input"
"$SHADESWEEP" merge -o m s1 s2 2>/dev/null || fail "merge"
check_summary m 8
[ "$(tree s1)" = "$b1" ] && [ "$(tree s2)" = "$b2" ] || fail "merge touched an input"
# merge -o over a folder that is not ours: refused even with --force
expect 2 "thesis exists and is not a shadesweep output folder" "$SHADESWEEP" merge --force -o thesis s1 s2

# --- 2. One writer per folder ----------------------------------------------------
cat > slow.yaml <<'YAML'
shadesweep: 1
name: slow
scene: empty
renderers: [null]
resolution: 16x16
duration: {seconds: 20}
sweep:
  lights.seed: [1, 2]
YAML
"$SHADESWEEP" run -o busy slow.yaml 2>busy.err &
pid=$!
for _ in $(seq 1 200); do [ -d busy/runs ] && [ "$(cat busy/lock 2>/dev/null)" = "$pid" ] && break; sleep 0.05; done
[ "$(cat busy/lock 2>/dev/null)" = "$pid" ] || fail "the lock does not name the sweep's pid"
for mode in --resume --force; do
  expect 2 "busy is in use by shadesweep process $pid" "$SHADESWEEP" run $mode -o busy slow.yaml
done
expect 2 "busy is in use by shadesweep process $pid" "$SHADESWEEP" merge --force -o busy a
kill -0 $pid || fail "the sweep did not survive the second writers"
# a dead holder's lock is no obstacle (flock goes with the process)
kill -9 $pid; wait $pid 2>/dev/null || true
sleep 0.2
[ -f busy/lock ] || fail "no lock file"
"$SHADESWEEP" run --resume -o busy slow.yaml 2>stale.err &
rpid=$!
for _ in $(seq 1 100); do [ "$(cat busy/lock 2>/dev/null)" = "$rpid" ] && break; sleep 0.05; done
grep -q "in use" stale.err && fail "a dead process's lock stopped the resume: $(cat stale.err)"
[ "$(cat busy/lock)" = "$rpid" ] || fail "resume did not take the stale lock"
kill -9 $rpid; wait $rpid 2>/dev/null || true

# --- 3. Complete only when proven ------------------------------------------------
"$SHADESWEEP" run -o c t.yaml 2>/dev/null || fail "sweep c"
mapfile -t ids < <(tail -n +2 c/plan.csv | cut -d, -f2)
cp -r c c_copy   # merge gets the same damage below
damage() {   # damage DIR: four runs broken four ways
  local d=$1
  head -c -40 "$d/runs/${ids[0]}/summary.csv" > x && mv x "$d/runs/${ids[0]}/summary.csv"   # cut off mid-row
  : > "$d/runs/${ids[1]}/summary.csv"                                                   # empty
  echo "{{ not yaml" >> "$d/runs/${ids[2]}/meta.yaml"                                    # broken meta
  rm "$d/runs/${ids[3]}/frames.csv"                                                     # missing file
}
damage c
expect 0 "resuming: 0 of 4 runs already complete" "$SHADESWEEP" run --resume -o c t.yaml
for why in "${ids[0]} is incomplete (summary.csv: " "${ids[1]} is incomplete (summary.csv: 0 bytes" \
           "${ids[2]} is incomplete (meta.yaml: " "${ids[3]} is incomplete (frames.csv: missing)"; do
  grep -qF "resuming: run $why" cmd.err || fail "resume did not say '$why': $(cat cmd.err)"
done
[ "$(grep -c '^[0-9] of 8: run ' cmd.err)" -eq 8 ] || fail "resume did not rerun the 4 runs' 8 trials"
check_summary c 8
# a run whose summary.csv has another header (another version's) is rerun up front
id=${ids[1]}
sed -i '1s/^experiment,/experimentX,/' c/runs/$id/summary.csv
# (files.txt must agree for this case to reach the header check)
"$PYTHON" - c/runs/$id <<'PY'
import sys, os
d = sys.argv[1]
def fnv(b):
    h = 0xcbf29ce484222325
    for x in b: h = ((h ^ x) * 0x100000001b3) & 0xffffffffffffffff
    return h
lines = open(f"{d}/files.txt").read().splitlines()
out = [lines[0]]
for l in lines[1:]:
    n, s, h = l.split()
    if n == "summary.csv":
        b = open(f"{d}/{n}", "rb").read(); s, h = str(len(b)), "%016x" % fnv(b)
    out.append(f"{n} {s} {h}")
open(f"{d}/files.txt", "w").write("\n".join(out) + "\n")
PY
expect 0 "resuming: run $id is incomplete (summary.csv: header differs" "$SHADESWEEP" run --resume -o c t.yaml
[ "$(grep -c '^[0-9] of 2: run ' cmd.err)" -eq 2 ] || fail "the run with a bad header was not rerun"
check_summary c 8
# merge takes no damaged run, says which and why, and writes only parsed rows
damage c_copy
expect 1 "missing runs (no folder has them complete)" "$SHADESWEEP" merge -o cm c_copy
for i in 0 1 2 3; do
  grep -qF "run ${ids[$i]} in c_copy is incomplete (" cmd.err || fail "merge did not name ${ids[$i]}: $(cat cmd.err)"
done
grep -qF "merged 0 of 4 runs" cmd.err || fail "merge took damaged runs: $(cat cmd.err)"
check_summary cm 0

# --- 4. Resume is the same sweep; the exit status is the folder's ----------------
sed 's/duration: {frames: 3}/duration: {frames: 4}/' t.yaml > t2.yaml
before=$(tree a)
h1=$(grep manifest_hash a/sweep.yaml | tr -dc 0-9a-f | tail -c 16)
expect 2 "--resume: a was made from manifest t.yaml (hash $h1), this is t2.yaml (hash " \
  "$SHADESWEEP" run --resume -o a t2.yaml
expect 2 "--resume: a holds shard all, this run is 1/2: not the same sweep" \
  "$SHADESWEEP" run --resume --shard 1/2 -o a t.yaml
expect 2 "not the same sweep" "$SHADESWEEP" run --resume --scale 0.5 -o a t.yaml
[ "$(tree a)" = "$before" ] || fail "a refused resume changed the folder"
expect 2 "--retry-failed: only with --resume" "$SHADESWEEP" run --retry-failed -o a t.yaml

# --- 6 (in part). --device N that does not exist: refused before anything is written
n=$("$SHADESWEEP" info | sed -n 's/^egl_devices: \([0-9]*\)$/\1/p')
if [ -n "$n" ]; then
  expect 2 "--device 99: no such EGL device; $n found" "$SHADESWEEP" run --device 99 -o dev t.yaml
  [ ! -e dev ] || fail "--device 99 created its output folder"
  expect 2 "no such EGL device" "$SHADESWEEP" run --resume --device 99 -o a t.yaml
  [ "$(tree a)" = "$before" ] || fail "--device 99 changed the folder"
else
  echo "folders: no EGL device enumeration here: --device part skipped" >&2
fi

# --- A closed stderr: the sweep runs whole (today: exit 2 and a half-made folder) ---
set +e
"$SHADESWEEP" run -o closed t.yaml 2>&-; rc=$?
set -e
[ $rc -eq 0 ] || fail "stderr closed: exit $rc"
check_summary closed 8
[ -z "$(find closed -name '*.tmp.*')" ] || fail "temporary files left"
# ... and a stderr whose reader has gone (a closed pipe): no SIGPIPE death half-way, the
# folder complete, and exit 2, since what it said was not written (issue 39: stdout and
# stderr are checked at exit)
{ rc=0; "$SHADESWEEP" run -o piped t.yaml 2>&1 >/dev/null || rc=$?; echo "$rc" > piped.rc; } |
  true
[ "$(cat piped.rc)" -eq 2 ] || fail "stderr into a closed pipe: exit $(cat piped.rc), not 2"
check_summary piped 8
echo ok
