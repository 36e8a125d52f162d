#!/usr/bin/env bash
# Signals and crashes (issue 14, items 5 and 7):
#  A. SIGINT, SIGTERM and SIGHUP, to the sweep or to its whole process group, at
#     random moments (18 times): exit 128 + signal, the run in progress discarded
#     every time, never a failed:SIGINT row; the folder resumes to completion.
#  B. A run's process killed with SIGKILL from outside is failed:SIGKILL (not oom);
#     the exit status of --resume is the folder's (1 while a row is failed), and
#     --resume --retry-failed runs it again.
#  C. Crash consistency: a sweep killed with SIGKILL at random moments (15 times),
#     resumed after each, ends with exactly the plan's rows, every row parsing, no
#     duplicate, nothing outside its folder touched.
#  D. failed:oom when the kernel's OOM killer did it (a memory cgroup of 200 MB and
#     an 8192x8192 run), where this machine lets the test make a cgroup.
# Counts and sleeps are bounded: the whole script takes about a minute on 2 cores.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat > m.yaml <<'YAML'
shadesweep: 1
name: m
scene: empty
renderers: [null]
resolution: 16x16
duration: {seconds: 0.25}
sweep:
  lights.seed: [1, 2, 3, 4, 5]
YAML
cat > quick.yaml <<'YAML'
shadesweep: 1
name: quick
scene: empty
renderers: [null]
resolution: 32x32
trials: 2
duration: {frames: 20}
clock: fixed
sweep:
  lights.seed: [1, 2, 3, 4, 5, 6]
YAML

"$PYTHON" - "$SHADESWEEP" <<'PY'
import csv, io, os, random, shutil, signal, subprocess, sys, time
exe = sys.argv[1]
seed = int(os.environ.get("SIGNALS_SEED", time.time()))
rng = random.Random(seed)
def fail(m):
    print(f"FAIL: {m} (SIGNALS_SEED={seed})", file=sys.stderr); sys.exit(1)

def start(*args):
    err = open("err.txt", "w")
    return subprocess.Popen([exe, "run", *args], stdout=subprocess.DEVNULL, stderr=err,
                            start_new_session=True)

def finish(p, what):
    try:
        return p.wait(timeout=60)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL); fail(f"{what}: the sweep did not end")

def summary(d):
    """The folder's summary.csv, every row checked for its width; [] when absent."""
    path = f"{d}/summary.csv"
    if not os.path.exists(path): return []
    text = open(path, newline="").read()
    if not text.endswith("\n"): fail(f"{path}: cut off")
    rows = list(csv.reader(io.StringIO(text)))
    if any(len(r) != len(rows[0]) for r in rows): fail(f"{path}: a row of another width")
    rows = [dict(zip(rows[0], r)) for r in rows[1:]]
    keys = [(r["run_id"], r["trial"]) for r in rows]
    if len(set(keys)) != len(keys): fail(f"{path}: duplicated rows {keys}")
    return rows

def run_dirs(d):
    r = f"{d}/runs"
    return sorted(os.listdir(r)) if os.path.isdir(r) else []

def check_complete(d, trials):
    """Every run folder left is complete (files.txt) and its rows are in summary.csv."""
    rows = summary(d)
    dirs = []
    for i in run_dirs(d):
        if os.path.exists(f"{d}/runs/{i}/files.txt"):
            dirs.append(i)
            continue
        # a run cut off between its trials keeps its complete trials (resume goes on
        # from them): only its log and trial folders with their own files.txt
        left = sorted(os.listdir(f"{d}/runs/{i}"))
        trials_kept = [x for x in left if x.startswith("trial-")]
        if not trials_kept or any(x not in ("log.txt",) and not x.startswith("trial-") for x in left) \
                or any(not os.path.exists(f"{d}/runs/{i}/{x}/files.txt") for x in trials_kept):
            fail(f"{d}/runs/{i}: a run folder without files.txt was left (not discarded): {left}")
    ids = sorted({r["run_id"] for r in rows})
    if ids != dirs: fail(f"{d}: summary has runs {ids}, folder has {dirs}")
    if len(rows) != trials * len(dirs): fail(f"{d}: {len(rows)} rows for {len(dirs)} runs")
    return rows

def plan(d):
    return [r["run_id"] for r in csv.DictReader(open(f"{d}/plan.csv"))]

