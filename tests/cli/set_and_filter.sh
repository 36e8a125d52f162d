#!/usr/bin/env bash
# --set KEY=VALUE and --renderer LIST (runner/manifest/overrides.c): the plan of a manifest with
# them is the plan of the manifest with the same written into it (same runs, same ids,
# same order), a bad value gets the manifest's own message and exit 2, and a run records
# them in meta.yaml and resumes only with the same ones.
. "$(dirname "$0")/lib.sh"
cd "$T"
cat >m.yaml <<'YAML'
shadesweep: 1
name: sf
scene: shapes
renderers: [null, deferred, forward-mpml]
resolution: 16x16
duration: {frames: 2}
clock: fixed
gbuffer: fat
lights: {count: 4, radius: 1}
sweep:
  lights.seed: [1, 2]
  sync: [finish, fence]
YAML
"$SHADESWEEP" list m.yaml >base.txt
# same FILE ARGS...: `list ARGS m.yaml` and `list FILE` agree (ids, order, lines), and
# differ from the manifest's plan
same() {
  local file=$1; shift
  "$SHADESWEEP" list "$@" m.yaml >a.txt 2>a.err || fail "list $*: $(cat a.err)"
  "$SHADESWEEP" list "$file" >b.txt 2>b.err || fail "list $file: $(cat b.err)"
  [ -s a.txt ] && cmp -s a.txt b.txt || fail "list $* != $file: $(diff a.txt b.txt)"
  cmp -s a.txt base.txt && fail "list $*: the manifest's own plan"
  return 0
}
# keys set in place, replaced (in order: the last resolution wins); a member of a group
# set by its shorthand; and every parameter of every run the same (--json)
sed -e 's/count: 4/count: 8/' -e 's/^resolution: 16x16$/resolution: 32x16/' \
    -e 's/^gbuffer: fat$/gbuffer: {preset: fat, normal: float32}/' m.yaml >w1.yaml
args=(--set lights.count=8 --set gbuffer.normal=float32 --set resolution=8x8 --set resolution=32x16)
same w1.yaml "${args[@]}"
"$SHADESWEEP" list --json "${args[@]}" m.yaml | cmp -s - <("$SHADESWEEP" list --json w1.yaml) \
  || fail "list --json ${args[*]} != w1.yaml"
# a swept key set: that one value, the axis gone
sed -e 's/count: 4,/count: 4, seed: 7,/' -e '/lights.seed:/d' m.yaml >w2.yaml
same w2.yaml --set lights.seed=7
# an axis replaced where it stands, and a key set in place made an axis (the last)
sed -e 's/lights.seed: \[1, 2\]/lights.seed: [3]/' -e 's/count: 4, //' m.yaml >w3.yaml
echo "  lights.count: [2, 8]" >>w3.yaml
same w3.yaml --set 'sweep.lights.seed=[3]' --set 'sweep.lights.count=[2, 8]'
# the whole sweep replaced: its keys removed in place
sed -e 's/count: 4, //' -e '/^  /d' m.yaml >w4.yaml
echo "  lights.count: [2, 8]" >>w4.yaml
same w4.yaml --set 'sweep={lights.count: [2, 8]}'
# the renderer filter: the manifest's renderers it names, in the manifest's order (and an
# axis made and then set back in place: the manifest's plan)
sed 's/^renderers: .*/renderers: [null, forward-mpml]/' m.yaml >w5.yaml
same w5.yaml --renderer forward-mpml,null --set 'sweep.lights.count=[2,8]' --set lights.count=4

