#!/usr/bin/env bash
# One parameter definition (runner/manifest/params.def): docs/manifest.md and the bash
# completion are its output and must not be stale; `params`, `COMMAND --help`,
# options after the operands, `gbuffer` as a sweep axis, and the folded plan as
# `validate`, `list` and plan.csv report it.
. "$(dirname "$0")/lib.sh"
cd "$T"

"$SHADESWEEP" params --markdown >manifest.md
cmp -s manifest.md "$SOURCE_ROOT/docs/manifest.md" \
  || fail "docs/manifest.md is stale: run 'shadesweep params --markdown > docs/manifest.md'"
"$SHADESWEEP" params --bash >completion.bash
cmp -s completion.bash "$SOURCE_ROOT/scripts/completion/shadesweep.bash" \
  || fail "scripts/completion/shadesweep.bash is stale: run 'shadesweep params --bash > scripts/completion/shadesweep.bash'"
bash -n completion.bash || fail "the completion script does not parse"
# the completion offers the keys after `params` and the options of `run`
out=$(bash -c '. ./completion.bash; COMP_WORDS=(shadesweep params gbuffer.p); COMP_CWORD=2;
  _shadesweep; printf "%s\n" "${COMPREPLY[@]}"')
[ "$out" = "gbuffer.preset
gbuffer.position" ] || fail "completion of 'params gbuffer.p': $out"
out=$(bash -c '. ./completion.bash; COMP_WORDS=(shadesweep run --re); COMP_CWORD=2;
  _shadesweep; printf "%s\n" "${COMPREPLY[@]}"')
[ "$out" = "--resume
--retry-failed
--renderer" ] || fail "completion of 'run --re': $out"
# after --set, the keys (sweep.KEY too) with their '='
out=$(bash -c '. ./completion.bash; COMP_WORDS=(shadesweep list --set sweep.lights.co); COMP_CWORD=3;
  _shadesweep; printf "%s\n" "${COMPREPLY[@]}"')
[ "$out" = "sweep.lights.count=
sweep.lights.color_max=" ] || fail "completion of 'list --set sweep.lights.co': $out"

# every key in the text listing, with its default and readers
"$SHADESWEEP" params >params.txt
grep -q "^deferred.light_volumes  (enum, sweepable)$" params.txt || fail "params: $(head params.txt)"
grep -A4 "^deferred.light_volumes " params.txt | grep -q "read by:   deferred" \
  || fail "params: readers of deferred.light_volumes"
grep -A2 "^lights.seed " params.txt | grep -q "default:   1337" || fail "params: default of lights.seed"

# --json: every key of the text listing, typed
"$SHADESWEEP" params --json >params.json || fail "params --json"
"$PYTHON" - params.txt params.json <<'PY' || fail "params --json: $(head -c 400 params.json)"
import json, re, sys
keys = [m.group(1) for m in re.finditer(r"^(\S+)  \(", open(sys.argv[1]).read(), re.M)]
d = json.load(open(sys.argv[2]))
assert (d["schema"], d["version"]) == ("shadesweep-params", 1)
k = {x["key"]: x for x in d["keys"]}
assert [x["key"] for x in d["keys"]] == keys, set(keys) ^ set(k)
assert k["lights.seed"]["default"] == 1337 and k["lights.seed"]["sweep"] is True
assert k["deferred.light_volumes"]["read_by"] == ["deferred", "deferred-lighting"], k["deferred.light_volumes"]
assert k["shadesweep"]["required"] is True and k["shadesweep"]["default"] is None
PY
# every command has --help (stdout, exit 0), wherever it stands
for c in run validate list info merge params; do
  "$SHADESWEEP" "$c" --help >help.txt 2>err.txt || fail "$c --help: exit $?: $(cat err.txt)"
  grep -q "^usage: shadesweep $c" help.txt || fail "$c --help: $(cat help.txt)"
done
# the top-level help lists every command; the version answers to its three spellings
"$SHADESWEEP" --help >top.txt || fail "--help"
for c in run validate list info merge compare report ratios params columns version help; do
  grep -q "^  $c[ ,]" top.txt || fail "--help does not list $c"
done
v=$("$SHADESWEEP" --version) && [ "$("$SHADESWEEP" -V)" = "$v" ] && [ "$("$SHADESWEEP" version)" = "$v" ] &&
  echo "$v" | grep -q "^shadesweep [0-9]" || fail "version: '$v'"
"$SHADESWEEP" run some.yaml -o x --help >help.txt || fail "run ... --help"
grep -q -- "--resume" help.txt || fail "run --help lists --resume"

cat >fold.yaml <<'YAML'
shadesweep: 1
name: fold
scene: shapes
renderers: [deferred, forward-spml, forward-mpml]
duration: {frames: 2}
resolution: 32x32
sweep:
  deferred.light_volumes: [stencil, fullscreen, volume, stencil-two-pass]
  gbuffer: [curtis, fat]
YAML
"$SHADESWEEP" validate fold.yaml >v.txt || fail "validate fold.yaml"
grep -qx "fold.yaml: ok, 10 runs (14 of 24 grid points folded: they differ only in keys their renderer does not read)" v.txt \
  || fail "validate: $(cat v.txt)"
# deferred-lighting reads deferred_lighting.light_buffer and not deferred.separate_specular,
# deferred the other way round: each keeps two of the four points
cat >lpp.yaml <<'YAML'
shadesweep: 1
name: lpp
scene: shapes
renderers: [deferred, deferred-lighting]
duration: {frames: 2}
resolution: 32x32
sweep:
  deferred_lighting.light_buffer: [rgba16f, rgba8]
  deferred.separate_specular: [false, true]
YAML
"$SHADESWEEP" validate lpp.yaml >v.txt || fail "validate lpp.yaml"
grep -qx "lpp.yaml: ok, 4 runs (4 of 8 grid points folded: they differ only in keys their renderer does not read)" v.txt \
  || fail "validate lpp.yaml: $(cat v.txt)"
# options after the operand, as getopt_long permutes them
"$SHADESWEEP" list fold.yaml --shard 1/2 >l.txt || fail "list MANIFEST --shard"
# one sweep point (only keys some renderers read vary): a shard holds it whole
[ "$(grep -vc '^#' l.txt)" -eq 10 ] || fail "list --shard 1/2 after the manifest: $(cat l.txt)"
"$SHADESWEEP" list fold.yaml >l.txt
grep -q "^# 14 of 24 grid points folded" l.txt || fail "list names the folds: $(cat l.txt)"
[ "$(grep -c ' -> ' l.txt)" -eq 14 ] || fail "list: a line per fold"

# the folded plan on disk: 10 rows, the forward runs standing for 7 more points each
need_gl
"$SHADESWEEP" run fold.yaml -o out >run.txt 2>&1 || fail "run fold.yaml: $(tail run.txt)"
$PYTHON - out <<'PY'
import csv, sys
d = sys.argv[1]
plan = list(csv.DictReader(open(f"{d}/plan.csv")))
if len(plan) != 10: sys.exit(f"FAIL: plan.csv has {len(plan)} rows")
folded = {p["renderer"]: p["folded"] for p in plan if p["renderer"] != "deferred"}
if folded != {"forward-spml": "7", "forward-mpml": "7"}: sys.exit(f"FAIL: folded {folded}")
summ = list(csv.DictReader(open(f"{d}/summary.csv")))
if sorted(r["run_id"] for r in summ) != sorted(p["run_id"] for p in plan):
    sys.exit("FAIL: summary.csv rows are not the plan's distinct runs")
PY
