#!/usr/bin/env bash
# scripts/slurm/sweep.sbatch on a real one-node Slurm cluster started here on localhost
# (private munged socket, private ports, everything under $T): a job array of 3 shards,
# then the documented dependent merge job; the merged folder must match one machine's run.
# Installs slurm-wlm and munge when missing (root, apt); skips (77) when it cannot, or when
# the daemons cannot run here. Every wait is bounded, and the daemons, the jobs and anything
# they started are stopped on every exit.
. "$(dirname "$0")/lib.sh"
need_gl

SBATCH_SCRIPT="$SOURCE_ROOT/scripts/slurm/sweep.sbatch"
SHARDS=3
PIDS=()           # daemons started here, stopped in reverse order
JOBS=()           # jobs submitted here, cancelled on exit

skip() { echo "SKIP: $*" >&2; exit 77; }
now() { date +%s; }
logs() {
  local f
  for f in "$T"/log/*; do
    [ -f "$f" ] || continue
    echo "--- $f" >&2; tail -n 25 "$f" >&2
  done
}
# Slurm and munge client commands, never allowed to hang.
sc() { timeout 20 "$@"; }

stop_pid() {
  local pid=$1 i
  kill -0 "$pid" 2>/dev/null || { wait "$pid" 2>/dev/null || true; return 0; }
  kill -TERM "$pid" 2>/dev/null || true
  for i in $(seq 1 50); do
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  kill -KILL "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
}
cleanup() {
  local rc=$? i p
  trap - EXIT INT TERM
  set +e
  if [ -n "${SLURM_CONF:-}" ] && [ ${#JOBS[@]} -gt 0 ]; then
    sc scancel "${JOBS[@]}" >/dev/null 2>&1
  fi
  for ((i = ${#PIDS[@]} - 1; i >= 0; i--)); do stop_pid "${PIDS[i]}"; done
  # Whatever the cluster started (slurmstepd, job scripts) carries our SLURM_CONF.
  if [ -n "${SLURM_CONF:-}" ]; then
    for p in /proc/[0-9]*; do
      p=${p#/proc/}
      [ "$p" = $$ ] && continue
      grep -qzxF "SLURM_CONF=$SLURM_CONF" "/proc/$p/environ" 2>/dev/null && kill -KILL "$p" 2>/dev/null
    done
  fi
  rm -rf "$T"
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 143' INT TERM

# --- Slurm and munge: installed, or installable here ---------------------------------------
need=(sbatch squeue scontrol sinfo scancel slurmctld slurmd munged munge)
missing() { local c; for c in "${need[@]}"; do command -v "$c" >/dev/null 2>&1 || echo "$c"; done; }
PATH=$PATH:/usr/sbin:/sbin
if [ -n "$(missing)" ]; then
  [ "$(id -u)" -eq 0 ] || skip "slurm-wlm and munge are not installed and this is not root (missing: $(missing | tr '\n' ' '))"
  command -v apt-get >/dev/null || skip "slurm-wlm and munge are not installed and there is no apt-get"
  echo "installing slurm-wlm and munge (apt-get)" >&2
  apt_install() {
    DEBIAN_FRONTEND=noninteractive timeout 240 apt-get install -y -q \
      -o DPkg::Lock::Timeout=120 slurm-wlm munge >"$T/apt.log" 2>&1
  }
  if ! apt_install; then
    DEBIAN_FRONTEND=noninteractive timeout 90 apt-get update -q >>"$T/apt.log" 2>&1
    apt_install || skip "apt-get install slurm-wlm munge failed: $(tail -n 3 "$T/apt.log")"
  fi
  [ -z "$(missing)" ] || skip "still missing after installing: $(missing | tr '\n' ' ')"
fi
[ "$(id -u)" -eq 0 ] || skip "a private slurmd must run as root (SlurmdUser=root)"

# --- munged on a private socket with a throwaway key ---------------------------------------
# munged wants execute permission for all on the socket's folders.
chmod 711 "$T"
mkdir -m 755 "$T/munge"
mkdir -m 700 "$T/log" "$T/state" "$T/spool"
head -c 1024 /dev/urandom >"$T/munge.key"
chmod 400 "$T/munge.key"
SOCK=$T/munge/munge.sock
munged --foreground --socket="$SOCK" --key-file="$T/munge.key" --pid-file="$T/munged.pid" \
  --log-file="$T/log/munged.log" --seed-file="$T/munged.seed" >"$T/log/munged.out" 2>&1 &
PIDS+=($!)
deadline=$(($(now) + 15))
until sc munge -S "$SOCK" -n 2>/dev/null | sc unmunge -S "$SOCK" >/dev/null 2>&1; do
  kill -0 "${PIDS[0]}" 2>/dev/null || { logs; skip "munged cannot run here"; }
  [ "$(now)" -lt "$deadline" ] || { logs; skip "munged did not answer within 15 s"; }
  sleep 0.2
done

# --- slurm.conf: one node, this machine, private ports and folders -------------------------
read -r PORT_CTLD PORT_D < <("$PYTHON" -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("", 0))
print(*[x.getsockname()[1] for x in s])')
CPUS=$(nproc)
MEM_MB=$(awk '/^MemTotal:/ { m = int($2 / 1024 / 2); print (m > 0 ? m : 1) }' /proc/meminfo)
export SLURM_CONF=$T/slurm.conf
cat >"$SLURM_CONF" <<EOF
ClusterName=shadesweeptest
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$PORT_CTLD
SlurmdPort=$PORT_D
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$SOCK
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
ReturnToService=2
MinJobAge=600
MailProg=/bin/true
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$CPUS RealMemory=$MEM_MB State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF

slurmctld -D -i -f "$SLURM_CONF" >"$T/log/slurmctld.out" 2>&1 &
PIDS+=($!)
deadline=$(($(now) + 30))
until sc scontrol ping 2>/dev/null | grep -q 'is UP'; do
  kill -0 "${PIDS[1]}" 2>/dev/null || { logs; skip "slurmctld cannot run here"; }
  [ "$(now)" -lt "$deadline" ] || { logs; skip "slurmctld did not answer within 30 s"; }
  sleep 0.2
done
slurmd -D -N localhost -f "$SLURM_CONF" >"$T/log/slurmd.out" 2>&1 &
PIDS+=($!)
deadline=$(($(now) + 30))
until [ "$(sc sinfo -h -n localhost -o %T 2>/dev/null)" = idle ]; do
  kill -0 "${PIDS[2]}" 2>/dev/null || { logs; skip "slurmd cannot run here"; }
  if [ "$(now)" -ge "$deadline" ]; then
    sc scontrol show node localhost >&2
    logs; skip "the node did not become idle within 30 s"
  fi
  sleep 0.2
done

# --- the sweep: a job array of shards, then the documented dependent merge -----------------
cd "$T" || fail "cd $T"
cat >m.yaml <<'EOF'
shadesweep: 1
name: slurm-array
scene: empty
renderers: [null]
trials: 2
warmup: {frames: 2}
duration: {frames: 10}
clock: fixed
step: 0.1
outputs: {frames: true, seconds: true}
sweep:
  resolution: [32x32, 48x32, 64x32]
  sync: [finish, fence]
EOF
# The jobs inherit this environment (sbatch --export=ALL): SHADESWEEP, SHADESWEEP_GL_DEBUG.
export SHADESWEEP
SB=(--cpus-per-task=1 --parsable)
ARRAY=$(sc sbatch "${SB[@]}" --array=1-$SHARDS --output="$T/log/%A_%a.out" \
  "$SBATCH_SCRIPT" m.yaml out) || { logs; fail "sbatch of the array"; }
ARRAY=${ARRAY%%;*}
JOBS+=("$ARRAY")
MERGE=$(sc sbatch "${SB[@]}" --dependency=afterok:"$ARRAY" --output="$T/log/merge-%j.out" \
  "$SBATCH_SCRIPT" --merge out) || { logs; fail "sbatch of the merge job"; }
MERGE=${MERGE%%;*}
JOBS+=("$MERGE")

# Prints one "ArrayTaskId JobState ExitCode" line per job record; fails when the job is
# unknown to slurmctld.
job_states() {
  sc scontrol -o show job "$1" |
    awk '{ t = "-"; s = ""; e = "";
           for (i = 1; i <= NF; i++) {
             split($i, kv, "=")
             if (kv[1] == "ArrayTaskId") t = kv[2]
             if (kv[1] == "JobState") s = kv[2]
             if (kv[1] == "ExitCode") e = substr($i, 10)
           }
           print t, s, e }'
}
# Waits (bounded) until no record of the job is pending or running; leaves the records in
# $ST. Runs in this shell, so that a SIGTERM is handled within a second.
wait_job() {
  local id=$1 what=$2 deadline=$(($(now) + $3))
  while :; do
    ST=$(job_states "$id") || { logs; fail "$what: scontrol show job $id failed"; }
    if ! grep -Eq ' (PENDING|RUNNING|CONFIGURING|COMPLETING|SUSPENDED|REQUEUED|REQUEUE_HOLD|REQUEUE_FED|RESIZING|SIGNALING|STAGE_OUT)( |$)' <<<"$ST"; then
      return 0
    fi
    if [ "$(now)" -ge "$deadline" ]; then
      echo "$ST" >&2; sc squeue -a -j "$id" >&2; logs; fail "$what: not done within $3 s"
    fi
    sleep 0.3
  done
}
wait_job "$ARRAY" "the array job" 240
[ "$(grep -c ' COMPLETED 0:0$' <<<"$ST")" -eq $SHARDS ] ||
  { echo "$ST" >&2; logs; fail "the array job: want $SHARDS tasks COMPLETED with exit 0"; }
wait_job "$MERGE" "the merge job" 120
[ "$ST" = "- COMPLETED 0:0" ] || { echo "$ST" >&2; logs; fail "the merge job did not complete"; }
grep -q "merged 6 of 6 runs from $SHARDS folders into out/merged" "$T/log/merge-$MERGE.out" ||
  { logs; fail "the merge job's report"; }
for i in $(seq 1 $SHARDS); do
  grep -q "shard $i/$SHARDS of m.yaml into out/shard-$i" "$T/log/${ARRAY}_$i.out" ||
    { logs; fail "task $i did not run shard $i/$SHARDS"; }
done

# A requeued task (node failure, preemption) resumes its shard: the runs it finished stay.
before=$(cd out/shard-2 && find runs -type f -exec md5sum {} + | sort)
sc scontrol requeue "${ARRAY}_2" || { logs; fail "scontrol requeue ${ARRAY}_2"; }
# A requeued job waits the credential lifetime (120 s) before it may start: not here.
sc scontrol update JobId="${ARRAY}_2" StartTime=now || { logs; fail "scontrol update StartTime"; }
wait_job "${ARRAY}_2" "the requeued task" 120
[ "$ST" = "2 COMPLETED 0:0" ] || { echo "$ST" >&2; logs; fail "the requeued task did not complete"; }
grep -q -- "--resume" "$T/log/${ARRAY}_2.out" || { logs; fail "the requeued task did not resume"; }
[ "$(cd out/shard-2 && find runs -type f -exec md5sum {} + | sort)" = "$before" ] ||
  fail "the requeued task did not keep its shard's finished runs"

# --- the same manifest on one machine, and the comparison ----------------------------------
"$SHADESWEEP" run -o single m.yaml >single.log 2>&1 || { cat single.log >&2; fail "single-machine run"; }
"$PYTHON" - "$SHARDS" <<'PY'
import csv, filecmp, io, os, sys
shards = int(sys.argv[1])
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
def read(p): return open(p, "rb").read()
def rows(p): return list(csv.DictReader(io.StringIO(read(p).decode())))

# plan.csv: the shards' own (byte for byte), which is the single run's but for the shard
# column, the array task that ran each run: (index mod N) + 1.
mp, sp = read("out/merged/plan.csv"), read("single/plan.csv")
if mp != read("out/shard-1/plan.csv"): fail("merged plan.csv is not the shards' plan.csv")
def cols(t): return [l.split(b",") for l in t.splitlines()]
mc, sc = cols(mp), cols(sp)
if len(mc) != len(sc) or mc[0] != sc[0] or mc[0][:3] != [b"index", b"run_id", b"shard"]:
    fail(f"plan.csv header or length: {mc[0]} / {sc[0]}")
for a, b in zip(mc[1:], sc[1:]):
    if a[:2] + a[3:] != b[:2] + b[3:]:
        fail(f"merged plan row {a} differs from the single run's {b} beyond the shard")
    if int(a[2]) != int(a[0]) % shards + 1: fail(f"merged plan row {a}: shard")
plan = rows("single/plan.csv")
ids = [p["run_id"] for p in plan]
if len(ids) != 6 or len(set(ids)) != 6: fail(f"plan: want 6 distinct runs, got {ids}")

# Each array task ran its own shard, and together they ran every run once.
seen = []
for k in range(1, shards + 1):
    d = f"out/shard-{k}"
    sp = rows(f"{d}/plan.csv")
    if [p["run_id"] for p in sp] != ids: fail(f"{d}/plan.csv lists other runs")
    want = [p["run_id"] for i, p in enumerate(sp) if i % shards == k - 1]
    if [p["run_id"] for p in sp if p["shard"] == str(k)] != want: fail(f"{d}: shard column")
    got = sorted(os.listdir(f"{d}/runs"))
    if got != sorted(want): fail(f"{d} ran {got}, want {sorted(want)}")
    seen += got
if sorted(seen) != sorted(ids): fail("the shards did not cover the plan exactly once")

# The merged runs are the shards' runs, copied whole.
if sorted(os.listdir("out/merged/runs")) != sorted(ids): fail("merged runs/ folders")
for k in range(1, shards + 1):
    for rid in os.listdir(f"out/shard-{k}/runs"):
        a, b = f"out/shard-{k}/runs/{rid}", f"out/merged/runs/{rid}"
        c = filecmp.dircmp(a, b)
        if c.left_only or c.right_only or c.diff_files or c.funny_files:
            fail(f"merged runs/{rid} is not a copy of {a}: {c.left_only} {c.right_only} {c.diff_files}")
        _, mismatch, errors = filecmp.cmpfiles(a, b, c.common_files, shallow=False)
        if mismatch or errors: fail(f"merged runs/{rid}: {mismatch} {errors} differ")

# summary.csv: same header, same rows in the same order; only the timings may differ.
ms, ss = read("out/merged/summary.csv"), read("single/summary.csv")
if ms.split(b"\n", 1)[0] != ss.split(b"\n", 1)[0]: fail("summary.csv headers differ")
m, s = rows("out/merged/summary.csv"), rows("single/summary.csv")
if len(s) != 2 * len(ids): fail(f"single summary: want {2 * len(ids)} rows, got {len(s)}")
if len(m) != len(s): fail(f"merged summary has {len(m)} rows, single {len(s)}")
same = ["experiment", "run_id", "renderer", "scene", "width", "height", "lights_count",
        "trial", "frames", "draw_calls_mean", "state_changes_mean", "status"]
for i, (a, b) in enumerate(zip(m, s)):
    for c in same:
        if a[c] != b[c]: fail(f"summary row {i + 1}: {c} = {a[c]!r}, single machine {b[c]!r}")
    if a["status"] != "ok": fail(f"summary row {i + 1}: status {a['status']}")
    if a["frames"] != "10": fail(f"summary row {i + 1}: frames {a['frames']}")
if [r["run_id"] for r in m][::2] != ids: fail("merged summary is not in plan order")
PY
echo ok
