#!/usr/bin/env bash
# A CI job's performance gate (issue 41, item 4): runs MANIFEST's smoke variant (`run
# --smoke`) into a new folder, adds it to the results history (`history add`), and gates
# on `history check` over the whole history: exit 1 when a change point is a
# regression, 2 on an error (a failed run also fails the gate, after its folder is added).
#   scripts/ci-gate.sh [--db URL] [--out DIR] MANIFEST [CHECK OPTIONS...]
#     --db URL    the history: a SQLite file or postgresql://... (default:
#                 $SHADESWEEP_HISTORY, else DIR/history.sqlite)
#     --out DIR   where each gate's folder goes (default out/ci-gate)
#     CHECK OPTIONS  passed to `history check` (--min-change 5%, --max-pvalue 0.001,
#                 --metric M, ...); its JSON goes beside the folder, FOLDER.check.json
# SHADESWEEP names the program (default: build/runner/shadesweep, built if missing).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
db=${SHADESWEEP_HISTORY:-}
out=out/ci-gate
while [ $# -gt 0 ]; do
  case $1 in
    --db) db=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    -h|--help) sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) break ;;
  esac
done
[ $# -ge 1 ] || { echo "usage: scripts/ci-gate.sh [--db URL] [--out DIR] MANIFEST [CHECK OPTIONS...]" >&2; exit 2; }
manifest=$1; shift
exe=${SHADESWEEP:-}
if [ -z "$exe" ]; then
  "$root/scripts/build.sh" "$root/build"
  exe=$root/build/runner/shadesweep
fi
[ -n "$db" ] || db=$out/history.sqlite
mkdir -p "$out"
# one folder per gate: the time and the process, so two jobs at once do not collide
folder=$out/$(date -u +%Y%m%dT%H%M%SZ)-$$
run_rc=0
"$exe" run --smoke -o "$folder" "$manifest" || run_rc=$?
[ "$run_rc" -le 1 ] || { echo "ci-gate: run failed (exit $run_rc)" >&2; exit 2; }
"$exe" history add --db "$db" "$folder" || { echo "ci-gate: history add failed" >&2; exit 2; }
check_rc=0
"$exe" history check --db "$db" --json "$folder.check.json" "$@" || check_rc=$?
if [ "$check_rc" -ge 2 ]; then
  echo "ci-gate: history check failed (exit $check_rc)" >&2; exit 2
fi
[ "$run_rc" -eq 0 ] || { echo "ci-gate: some run failed or is partial: $folder/summary.csv" >&2; exit 1; }
[ "$check_rc" -eq 0 ] || echo "ci-gate: a regression in the history: $folder.check.json" >&2
exit "$check_rc"
