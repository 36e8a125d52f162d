#!/usr/bin/env bash
# Output folders: never clobbered by accident; one failing run does not stop the sweep.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat > tiny.yaml <<'YAML'
shadesweep: 1
name: tiny
scene: empty
renderers: [null]
duration: {frames: 3}
clock: fixed
sweep:
  resolution: [8x8, 32768x32768, 1x1]
YAML
set +e
"$SHADESWEEP" run tiny.yaml >out.txt 2>err.txt; rc=$?
set -e
# 32768x32768 exceeds llvmpipe's limits: that run fails with a clear message, the others run.
[ $rc -eq 1 ] || fail "sweep with one impossible run exited $rc, want 1: $(cat err.txt)"
grep -q "32768x32768 exceeds" err.txt || fail "no clear message for the oversize run: $(cat err.txt)"
"$PYTHON" - <<'PY'
import csv, sys
rows = list(csv.DictReader(open("out/tiny/summary.csv")))
st = [(r["width"], r["status"]) for r in rows]
if st != [("8", "ok"), ("32768", "failed:context"), ("1", "ok")]:
    print("FAIL: statuses", st, file=sys.stderr); sys.exit(1)
if "32768x32768 exceeds" not in rows[1]["message"] or rows[0]["message"] != "":
    print("FAIL: message column", [r["message"] for r in rows], file=sys.stderr); sys.exit(1)
PY

# An existing folder is an error without --force or --resume, and is left as it was.
echo keep > out/tiny/note.txt
set +e
"$SHADESWEEP" run tiny.yaml 2>err.txt; rc=$?
set -e
[ $rc -eq 2 ] && grep -q "exists; use --resume to finish it, --force to replace it" err.txt \
  || fail "existing folder: rc $rc $(cat err.txt)"
[ -f out/tiny/note.txt ] || fail "existing folder was touched"
# --force replaces a shadesweep folder's own files (and keeps anyone else's) ...
set +e
"$SHADESWEEP" run --force tiny.yaml 2>err.txt; rc=$?
set -e
[ $rc -eq 1 ] && [ "$(cat out/tiny/note.txt)" = keep ] && [ -f out/tiny/summary.csv ] \
  || fail "--force: rc $rc"
# ... but never a folder that is not one.
mkdir precious && echo data > precious/thesis.tex
set +e
"$SHADESWEEP" run --force -o precious tiny.yaml 2>err.txt; rc=$?
set -e
[ $rc -eq 2 ] && [ -f precious/thesis.tex ] && grep -q "not a shadesweep output folder" err.txt \
  || fail "--force on a foreign folder: rc $rc $(cat err.txt)"
# An output folder that cannot be created: a clear message, exit 2.
set +e
"$SHADESWEEP" run -o /proc/nonexistent/x tiny.yaml 2>err.txt; rc=$?
set -e
[ $rc -eq 2 ] && grep -q "/proc/nonexistent" err.txt || fail "unwritable output: rc $rc $(cat err.txt)"
echo ok