# refused: exit 2, one line on stderr, nothing on stdout (and `run` writes nothing)
refuse() {
  local msg=$1; shift
  set +e
  "$@" >r.out 2>r.err; local rc=$?
  set -e
  [ $rc -eq 2 ] && [ ! -s r.out ] && [ "$(wc -l <r.err)" -eq 1 ] || fail "$*: exit $rc: $(cat r.out r.err)"
  grep -qF -- "$msg" r.err || fail "$*: no '$msg' in: $(cat r.err)"
}
# a bad value: the manifest's message, located at the --set instead of a line
sed 's/count: 4/count: abc/' m.yaml >bad.yaml
refuse "lights.count: expected" "$SHADESWEEP" validate bad.yaml
want=$(sed 's/^bad\.yaml:[0-9]*:[0-9]*: //' r.err)
refuse "m.yaml: --set lights.count=abc: $want" "$SHADESWEEP" list --set lights.count=abc m.yaml
refuse "m.yaml: --set lights.count=abc: $want" "$SHADESWEEP" run -o out --set lights.count=abc m.yaml
[ ! -e out ] || fail "run with a bad --set made its folder"
# in a sweep too
sed 's/sync: \[finish, fence\]/sync: [finish, fast]/' m.yaml >bad2.yaml
refuse "sweep.sync[1]: expected" "$SHADESWEEP" validate bad2.yaml
want=$(sed 's/^bad2\.yaml:[0-9]*:[0-9]*: //' r.err)
refuse "m.yaml: --set sweep.sync=[finish, fast]: $want" \
  "$SHADESWEEP" list --set 'sweep.sync=[finish, fast]' m.yaml
# an unknown key, no '=', a value that is not YAML, an unknown or absent renderer
refuse "m.yaml: --set lights.colour=1: lights.colour: expected one of culling, culling_error, placement, seed," \
  "$SHADESWEEP" validate --set lights.colour=1 m.yaml
refuse "shadesweep: --set: expected KEY=VALUE" "$SHADESWEEP" list --set lights.count m.yaml
refuse "m.yaml: --set lights.count=[1,: expected valid YAML" "$SHADESWEEP" list --set 'lights.count=[1,' m.yaml
refuse "shadesweep: --renderer: expected renderer names separated by commas (each one of null," \
  "$SHADESWEEP" list --renderer deferred,tiled m.yaml
refuse "m.yaml: --renderer forward-plus: renderers: expected one or more of the manifest's renderers (null, deferred, forward-mpml), found none of them" \
  "$SHADESWEEP" validate --renderer forward-plus m.yaml
refuse "shadesweep info: --set: unknown option here" "$SHADESWEEP" info --set lights.count=1

# a run: meta.yaml records every --set and the filter verbatim, in order; its ids are
# list's; --resume takes the same ones only
need_gl
set -- --set lights.count=2 --set 'sweep.sync=[finish]' --renderer null
"$SHADESWEEP" run -o out "$@" m.yaml >/dev/null 2>run.err || fail "run: $(cat run.err)"
"$SHADESWEEP" list "$@" m.yaml | cut -d' ' -f1 >ids.txt
"$PYTHON" - out ids.txt <<'PY' || fail "meta.yaml"
import csv, os, sys, yaml
out, ids = sys.argv[1], open(sys.argv[2]).read().split()
plan = [r["run_id"] for r in csv.DictReader(open(os.path.join(out, "plan.csv")))]
assert plan == ids and len(ids) == 2, (plan, ids)
for i in ids:
    m = yaml.safe_load(open(os.path.join(out, "runs", i, "meta.yaml")))["manifest"]
    assert m["set"] == ["lights.count=2", "sweep.sync=[finish]"], m["set"]
    assert m["renderer_filter"] == "null", m["renderer_filter"]
    assert "count: 4" in m["text"]   # the manifest itself, verbatim
PY
snapshot() { find out -type f ! -name lock -printf '%p %s %T@\n' | sort; }
snapshot >before.txt
refuse "not the same sweep" "$SHADESWEEP" run --resume -o out --set lights.count=3 \
  --set 'sweep.sync=[finish]' --renderer null m.yaml
refuse "not the same sweep" "$SHADESWEEP" run --resume -o out --set lights.count=2 \
  --set 'sweep.sync=[finish]' --renderer null,deferred m.yaml
snapshot | cmp -s - before.txt || fail "a refused --resume changed the folder"
"$SHADESWEEP" run --resume -o out "$@" m.yaml >/dev/null 2>again.err || fail "resume: $(cat again.err)"
grep -qx "resuming: 2 of 2 runs already complete" again.err || fail "resume: $(cat again.err)"
echo ok
