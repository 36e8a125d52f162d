#!/usr/bin/env bash
# Every output that is not written is a failure (issue 39):
#   - each command's stdout on a full device (/dev/full): exit 2 and one line on stderr
#     naming standard output and the cause (they exited 0 with their output lost);
#   - a sweep under a file-size limit (ulimit -f): exit 2, not death by SIGXFSZ (153),
#     a message naming the file with "File too large", no temporary left, and nothing
#     outside its folder changed.
#   - a sweep whose image module cannot be loaded (common/image_codec.h): each run
#     failed:write with the image's path and the loader's reason, exit 1.
# The failing summary write (summary.json on a resume) is tests/cli/io_errors.sh's.
. "$(dirname "$0")/lib.sh"
cd "$T"
cat >m.yaml <<'YAML'
shadesweep: 1
name: wf
scene: shapes
renderers: [null]
resolution: 16x16
trials: 1
warmup: {frames: 0}
duration: {frames: 2}
clock: fixed
YAML
full() {
  local rc=0
  "$SHADESWEEP" "$@" >/dev/full 2>err.txt || rc=$?
  [ $rc -eq 2 ] || fail "$* >/dev/full: exit $rc, want 2: $(cat err.txt)"
  tail -n1 err.txt | grep -qE "^shadesweep [-a-z]+: standard output: No space left on device \(the disk is full\)$" ||
    fail "$* >/dev/full: no message naming standard output: $(cat err.txt)"
}
full list m.yaml
full list --json m.yaml
full validate m.yaml
full params
full params --json
full columns --markdown
full version
full --help
full ratios --help
full run --help
# the same commands to a device that takes the bytes: exit 0
"$SHADESWEEP" list m.yaml >/dev/null || fail "list >/dev/null"
"$SHADESWEEP" params >/dev/null || fail "params >/dev/null"

# `ratios --help` is ratios' own usage, not the top-level lines that point back at it
"$SHADESWEEP" ratios --help >help.txt || fail "ratios --help: exit $?"
grep -q "^    ratio FOLDER_A RUN_A FOLDER_B RUN_B" help.txt || fail "ratios --help: $(cat help.txt)"

need_gl
# a file-size limit of 2 KiB (bash counts ulimit -f in KiB): the run's files do not fit
snapshot() {   # every file outside the output folder, with its checksum
  find . -path ./o -prune -o -type f ! -name out.txt ! -name err.txt ! -name 'snap*' -print0 |
    sort -z | xargs -0 md5sum
}
snapshot >snap1.txt
rc=0
(ulimit -f 2; exec "$SHADESWEEP" run -o o m.yaml >out.txt 2>err.txt) || rc=$?
[ $rc -eq 2 ] || fail "under ulimit -f 2: exit $rc, want 2 (153: killed by SIGXFSZ): $(cat err.txt)"
grep -qE "^run [0-9a-f]{12}: o/runs/[0-9a-f]{12}/[-a-z0-9/]+\.[a-z]+: File too large \(over the file-size limit, ulimit -f, or the file system's largest file\)$" err.txt ||
  fail "under ulimit -f 2: no message naming the file: $(cat err.txt)"
leftover=$(find o -name '*.tmp.*')
[ -z "$leftover" ] || fail "under ulimit -f 2: temporaries left: $leftover"
snapshot >snap2.txt
cmp -s snap1.txt snap2.txt || fail "under ulimit -f 2: files outside the folder changed: $(diff snap1.txt snap2.txt)"
# the limit gone, the folder resumes to a whole sweep
"$SHADESWEEP" run --resume -o o m.yaml >out.txt 2>err.txt || fail "resume: exit $?: $(cat err.txt)"
for f in summary.csv summary.md summary.json summary_long.csv; do
  [ -s "o/$f" ] || fail "resume: no o/$f"
done

# no image module: every run fails to write its first image, saying why
rc=0
sed 's/renderers: \[null\]/renderers: [forward-spml]/' m.yaml >shaded.yaml   # null draws no image
SHADESWEEP_IMAGE_MODULE=$T/no-such-module.so "$SHADESWEEP" run -o nomod shaded.yaml >out.txt 2>err.txt || rc=$?
[ $rc -eq 1 ] || fail "without the image module: exit $rc, want 1: $(cat err.txt)"
"$PYTHON" - <<'PY' || fail "without the image module: summary.csv"
import csv, sys
rows = list(csv.DictReader(open("nomod/summary.csv")))
want = "cannot write image: cannot load the image module: "
ok = len(rows) == 1 and rows[0]["status"] == "failed:write" and want in rows[0]["message"] \
    and "no-such-module.so" in rows[0]["message"] and ".png" in rows[0]["message"]
if not ok:
    print(rows, file=sys.stderr)
sys.exit(0 if ok else 1)
PY
echo ok
