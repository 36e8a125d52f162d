#!/usr/bin/env bash
# Runs the papers' reproduction manifests (and the G-buffer study) into one folder and
# writes the report over them:
#   scripts/reproduce.sh [--scale S] [--smoke] [--only NAME...] OUTDIR
# --scale S multiplies every resolution (0.25 turns 1280x720 into 320x180: what llvmpipe
# on a small machine finishes in reasonable time); --smoke runs the smoke variants.
# A folder that exists is resumed (complete runs are kept), so a killed reproduction
# goes on where it stopped. Ends with OUTDIR/report.md.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
all=(s003-exp1 s003-exp2 s000-resolution s000-drawcalls s000-spot-coverage s000-two-spots
     s000-stencil s000-illumination-sets gbuffer-error)
opts=() only=() out=""
while [ $# -gt 0 ]; do
  case $1 in
    --scale) opts+=(--scale "$2"); shift 2 ;;
    --smoke) opts+=(--smoke); shift ;;
    --only) shift; while [ $# -gt 1 ] && [[ $1 != --* ]]; do only+=("$1"); shift; done ;;
    -*) echo "reproduce: unknown option $1" >&2; exit 2 ;;
    *) out=$1; shift ;;
  esac
done
[ -n "$out" ] || { echo "usage: scripts/reproduce.sh [--scale S] [--smoke] [--only NAME...] OUTDIR" >&2; exit 2; }
[ ${#only[@]} -gt 0 ] || only=("${all[@]}")
"$root/scripts/build.sh" "$root/build"
exe="$root/build/runner/shadesweep"
mkdir -p "$out"
status=0
for m in "${only[@]}"; do
  [ -f "$root/experiments/$m.yaml" ] || { echo "reproduce: no experiments/$m.yaml" >&2; exit 2; }
  resume=()
  [ -f "$out/$m/sweep.yaml" ] && resume=(--resume)
  echo "== $m" >&2
  "$exe" run "${opts[@]}" "${resume[@]}" --out "$out/$m" "$root/experiments/$m.yaml" || status=1
done
"$root/scripts/report" "$out"
exit $status
