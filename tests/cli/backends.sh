#!/usr/bin/env bash
# `info` on each backend, EGL device selection errors, and an OSMesa run with the
# same columns as the EGL run.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
for key in backend vendor renderer version glsl max_draw_buffers max_samples \
           max_uniform_block_size timer_query pipeline_statistics_query; do
  grep -q "^$key: " info.txt || fail "info lacks '$key': $(cat info.txt)"
done
grep -q "^backend: egl-surfaceless" info.txt || fail "default backend"
# --json: the same keys and values, typed, the renderer and scene lists as arrays
"$SHADESWEEP" info >info-text.txt 2>/dev/null && "$SHADESWEEP" info --json >info.json 2>/dev/null ||
  fail "info --json"
"$PYTHON" - info-text.txt info.json <<'PY' || fail "info --json: $(cat info.json)"
import json, sys
text = dict(l.rstrip("\n").split(": ", 1) for l in open(sys.argv[1]) if ": " in l)
d = json.load(open(sys.argv[2]))
assert set(d) == set(text), (set(d) ^ set(text))
assert d["max_uniform_block_size"] == int(text["max_uniform_block_size"]) >= 16384
assert d["forward_spml_max_lights"] == d["max_uniform_block_size"] // 80
assert d["glsl"] == text["glsl"] and d["renderer"] == text["renderer"]
assert d["timer_query"] is (text["timer_query"] == "yes")
assert d["renderers"] == text["renderers"].split() and "deferred" in d["renderers"]
PY
set +e
"$SHADESWEEP" info --device 99 >out.txt 2>err.txt; rc=$?
set -e
[ $rc -eq 2 ] && grep -q "EGL device 99" err.txt || fail "device 99: rc $rc: $(cat err.txt)"

if ! "$SHADESWEEP" info --backend osmesa >osmesa.txt 2>&1; then
  if grep -q "built without OSMesa" osmesa.txt; then echo "SKIP: no OSMesa" >&2; exit 77; fi
  fail "info --backend osmesa: $(cat osmesa.txt)"
fi
grep -q "^backend: osmesa" osmesa.txt || fail "osmesa info: $(cat osmesa.txt)"

"$SHADESWEEP" run -o egl "$SOURCE_ROOT/experiments/smoke.yaml" 2>egl.err || fail "egl run: $(cat egl.err)"
"$SHADESWEEP" run --backend osmesa -o osm "$SOURCE_ROOT/experiments/smoke.yaml" 2>osm.err \
  || fail "osmesa run: $(cat osm.err)"
for f in summary.csv plan.csv; do
  [ "$(head -1 egl/$f)" = "$(head -1 osm/$f)" ] || fail "$f columns differ between backends"
done
cmp -s egl/plan.csv osm/plan.csv || fail "plan differs between backends"
id=$(sed -n 2p egl/plan.csv | cut -d, -f2)
for f in frames.csv seconds.csv passes.csv; do
  [ "$(head -1 egl/runs/$id/$f)" = "$(head -1 osm/runs/$id/$f)" ] || fail "$f columns differ"
done
[ "$(wc -l <osm/summary.csv)" -eq 33 ] || fail "osmesa summary rows"
grep -q "backend: osmesa" osm/runs/$id/meta.yaml || fail "meta.yaml backend"
! grep -v ',ok,$' osm/summary.csv | tail -n +2 | grep -q . || fail "osmesa runs failed: $(cat osm/summary.csv)"
echo ok