# --- A. stop signals ---------------------------------------------------------------
names = {signal.SIGINT: "SIGINT", signal.SIGTERM: "SIGTERM", signal.SIGHUP: "SIGHUP"}
sigs = [signal.SIGINT, signal.SIGTERM, signal.SIGHUP]
interrupted = 0
for i in range(18):
    sig = sigs[i % 3]
    group = (i // 3) % 2 == 1
    p = start("--resume", "-o", "sig", "m.yaml")
    # from the moment it holds the folder's lock (before that, the dynamic loader
    # is still mapping libraries: nothing of ours runs, and nothing is written)
    for _ in range(1000):
        try:
            if open("sig/lock").read().strip() == str(p.pid): break
        except OSError:
            pass
        if p.poll() is not None: break
        time.sleep(0.005)
    time.sleep(rng.uniform(0.0, 1.2))
    try:
        (os.killpg if group else os.kill)(p.pid, sig)
    except ProcessLookupError:
        pass
    rc = finish(p, f"signal {names[sig]}")
    err = open("err.txt").read()
    if rc == 0:   # it finished first: start again from nothing
        rows = check_complete("sig", 1)
        if len(rows) != 5 or any(r["status"] != "ok" for r in rows): fail(f"complete sweep: {rows}")
        shutil.rmtree("sig")
        continue
    if rc != 128 + sig:
        fail(f"{names[sig]} to the {'group' if group else 'sweep'}: exit {rc}: {err}")
    if "before the sweep began; nothing was written" in err:
        continue
    if f"interrupted by {names[sig]}" not in err or "shadesweep run --resume -o sig" not in err:
        fail(f"{names[sig]}: no resume line: {err}")
    rows = check_complete("sig", 1)
    bad = [(r["run_id"], r["status"]) for r in rows if r["status"] != "ok"]
    if bad: fail(f"{names[sig]} to the {'group' if group else 'sweep'} recorded {bad}")
    interrupted += 1
if interrupted < 9: fail(f"only {interrupted} of 18 signals landed while the sweep ran")
p = start("--resume", "-o", "sig", "m.yaml")
if finish(p, "final resume") != 0: fail(f"final resume: {open('err.txt').read()}")
rows = check_complete("sig", 1)
if [r["run_id"] for r in rows] != plan("sig") or any(r["status"] != "ok" for r in rows):
    fail(f"after the signals: {[(r['run_id'], r['status']) for r in rows]}")

# --- B. SIGKILL from outside; the exit status is the folder's; --retry-failed -------
def children(pid):
    try:
        return [int(c) for c in open(f"/proc/{pid}/task/{pid}/children").read().split()]
    except OSError:
        return []
p = start("-o", "k", "m.yaml")
victim = None
for _ in range(3000):   # 30 s at most (a sanitizer build starts runs slowly)
    kids = children(p.pid)
    if kids and len(run_dirs("k")) >= 2:   # the second run is under way
        victim = kids[0]
        break
    time.sleep(0.01)
if victim is None: fail("no run process to kill")
os.kill(victim, signal.SIGKILL)
rc = finish(p, "SIGKILL to a run")
err = open("err.txt").read()
rows = summary("k")
st = [r["status"] for r in rows]
if rc != 1 or st.count("failed:SIGKILL") != 1 or st.count("ok") != 4:
    fail(f"a run killed from outside: exit {rc}, statuses {st}: {err}")
killed = [r for r in rows if r["status"] == "failed:SIGKILL"][0]
if not killed["message"].startswith("SIGKILL after "): fail(f"message {killed['message']}")
# resume keeps the failed run and says so in its exit status
p = start("--resume", "-o", "k", "m.yaml")
rc = finish(p, "resume")
err = open("err.txt").read()
if rc != 1 or "resuming: 5 of 5 runs already complete" not in err:
    fail(f"--resume of a folder with a failed run: exit {rc}: {err}")
p = start("--resume", "--retry-failed", "-o", "k", "m.yaml")
rc = finish(p, "retry")
err = open("err.txt").read()
if rc != 0 or "retrying 1 failed run" not in err or err.count(" of 1 ") != 1:
    fail(f"--retry-failed: exit {rc}: {err}")
rows = summary("k")
if [r["run_id"] for r in rows] != plan("k") or any(r["status"] != "ok" for r in rows):
    fail(f"after --retry-failed: {[(r['run_id'], r['status']) for r in rows]}")

# --- C. crash consistency under SIGKILL ------------------------------------------
os.makedirs("bystander")
for n in ("a.txt", "plan.csv", "summary.csv", "x.tmp.1"):
    open(f"bystander/{n}", "w").write(n + "\n")
def outside():
    got = []
    for dp, dn, fn in os.walk("."):
        if dp == "./cc" or dp.startswith("./cc/"): continue
        if dp == ".": fn = [f for f in fn if f != "err.txt"]
        for f in fn:
            st = os.lstat(os.path.join(dp, f))
            got.append((os.path.join(dp, f), st.st_size, st.st_mtime_ns))
    return sorted(got)
snapshot = outside()
completed = 0
for i in range(15):
    p = start("--resume", "-o", "cc", "quick.yaml")
    time.sleep(rng.uniform(0.0, 1.2))
    try:
        (os.killpg if i % 2 else os.kill)(p.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    rc = finish(p, "SIGKILL")
    if outside() != snapshot: fail("a file outside the output folder changed")
    summary("cc")   # whatever is there parses
    if rc == 0:
        completed += 1
        rows = check_complete("cc", 2)
        if len(rows) != 12: fail(f"a complete sweep with {len(rows)} rows")
        shutil.rmtree("cc")
    elif rc != -signal.SIGKILL:
        fail(f"killed sweep: exit {rc}: {open('err.txt').read()}")
for _ in range(3):
    p = start("--resume", "-o", "cc", "quick.yaml")
    if finish(p, "resume after the kills") == 0: break
else:
    fail(f"resume after the kills: {open('err.txt').read()}")
rows = check_complete("cc", 2)
want = [(i, t) for i in plan("cc") for t in ("1", "2")]
if [(r["run_id"], r["trial"]) for r in rows] != want or any(r["status"] != "ok" for r in rows):
    fail(f"after the kills: {[(r['run_id'], r['trial'], r['status']) for r in rows]}")
for dp, dn, fn in os.walk("cc"):
    left = [f for f in fn if ".tmp." in f]
    if left: fail(f"temporary files left in {dp}: {left}")
if outside() != snapshot: fail("a file outside the output folder changed")
print(f"signals: {interrupted} interrupts, {15 - completed} kills mid-sweep", file=sys.stderr)
PY

# --- D. failed:oom only when the kernel says so -------------------------------------
cat > big.yaml <<'YAML'
shadesweep: 1
name: big
scene: empty
renderers: [null]
duration: {frames: 2}
clock: fixed
sweep:
  resolution: [8192x8192, 16x16]
YAML
cg=""
v1=$(sed -n 's/^[0-9]*:\([^:]*,\)\{0,1\}memory\(,[^:]*\)\{0,1\}:\(.*\)$/\3/p' /proc/self/cgroup)
if [ -n "$v1" ] && [ -w "/sys/fs/cgroup/memory${v1%/}" ]; then
  cg="/sys/fs/cgroup/memory${v1%/}/shadesweep-test-$$"
  mkdir "$cg" 2>/dev/null && echo $((200 << 20)) > "$cg/memory.limit_in_bytes" || cg=""
else
  v2=$(sed -n 's/^0::\(.*\)$/\1/p' /proc/self/cgroup)
  base="/sys/fs/cgroup${v2%/}"
  if [ -n "$v2" ] && [ -f "$base/memory.events" ] && grep -qw memory "$base/cgroup.subtree_control" 2>/dev/null; then
    cg="$base/shadesweep-test-$$"
    mkdir "$cg" 2>/dev/null && echo $((200 << 20)) > "$cg/memory.max" || cg=""
  fi
fi
if [ -n "$cg" ]; then
  trap 'rmdir "$cg" 2>/dev/null; rm -rf "$T"' EXIT
  set +e
  # the memory check off: the run must reach the kernel's OOM killer, not be refused
  (echo $BASHPID > "$cg/cgroup.procs" && SHADESWEEP_MEMORY_CHECK=off exec "$SHADESWEEP" run -o big big.yaml) >/dev/null 2>big.err; rc=$?
  set -e
  [ $rc -eq 1 ] || fail "the OOM sweep exited $rc: $(cat big.err)"
  "$PYTHON" - <<'PY'
import csv, sys
rows = list(csv.DictReader(open("big/summary.csv")))
st = [(r["width"], r["status"]) for r in rows]
if st != [("8192", "failed:oom"), ("16", "ok")]:
    print("FAIL: OOM statuses", st, file=sys.stderr); sys.exit(1)
if "OOM killer" not in rows[0]["message"]:
    print("FAIL: OOM message", rows[0]["message"], file=sys.stderr); sys.exit(1)
PY
else
  echo "signals: no memory cgroup can be made here: the OOM part is skipped" >&2
fi
echo ok
