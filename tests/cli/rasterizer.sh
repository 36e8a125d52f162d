#!/usr/bin/env bash
# measure.rasterizer: each trial's process sets llvmpipe's threads before its context, and
# meta.yaml records what it ran with (gl.lp_num_threads). auto with CPU time ranking and
# no LP_NUM_THREADS in the environment: "0" (the trial's thread rasterizes); auto with
# the environment's LP_NUM_THREADS: that value; threaded: llvmpipe's own (null); single:
# "0" whatever the environment; auto ranked by wall time: llvmpipe's own.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat > m.yaml <<'YAML'
shadesweep: 1
name: rasterizer
scene: shapes
renderers: [forward-plus]
resolution: 16x16
duration: {frames: 2}
clock: fixed
lights: {count: 2, radius: 4}
outputs: {frames: false, seconds: false}
YAML
threads() {  # threads FOLDER: gl.lp_num_threads of its one run
  "$PYTHON" -c "import glob, yaml; print(yaml.safe_load(open(glob.glob('$1/runs/*/meta.yaml')[0]))['gl']['lp_num_threads'])"
}
go() {  # go NAME WANT [env and --set ...]
  local name=$1 want=$2; shift 2
  local envs=() sets=()
  for a in "$@"; do case $a in *=*:env) envs+=("${a%:env}") ;; *) sets+=(--set "$a") ;; esac; done
  env -u LP_NUM_THREADS "${envs[@]}" "$SHADESWEEP" run -o "$name" "${sets[@]}" m.yaml >"$name.out" 2>"$name.err" ||
    fail "$name: $(tail -3 "$name.err")"
  got=$(threads "$name")
  [ "$got" = "$want" ] || fail "$name: lp_num_threads $got, want $want"
}
go auto 0
go auto-env 1 LP_NUM_THREADS=1:env
go threaded None measure.rasterizer=threaded
go single 0 measure.rasterizer=single LP_NUM_THREADS=2:env
go wall None measure.metric=wall
# not part of the run id: the same run in every folder
[ "$(ls auto/runs)" = "$(ls threaded/runs)" ] || fail "ids differ: $(ls auto/runs) $(ls threaded/runs)"
echo "rasterizer: ok"
