#!/usr/bin/env bash
# Hostile file systems: a disk that fills mid-sweep, an output parent that cannot
# be written, a manifest deleted while the sweep runs.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"

# Mounts and immutable flags made here are undone whatever happens, before lib.sh's
# rm -rf of the scratch folder (which would fail on them).
mounts=()
immutable=()
cleanup() {
  local m d
  for d in "${immutable[@]}"; do chattr -i "$d" 2>/dev/null || true; done
  for m in "${mounts[@]}"; do umount "$m" 2>/dev/null || umount -l "$m" 2>/dev/null || true; done
  rm -rf "$T"
}
trap cleanup EXIT
# mount_tmpfs DIR OPTIONS: true when mounted
mount_tmpfs() {
  mkdir -p "$1"
  mount -t tmpfs -o "$2" tmpfs "$1" 2>/dev/null || return 1
  mounts+=("$T/$1")
}

# Checks everything under an output folder: no temporary file is left, and every
# file under a final name is complete: each CSV parses, has its header and the
# header's number of fields on every row, and ends with a line end; each
# meta.yaml is a YAML mapping. Prints the number of run summaries with an ok row.
check_outputs() {
  "$PYTHON" - "$1" <<'PY'
import csv, glob, os, sys, yaml
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
root = sys.argv[1]
first_column = {"plan.csv": "index", "summary.csv": "experiment", "frames.csv": "run_id",
                "seconds.csv": "run_id", "passes.csv": "run_id"}
ok_runs = 0
for dirpath, _, names in os.walk(root):
    for n in names:
        p = os.path.join(dirpath, n)
        if ".tmp." in n:
            fail(f"temporary file left behind: {p}")
        if n.endswith(".csv"):
            data = open(p, newline="").read()
            if not data.endswith("\n"):
                fail(f"{p}: does not end with a line end (truncated)")
            rows = list(csv.reader(data.splitlines()))
            if not rows or not rows[0] or (n in first_column and rows[0][0] != first_column[n]):
                fail(f"{p}: no header: {rows[:1]}")
            width = len(rows[0])
            for i, r in enumerate(rows[1:], 2):
                if len(r) != width:
                    fail(f"{p}:{i}: {len(r)} fields, the header has {width}")
            if n == "summary.csv" and os.path.basename(os.path.dirname(dirpath)) == "runs":
                st = [dict(zip(rows[0], r))["status"] for r in rows[1:]]
                if not st:
                    fail(f"{p}: a run summary without rows")
                ok_runs += all(s == "ok" for s in st)
        elif n == "meta.yaml":
            try:
                m = yaml.safe_load(open(p))
            except yaml.YAMLError as e:
                fail(f"{p}: not YAML: {e}")
            if not isinstance(m, dict):
                fail(f"{p}: not a mapping")
print(ok_runs)
PY
}

# --- (a) The disk fills mid-sweep ---------------------------------------------
# Each run writes about 45 KB (frames.csv and passes.csv of 400 frames): a 300 KB
# file system fills after five or six of the ten runs.
cat > fill.yaml <<'YAML'
shadesweep: 1
name: fill
scene: empty
renderers: [null]
duration: {frames: 400}
clock: fixed
outputs: {frames: true, seconds: true}
sweep:
  resolution: [8x8, 9x9, 10x10, 11x11, 12x12, 13x13, 14x14, 15x15, 16x16, 17x17]
YAML
if mount_tmpfs small size=300k; then
  set +e
  "$SHADESWEEP" run -o small/out fill.yaml >fill.out 2>fill.err; rc=$?
  set -e
  [ $rc -ne 0 ] || fail "a sweep into a full disk exited 0: $(cat fill.err)"
  grep -q "small/out/[^ ]*: .*No space left on device" fill.err \
    || fail "no message naming the file and 'No space left on device': $(cat fill.err)"
  ok_runs=$(check_outputs small/out) || fail "outputs after the disk filled"
  # the runs finished before the disk filled keep their summaries, and the disk
  # filled during the sweep (not before it, not never)
  [ "$ok_runs" -ge 1 ] && [ "$ok_runs" -lt 10 ] \
    || fail "$ok_runs of 10 runs complete and ok: $(cat fill.err)"
  [ -f small/out/plan.csv ] || fail "plan.csv missing"
  umount small && unset 'mounts[-1]'
