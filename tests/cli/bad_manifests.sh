#!/usr/bin/env bash
# A manifest with errors: non-zero exit, every error with line and column, nothing on disk.
. "$(dirname "$0")/lib.sh"
cd "$T"
cat > bad.yaml <<'YAML'
shadesweep: 1
name: bad-one
scene: nowhere
renderers: [null, warp-drive]
resolution: 0x0
trials: -2
duration: {seconds: .nan}
colour: red
YAML
set +e
"$SHADESWEEP" run bad.yaml >stdout.txt 2>stderr.txt; rc=$?
set -e
[ $rc -eq 2 ] || fail "run of a bad manifest exited $rc, want 2"
[ ! -e out ] || fail "an output folder was created for a bad manifest"
[ -z "$(ls -A . | grep -v -e bad.yaml -e stdout.txt -e stderr.txt)" ] || fail "files appeared: $(ls -A)"
# every problem is listed, each as FILE:LINE:COL: KEY: expected ..., found ...
for want in "bad.yaml:3:8: scene:" "bad.yaml:4:19: renderers" "bad.yaml:5:13: resolution:" \
            "bad.yaml:6:9: trials:" "bad.yaml:7:21: duration.seconds:" "bad.yaml:8:1: colour:"; do
  grep -qF "$want" stderr.txt || fail "missing '$want' in: $(cat stderr.txt)"
done
n=$(grep -c '^bad.yaml:[0-9]*:[0-9]*: .*expected .*, found ' stderr.txt)
[ "$n" -eq 6 ] || fail "want 6 error lines, got $n: $(cat stderr.txt)"

set +e
"$SHADESWEEP" validate bad.yaml "$SOURCE_ROOT/experiments/smoke.yaml" >stdout.txt 2>stderr.txt; rc=$?
set -e
[ $rc -eq 2 ] || fail "validate exited $rc"
grep -q "smoke.yaml: ok, 16 runs" stdout.txt || fail "validate of the good manifest: $(cat stdout.txt)"
[ "$(grep -c '^bad.yaml:' stderr.txt)" -eq 6 ] || fail "validate lists every error"

"$SHADESWEEP" validate --no-gl "$SOURCE_ROOT"/experiments/*.yaml >/dev/null || fail "experiments/ must validate"
# against the GL too, but for extremes.yaml, whose forward-spml runs past the uniform
# block are its expected failures: validate refuses them where they cannot run
if "$SHADESWEEP" info >/dev/null 2>&1; then
  ok=()
  for m in "$SOURCE_ROOT"/experiments/*.yaml; do [ "${m##*/}" = extremes.yaml ] || ok+=("$m"); done
  "$SHADESWEEP" validate --gl "${ok[@]}" >/dev/null || fail "experiments/ must validate on this GL"
  set +e; "$SHADESWEEP" validate --gl "$SOURCE_ROOT/experiments/extremes.yaml" >/dev/null 2>err.txt; rc=$?; set -e
  [ $rc -eq 2 ] && grep -qF "extremes.yaml: forward.light_buffer: expected at most " err.txt &&
    grep -qF "found up to 65536 in 4 runs (" err.txt || fail "extremes.yaml --gl: exit $rc: $(cat err.txt)"
fi
# so must the README's manifest example
"$PYTHON" - "$SOURCE_ROOT/README.md" > readme.yaml <<'PY'
import sys
s = open(sys.argv[1]).read()
a = s.index("```yaml\n") + 8
print(s[a:s.index("```", a)], end="")
PY
"$SHADESWEEP" validate readme.yaml >/dev/null || fail "the README's manifest example is invalid"
# usage errors are clear too
set +e
"$SHADESWEEP" run --shard 5/4 "$SOURCE_ROOT/experiments/smoke.yaml" 2>stderr.txt; rc=$?
set -e
[ $rc -eq 2 ] && grep -q "shard" stderr.txt || fail "bad --shard: rc $rc: $(cat stderr.txt)"
set +e
"$SHADESWEEP" frobnicate 2>stderr.txt; rc=$?
set -e
[ $rc -eq 2 ] && grep -q "unknown command 'frobnicate'" stderr.txt || fail "unknown command"
[ ! -e out ] || fail "output created"
echo ok
