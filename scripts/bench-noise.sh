#!/usr/bin/env bash
# Do shadesweep's verdicts hold on a shared machine? On experiments/noise-aa.yaml (six
# renderers, one sweep point, 5 interleaved rounds), under a background load this script
# starts and stops itself (busy loops that come and go, bounded in time):
#   A/A     compare --exe SELF: the same build as BASE and NEW, paired rounds: every
#           slower/faster verdict is a false alarm (the folders also compared unpaired)
#   A/B     NEW's forward-plus slowed by +25% of its CPU time a frame (debug.busy_us): it
#           must be flagged slower, the other five not
#   repeat  the manifest run 4 times: the winner each names where it says it differs
#   cost    the interleaved schedule's wall time against the sequential one's, and
#           against OLD_SHADESWEEP (a build that ran a run's trials in one process)
# Prints one line per finding and a table for the README. Not part of CI (about 15
# minutes on a 2-core machine).
#   scripts/bench-noise.sh [OUT]        (default out/bench-noise)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
scripts/setup.sh >/dev/null
scripts/build.sh build >/dev/null
export LIBGL_ALWAYS_SOFTWARE=1 MESA_DEBUG=silent
exe=$root/build/runner/shadesweep
out=${1:-out/bench-noise}
manifest=$root/experiments/noise-aa.yaml
rm -rf "$out"
mkdir -p "$out"
out=$(cd "$out" && pwd)

# ---- the background load: one or two busy loops on, then off, at random, until stopped
load_pid=
load_stop() {
  [ -n "$load_pid" ] && kill "$load_pid" 2>/dev/null && wait "$load_pid" 2>/dev/null
  load_pid=
}
trap load_stop EXIT
load_start() {
  (
    trap 'kill $(jobs -p) 2>/dev/null; exit 0' TERM
    end=$((SECONDS + 3600))   # bounded: never outlives an hour
    while [ $SECONDS -lt $end ]; do
      n=$((RANDOM % 2 + 1)); on=$((RANDOM % 6 + 3)); off=$((RANDOM % 6 + 3))
      pids=()
      for _ in $(seq $n); do (while :; do :; done) & pids+=($!); done
      sleep $on
      kill "${pids[@]}" 2>/dev/null; wait "${pids[@]}" 2>/dev/null
      sleep $off
    done
  ) &
  load_pid=$!
}

verdicts() {   # verdicts CSV: "slower faster same undecided none" counts
  python3 - "$1" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
c = {k: 0 for k in ("slower", "faster", "same", "undecided", "no verdict")}
for r in rows: c[r["verdict"]] += 1
print(" ".join(str(c[k]) for k in c))
PY
}

echo "machine: $(nproc) CPUs, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "renderer: $("$exe" info | sed -n 's/^renderer: //p')"
load_start

# ---- A/A
t0=$SECONDS
"$exe" compare --exe "$exe" -o "$out/aa" --csv "$out/aa.csv" "$manifest" >"$out/aa.md" 2>"$out/aa.err" || true
aa_s=$((SECONDS - t0))
read -r s f same u n <<<"$(verdicts "$out/aa.csv")"
echo "A/A paired (compare --exe): $((s + f)) of 6 flagged (slower $s, faster $f, same $same, undecided $u, no verdict $n) at 5%"
"$exe" compare --csv "$out/aa-unpaired.csv" "$out/aa/base" "$out/aa/new" >/dev/null 2>&1 || true
read -r s f same u n <<<"$(verdicts "$out/aa-unpaired.csv")"
echo "A/A unpaired (two folders): $((s + f)) of 6 flagged (slower $s, faster $f, same $same, undecided $u, no verdict $n)"

# ---- A/B: +25% of forward-plus's CPU time per frame, measured in the A/A run
fp_us=$(python3 - "$out/aa/base/summary.csv" <<'PY'
import csv, sys
v = [float(r["metric_us"]) for r in csv.DictReader(open(sys.argv[1]))
     if r["renderer"] == "forward-plus" and r["metric_us"]]
print(int(round(0.25 * sorted(v)[len(v) // 2])))
PY
)
{ cat "$manifest"; echo "debug: {busy_us: $fp_us, busy_renderer: forward-plus}"; } >"$out/noise-ab.yaml"
"$exe" compare --exe "$exe" --base-manifest "$manifest" -o "$out/ab" --csv "$out/ab.csv" \
  "$out/noise-ab.yaml" >"$out/ab.md" 2>"$out/ab.err" || true
fp_verdict=$(awk -F, '$2 == "forward-plus" {print $13}' "$out/ab.csv")
fp_ratio=$(awk -F, '$2 == "forward-plus" {printf "%.3f (%.3f-%.3f)", $8, $9, $10}' "$out/ab.csv")
others=$(awk -F, 'NR > 1 && $2 != "forward-plus" && ($13 == "slower" || $13 == "faster")' "$out/ab.csv" | wc -l)
echo "A/B: forward-plus +$fp_us us of CPU a frame (+25%): $fp_verdict, NEW/BASE $fp_ratio; the other 5: $others flagged"

# ---- four repeats: the winner where it differs
for i in 1 2 3 4; do
  "$exe" run -o "$out/rep$i" "$manifest" >"$out/rep$i.out" 2>"$out/rep$i.err" || true
  python3 - "$out/rep$i/summary.md" "$i" <<'PY'
import re, sys
rows = [l.split("|")[1:-1] for l in open(sys.argv[1]) if re.match(r"^\| [0-9]+ \|", l)]
rows = [[c.strip() for c in r] for r in rows]
first = next(r for r in rows if r[0] == "1")
second = next(r for r in rows if r[0] == "2")
print(f"repeat {sys.argv[2]}: winner {first[1]}, the second ({second[1]}) {second[4]}, differs: {second[5]}")
PY
done

# ---- the cost of interleaving: the same frames, sequential schedule (load stopped: a
# time is what is compared here)
load_stop
sed 's/^trials: 5$/trials: 5\nschedule: sequential/' "$manifest" >"$out/noise-seq.yaml"
t0=$SECONDS
"$exe" run -o "$out/seq" "$out/noise-seq.yaml" >/dev/null 2>&1 || true
seq_s=$((SECONDS - t0))
t0=$SECONDS
"$exe" run -o "$out/int" "$manifest" >/dev/null 2>&1 || true
int_s=$((SECONDS - t0))
measured=$(python3 - "$out/int/summary.csv" <<'PY'
import csv, sys
print(round(sum(float(r["measured_s"] or 0) for r in csv.DictReader(open(sys.argv[1]))), 1))
PY
)
echo "cost: interleaved ${int_s} s, sequential ${seq_s} s (both a process per trial); measured frames ${measured} s of the interleaved sweep"
if [ -n "${OLD_SHADESWEEP:-}" ]; then
  t0=$SECONDS
  "$OLD_SHADESWEEP" run -o "$out/old" "$manifest" >/dev/null 2>&1 || true
  old_s=$((SECONDS - t0))
  echo "cost: one process per run ($OLD_SHADESWEEP): ${old_s} s; interleaved / that: $(python3 -c "print(round($int_s / max($old_s, 1), 2))")x"
fi
echo "A/A compare --exe took ${aa_s} s"