else
  echo "reliability: cannot mount a tmpfs here: full-disk part skipped" >&2
fi

# --- (b) An output parent that cannot be written ------------------------------
cat > tiny.yaml <<'YAML'
shadesweep: 1
name: tiny
scene: empty
renderers: [null]
duration: {frames: 3}
clock: fixed
YAML
tiny_id=$("$SHADESWEEP" list tiny.yaml | cut -d' ' -f1)
[ ${#tiny_id} -eq 12 ] || fail "list: no run id: $tiny_id"
# expect_refused OUT WHAT: exit 2, a message naming OUT (or the part of it in the
# way) and WHAT, and no run started (progress and run messages name the run id)
expect_refused() {
  set +e
  "$SHADESWEEP" run -o "$1" tiny.yaml >ro.out 2>ro.err; local rc=$?
  set -e
  [ $rc -eq 2 ] || fail "-o $1: exit $rc, want 2: $(cat ro.err)"
  grep -q -- "${1%/out}[/a-z]*: .*$2" ro.err || fail "-o $1: no message naming it and '$2': $(cat ro.err)"
  ! grep -q "$tiny_id" ro.err ro.out || fail "-o $1: a run started: $(cat ro.err)"
}
# A file where the parent folder should be.
echo "not a folder" > afile
expect_refused afile/out "Not a directory"
[ "$(cat afile)" = "not a folder" ] || fail "the file in the way was changed"
# An immutable folder (chattr +i holds even for root).
mkdir frozen
if chattr +i frozen 2>/dev/null; then
  immutable+=("$T/frozen")
  expect_refused frozen/out "Operation not permitted"
  [ -z "$(ls -A frozen)" ] || fail "something was created in the immutable folder"
  chattr -i frozen && unset 'immutable[-1]'
else
  echo "reliability: chattr +i not supported here: immutable-folder part skipped" >&2
fi
# A read-only file system.
if mount_tmpfs rofs ro,size=64k; then
  expect_refused rofs/out "Read-only file system"
  umount rofs && unset 'mounts[-1]'
else
  echo "reliability: cannot mount a tmpfs here: read-only part skipped" >&2
fi

# --- (c) The manifest is deleted while the sweep runs -------------------------
cat > gone.yaml <<'YAML'
shadesweep: 1
name: gone
scene: empty
renderers: [null]
duration: {frames: 5000}
clock: fixed
outputs: {frames: true, seconds: true}
sweep:
  resolution: [8x8, 9x9, 10x10, 11x11, 12x12, 13x13]
YAML
"$SHADESWEEP" run -o gone gone.yaml >gone.out 2>gone.err &
pid=$!
# the manifest has been read once plan.csv exists; delete it then
for _ in $(seq 1 400); do [ -f gone/plan.csv ] && break; sleep 0.025; done
[ -f gone/plan.csv ] || { kill $pid 2>/dev/null; fail "the sweep did not start: $(cat gone.err)"; }
rm gone.yaml
# summary.csv is written last: the sweep was still running when the manifest went
[ ! -f gone/summary.csv ] || fail "the sweep ended before its manifest was deleted"
set +e
wait $pid; rc=$?
set -e
[ $rc -eq 0 ] || fail "sweep whose manifest was deleted exited $rc: $(cat gone.err)"
check_outputs gone >ok_runs.txt || fail "outputs of the sweep whose manifest was deleted"
[ "$(cat ok_runs.txt)" -eq 6 ] || fail "$(cat ok_runs.txt) of 6 runs complete"
"$PYTHON" - <<'PY'
import csv, sys
rows = list(csv.DictReader(open("gone/summary.csv")))
plan = [r["run_id"] for r in csv.DictReader(open("gone/plan.csv"))]
if [r["run_id"] for r in rows] != plan or any(r["status"] != "ok" for r in rows):
    print("FAIL: summary after the manifest was deleted:", [(r["run_id"], r["status"]) for r in rows],
          file=sys.stderr); sys.exit(1)
PY
echo ok
