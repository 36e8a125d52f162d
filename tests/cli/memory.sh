#!/usr/bin/env bash
# Memory (README "Reliability", runner/plan/memory.h):
#  A. a run whose estimate exceeds what the process may use (here MemAvailable +
#     SwapFree, or the memory cgroup: 32768x32768 at 4x MSAA in RGBA32F with a reference
#     at 4 times the width and height needs about 3 TiB) is refused before any child
#     starts, as failed:memory with both numbers; the tiny run of the same sweep is ok;
#     meta.yaml has memory: {estimate_mb, peak_rss_mb}.
#  B. under `ulimit -v` (RLIMIT_AS) 16384x16384 at 4x MSAA is refused naming RLIMIT_AS.
#  C. with the check off, a run that really exhausts RLIMIT_AS (4096x4096 deferred in
#     950 MB) fails with a message that names memory and the numbers, not a bare signal.
# B and C set RLIMIT_AS, which AddressSanitizer cannot start under (it reserves
# terabytes of shadow address space): they are skipped in the sanitizer build (found by
# ASan's __asan_init in the executable). llvmpipe's thread count and glibc's malloc
# arenas (what a run maps besides its memory) are pinned so that the limits mean the
# same on any machine.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
export LP_NUM_THREADS=2 MALLOC_ARENA_MAX=2

# --- A. refused before rendering -----------------------------------------------------
cat > huge.yaml <<'YAML'
shadesweep: 1
name: huge
scene: shapes
renderers: [deferred]
duration: {frames: 2}
clock: fixed
msaa: 4
hdr: rgba32f
gbuffer: reference
error:
  reference: {renderer: deferred, supersample: 4}
  at: [0]
sweep:
  resolution: [32768x32768, 16x16]
YAML
set +e
"$SHADESWEEP" run huge.yaml >out.txt 2>err.txt; rc=$?
set -e
[ $rc -eq 1 ] || fail "A: a sweep with a refused run exits 1, got $rc: $(cat err.txt)"
"$PYTHON" - <<'PY'
import csv, os, re, sys, yaml
def fail(m): print("FAIL: A:", m, file=sys.stderr); sys.exit(1)
rows = list(csv.DictReader(open("out/huge/summary.csv")))
got = [(r["width"], r["status"]) for r in rows]
if got != [("32768", "failed:memory"), ("16", "ok")]: fail(f"statuses {got}")
m = rows[0]["message"]
want = (r"^needs about [0-9.]+ (GiB|TiB) \(targets [0-9.]+ (GiB|TiB) at 32768x32768 x 4x MSAA and "
        r"the reference's at 131072x131072, light lists 0 B, scene [0-9.]+ [KM]iB, read-back [0-9.]+ (GiB|TiB); 1\.25 times that \+ 128 MiB "
        r"for the driver\), the process may use [0-9.]+ [KMGT]?i?B \((/proc/meminfo "
        r"MemAvailable \+ SwapFree|the memory cgroup's .*)\)$")
if not re.match(want, m): fail(f"message {m!r}")
huge = rows[0]["run_id"]
# no child started: the child is what opens the run's log
if os.path.exists(f"out/huge/runs/{huge}/log.txt"): fail("a child ran the refused run")
meta = yaml.safe_load(open(f"out/huge/runs/{huge}/meta.yaml"))
if meta["status"] != "failed:memory" or meta["memory"]["peak_rss_mb"] != -1:
    fail(f"refused run's meta {meta['status']} {meta['memory']}")
if meta["memory"]["estimate_mb"] < 100000: fail(f"estimate {meta['memory']}")
tiny = yaml.safe_load(open(f"out/huge/runs/{rows[1]['run_id']}/meta.yaml"))["memory"]
if not (tiny["estimate_mb"] > 0 and tiny["peak_rss_mb"] > 0): fail(f"tiny run's memory {tiny}")
PY
grep -q "trial 1: needs about" err.txt || fail "A: the refusal is not on stderr: $(cat err.txt)"

if grep -qa __asan_init "$SHADESWEEP"; then
  echo "memory: sanitizer build: the RLIMIT_AS parts (B, C) are skipped" >&2
  echo ok
  exit 0
fi

# --- B. RLIMIT_AS: refused with both numbers ----------------------------------------
cat > as.yaml <<'YAML'
shadesweep: 1
name: as
scene: shapes
renderers: [deferred]
duration: {frames: 2}
clock: fixed
msaa: 4
sweep:
  resolution: [16384x16384, 16x16]
YAML
set +e
(ulimit -v $((1200 * 1024)); exec "$SHADESWEEP" run as.yaml) >out.txt 2>err.txt; rc=$?
set -e
[ $rc -eq 1 ] || fail "B: exit $rc: $(cat err.txt)"
"$PYTHON" - <<'PY'
import csv, re, sys
def fail(m): print("FAIL: B:", m, file=sys.stderr); sys.exit(1)
rows = list(csv.DictReader(open("out/as/summary.csv")))
got = [(r["width"], r["status"]) for r in rows]
if got != [("16384", "failed:memory"), ("16", "ok")]: fail(f"statuses {got}")
want = (r"^needs about [0-9.]+ GiB of address space \(targets [0-9.]+ GiB at 16384x16384 x 4x "
        r"MSAA, .*; 2\.5 times that \+ 192 MiB for the driver\), the process may map "
        r"[0-9.]+ [KMG]iB more \(RLIMIT_AS 1\.2 GiB, [0-9.]+ MiB mapped already\)$")
if not re.match(want, rows[0]["message"]): fail(f"message {rows[0]['message']!r}")
PY

# --- C. a run that really runs out says so -------------------------------------------
sed 's/^name: as$/name: out/; s/^msaa: 4$/msaa: 1/; s/16384x16384/4096x4096/' as.yaml > out.yaml
set +e
(ulimit -v $((950 * 1024)); SHADESWEEP_MEMORY_CHECK=off exec "$SHADESWEEP" run out.yaml) \
  >out.txt 2>err.txt; rc=$?
set -e
[ $rc -eq 1 ] || fail "C: exit $rc: $(cat err.txt)"
"$PYTHON" - <<'PY'
import csv, re, sys
def fail(m): print("FAIL: C:", m, file=sys.stderr); sys.exit(1)
rows = list(csv.DictReader(open("out/out/summary.csv")))
if rows[1]["status"] != "ok" or rows[0]["status"] in ("ok", "failed:memory"):
    fail(f"statuses {[(r['width'], r['status']) for r in rows]}")
want = (r"^memory is the likely cause: peak address space [0-9.]+ MiB of RLIMIT_AS 950 MiB, "
        r"peak resident [0-9.]+ MiB; ")
if not re.match(want, rows[0]["message"]):
    fail(f"{rows[0]['status']}: message {rows[0]['message']!r}")
PY
echo ok
