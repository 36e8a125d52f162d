#!/usr/bin/env bash
# Every write checked (issue 22): a sweep whose writes fail, one failure point at a time,
# through tests/cli/io_fault.c (LD_PRELOAD, after SQLite's I/O error injection). A first
# run counts the write-level calls the sweep makes to its output folder; then the Nth call
# fails (ENOSPC, the disk staying full after it, or a single EIO), and each time:
#   - the sweep exits non-zero (summary.md too, since issue 39); the run whose file was
#     lost is failed:write, never ok;
#   - a message names the file (its final name) with "No space left on device (the disk
#     is full)" (or the I/O error);
#   - nothing is half-written under a final name: files.txt's files exist with its sizes,
#     no empty file, every PNG ends with IEND, every CSV with a newline, no *.tmp.* left;
#   - `--resume` without the shim finishes the sweep: exit 0, every run ok, files whole.
# Three points are chosen below (a sweep and a resume each, about 5 s a call, 50 calls);
# IOFAULT_ALL=1 tries them all (every one passed on 2026-12-04).
. "$(dirname "$0")/lib.sh"
SHIM=${1:?the io_fault shim library}
need_gl
[ -f "$SHIM" ] || fail "no shim at $SHIM"
cd "$T"
cat > w.yaml <<'YAML'
shadesweep: 1
name: w
scene: shapes
renderers: [deferred]
resolution: 32x24
trials: 1
warmup: {frames: 0}
duration: {frames: 3}
clock: fixed
step: 0.1
lights: {count: 2, radius: 8}
outputs: {screenshots: [0]}
error:
  reference: {renderer: forward-spml}
  at: [0.1]
  save_images: true
YAML

# The sanitizer build: the ASan runtime must come first in the preload list.
PRELOAD=$SHIM
asan=$(ldd "$SHADESWEEP" | awk '/libasan/ {print $3}')
if [ -n "$asan" ]; then
  [ -f "$asan" ] || { echo "SKIP: ASan runtime $asan not found for preloading" >&2; exit 77; }
  PRELOAD="$asan:$SHIM"
fi

# under_shim OUT AT PERSIST ERRNO: the sweep into OUT with call AT failing
under_shim() {
  rm -f "$T/count" "$T/hit"
  set +e
  LD_PRELOAD="$PRELOAD" IOFAULT_DIR="$T/$1" IOFAULT_COUNT="$T/count" IOFAULT_AT="$2" \
    IOFAULT_PERSIST="$3" IOFAULT_ERRNO="$4" IOFAULT_HIT="$T/hit" IOFAULT_TRACE="$T/trace" \
    "$SHADESWEEP" run -o "$1" w.yaml >"$T/out.txt" 2>"$T/err.txt"
  rc=$?
  set -e
}

# check_folder OUT: nothing cut off under a final name
check_folder() {
  "$PYTHON" - "$1" <<'PY' || fail "after $what: $(cat "$T/err.txt")"
import os, sys
out = sys.argv[1]
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
for dp, dn, fn in os.walk(out):
    for f in fn:
        p = os.path.join(dp, f)
        if ".tmp." in f: fail(f"temporary file left: {p}")
        size = os.path.getsize(p)
        if f in ("lock", "log.txt"): continue
        if size == 0: fail(f"empty file under its final name: {p}")
        data = open(p, "rb").read()
        if f.endswith(".png") and not data.endswith(b"IEND\xaeB`\x82"): fail(f"cut PNG {p}")
        if f.endswith(".exr") and not data.startswith(b"\x76\x2f\x31\x01"): fail(f"bad EXR {p}")
        if f.endswith((".csv", ".yaml", ".txt", ".md")) and not data.endswith(b"\n"):
            fail(f"cut text file {p}")
    if "files.txt" in fn:
        lines = open(os.path.join(dp, "files.txt")).read().splitlines()[1:]
        for line in lines:
            name, size, _ = line.split()
            p = os.path.join(dp, name)
            if not os.path.exists(p): fail(f"files.txt vouches for a missing {p}")
            if os.path.getsize(p) != int(size): fail(f"{p}: size differs from files.txt")
PY
}

# A clean sweep under the shim, counting: the calls and the files they went to.
rm -f "$T/trace"
under_shim c0 0 0 ENOSPC
[ $rc -eq 0 ] || fail "counting run: exit $rc: $(cat "$T/err.txt")"
K=$(stat -c %s "$T/count")
[ "$K" -gt 20 ] || fail "only $K write calls counted: is the shim preloaded?"
grep -q '\.png\.tmp\.' "$T/trace" || fail "no PNG write counted: $(head "$T/trace")"
grep -q '\.exr\.tmp\.' "$T/trace" || fail "no EXR write counted"
check_folder c0
# the points, each "N PERSIST ERRNO": the first call on a PNG (a single EIO: the device
# recovers, the sweep goes on and records the run as failed:write), on a trial's
# files.txt (the child's last file: the parent writes the trial's row again) and the
# last call (summary.md), both ENOSPC with the disk staying full. IOFAULT_ALL=1: every
# call, ENOSPC that stays (about 5 s a call).
first() { awk -v re="$1" '$3 ~ re { print $1; exit }' "$T/trace"; }
if [ "${IOFAULT_ALL:-0}" = 1 ]; then
  points=$(seq -f "%g 1 ENOSPC" 1 "$K")
else
  points="$(first '[.]png[.]tmp[.]') 0 EIO
$(first 'trial-1/files[.]txt[.]tmp[.]') 1 ENOSPC
$K 1 ENOSPC"
fi
echo "$points" | grep -qv '^ ' || fail "a failure point is missing: $points"
npoints=$(echo "$points" | wc -l)
echo "io_errors: $K write calls; failing: $(echo "$points" | tr '\n' ,)"

while read -r n mode e; do
  out=o$n
  if [ "$e" = EIO ]; then text="Input/output error (the device reported an I/O error)"
  else text="No space left on device (the disk is full)"; fi
  what="call $n of $K failing with $e (persist $mode)"
  under_shim "$out" "$n" "$mode" "$e"
  [ -s "$T/hit" ] || fail "$what: the shim never failed a call"
  hit=$(head -n1 "$T/hit" | cut -d' ' -f2-)
  rel=${hit#"$T/"}
  rel=$(echo "$rel" | sed -E 's/\.tmp\.[0-9]+$//')
  grep -F "$rel: " "$T/err.txt" | grep -qF "$text" \
    || fail "$what: no message naming $rel with '$text': $(cat "$T/err.txt")"
  [ $rc -ne 0 ] || fail "$what: exit 0 after losing $rel"
  case $rel in
    */runs/*)
      # the run is not ok: failed:write where its row could be written at all, and
      # with a single failure it could
      if [ $mode = 0 ] || [ -f "$out/summary.csv" ]; then
        "$PYTHON" - "$out" <<'PY' || fail "$what: the run is not failed:write: $(cat "$T/err.txt")"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/summary.csv")))
sys.exit(0 if rows and all(r["status"] == "failed:write" for r in rows) else 1)
PY
      fi ;;
  esac
  check_folder "$out"
  what="resume after call $n"
  set +e
  "$SHADESWEEP" run --resume -o "$out" w.yaml >"$T/out.txt" 2>"$T/err.txt"; rc=$?
  set -e
  [ $rc -eq 0 ] || fail "$what: exit $rc: $(cat "$T/err.txt")"
  check_folder "$out"
  "$PYTHON" - "$out" <<'PY' || fail "$what"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/summary.csv")))
if len(rows) != 1 or rows[0]["status"] != "ok": print(f"FAIL: rows {rows}", file=sys.stderr); sys.exit(1)
PY
  [ -f "$out/summary.md" ] || fail "$what: no summary.md"
  ls "$out"/runs/*/screenshot-trial1-t0.png "$out"/runs/*/error-trial1-t0.1-error.exr >/dev/null \
    || fail "$what: images missing"
  rm -rf "$out"
done <<<"$points"

# The folder's summaries are written together (issue 39): a resume whose summary.json
# cannot be written (the disk full from its first write on) exits 2, names the file,
# and removes the summaries of the earlier sweep that would now describe other runs
# than summary.csv; nothing is left under a temporary name, and a resume without the
# shim writes them all again.
"$SHADESWEEP" run -o r w.yaml >"$T/out.txt" 2>"$T/err.txt" || fail "sweep r: $(cat "$T/err.txt")"
rm -f "$T/count" "$T/trace"
LD_PRELOAD="$PRELOAD" IOFAULT_DIR="$T/r" IOFAULT_COUNT="$T/count" IOFAULT_AT=0 \
  IOFAULT_TRACE="$T/trace" "$SHADESWEEP" run --resume -o r w.yaml >"$T/out.txt" 2>"$T/err.txt" ||
  fail "counting resume: $(cat "$T/err.txt")"
n=$(first 'summary[.]json[.]tmp[.]')
[ -n "$n" ] || fail "the resume wrote no summary.json: $(cat "$T/trace")"
rm -f "$T/count" "$T/hit"
set +e
LD_PRELOAD="$PRELOAD" IOFAULT_DIR="$T/r" IOFAULT_COUNT="$T/count" IOFAULT_AT="$n" \
  IOFAULT_PERSIST=1 IOFAULT_ERRNO=ENOSPC IOFAULT_HIT="$T/hit" \
  "$SHADESWEEP" run --resume -o r w.yaml >"$T/out.txt" 2>"$T/err.txt"
rc=$?
set -e
rm -f "$T/count"
[ $rc -eq 2 ] || fail "summary.json lost on a resume: exit $rc: $(cat "$T/err.txt")"
grep -qxF "shadesweep run: no summary table: r/summary.json: No space left on device (the disk is full); removed summary.md, summary.json, summary_long.csv, which would describe other runs than summary.csv" "$T/err.txt" ||
  fail "summary.json lost on a resume: message: $(cat "$T/err.txt")"
for f in summary.md summary.json summary_long.csv; do
  [ ! -e "r/$f" ] || fail "summary.json lost on a resume: a stale r/$f stayed"
done
what="summary.json lost on a resume"
check_folder r
"$SHADESWEEP" run --resume -o r w.yaml >"$T/out.txt" 2>"$T/err.txt" || fail "resume r: $(cat "$T/err.txt")"
for f in summary.md summary.json summary_long.csv; do
  [ -s "r/$f" ] || fail "resume r: no r/$f"
done
echo "ok ($npoints failure points, and a summary lost on a resume)"
