#!/usr/bin/env bash
# `validate` against the GL that run would use (issue 42, item 4): on llvmpipe (819
# lights in a 65536-byte uniform block) forward-spml with 16384 uniform lights is an
# error naming the run, the value and the limit (msaa 8 past its 4 samples too); the
# same with forward.light_buffer: storage is valid; the quick-start validates with
# nothing on stderr; --no-gl keeps the warning against the 204 lights every GL has; no
# context (--device 99): --gl refuses, the default says what it could not check and why.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
printf 'shadesweep: 1\nname: big\nscene: shapes\nrenderers: [forward-spml]\nresolution: 16x16\nduration: {frames: 2}\nclock: fixed\nlights: {count: 16384}\n' >big.yaml
id=$("$SHADESWEEP" list big.yaml 2>/dev/null | awk 'NR == 1 { print $1 }')
[ ${#id} -eq 12 ] || fail "list big.yaml: no run id: $("$SHADESWEEP" list big.yaml 2>&1)"
cap=$("$SHADESWEEP" info | sed -n 's/^forward_spml_max_lights: //p')
[ "$cap" -lt 16384 ] || { echo "SKIP: this GL holds $cap lights, not fewer than 16384" >&2; exit 77; }
msg="big.yaml: forward.light_buffer: expected at most $cap lights in forward-spml's uniform block on this GL ("
tail="found 16384 in run $id; set forward.light_buffer: storage or fewer lights"
expect 2 "$msg" "$SHADESWEEP" validate --gl big.yaml
grep -qF "$tail" "$T/cmd.err" || fail "validate --gl big.yaml: $(cat "$T/cmd.err")"
[ ! -s "$T/cmd.out" ] || fail "validate --gl big.yaml said ok: $(cat "$T/cmd.out")"
# the storage buffer has no such limit: by --set or in the manifest (beside big.yaml:
# exit 2, the valid one ok)
"$SHADESWEEP" validate --gl --set forward.light_buffer=storage big.yaml >out.txt 2>err.txt ||
  fail "storage: $(cat err.txt)"
[ "$(cat out.txt)" = "big.yaml: ok, 1 run" ] && [ ! -s err.txt ] || fail "storage: $(cat out.txt err.txt)"
printf 'shadesweep: 1\nname: big\nscene: shapes\nrenderers: [forward-spml]\nresolution: 16x16\nduration: {frames: 2}\nclock: fixed\nlights: {count: 16384}\nforward: {light_buffer: storage}\n' >ssbo.yaml
expect 2 "$tail" "$SHADESWEEP" validate --gl ssbo.yaml big.yaml
[ "$(cat "$T/cmd.out")" = "ssbo.yaml: ok, 1 run" ] || fail "ssbo.yaml beside big.yaml: $(cat "$T/cmd.out")"
# samples past the context's (llvmpipe: 4) likewise
samples=$("$SHADESWEEP" info | sed -n 's/^max_samples: //p')
if [ "$samples" -lt 8 ]; then
  expect 2 "big.yaml: msaa: expected at most $samples samples a pixel on this GL (" \
    "$SHADESWEEP" validate --gl --set forward.light_buffer=storage --set msaa=8 big.yaml
  grep -qF "found 8 in run " "$T/cmd.err" || fail "msaa 8: $(cat "$T/cmd.err")"
fi
# the default: the same refusal when the context came within 1 s, else the note and
# the warning (a loaded machine): either is exact
set +e; "$SHADESWEEP" validate big.yaml >out.txt 2>err.txt; rc=$?; set -e
if grep -qF "big.yaml: note: not checked against this GL (no GL context: no answer within 1 s)" err.txt; then
  [ $rc -eq 0 ] && grep -qF "big.yaml: warning: forward.light_buffer: 1 run ($id)" err.txt ||
    fail "default, no context in time: exit $rc: $(cat err.txt)"
else
  [ $rc -eq 2 ] && grep -qF "$msg" err.txt && [ "$(wc -l <err.txt)" -eq 1 ] ||
    fail "default: exit $rc, want 2: $(cat err.txt)"
fi
# --no-gl: today's warning against what every GL has, exit 0
"$SHADESWEEP" validate --no-gl big.yaml >out.txt 2>err.txt || fail "--no-gl: $(cat err.txt)"
[ "$(cat out.txt)" = "big.yaml: ok, 1 run" ] || fail "--no-gl: $(cat out.txt)"
grep -qxF "big.yaml: warning: forward.light_buffer: 1 run ($id) asks for up to 16384 lights in forward-spml's uniform block, past the 204 lights of the 16384 bytes every GL has; it fails where the GL has less (\`shadesweep info\`: forward_spml_max_lights; llvmpipe: 819); or set forward.light_buffer: storage" err.txt ||
  fail "--no-gl: $(cat err.txt)"
# the quick-start (scripts/run.sh): 590 lights fit llvmpipe's block: nothing on stderr
for mode in --gl ""; do
  "$SHADESWEEP" validate $mode "$SOURCE_ROOT/experiments/quickstart.yaml" >out.txt 2>err.txt ||
    fail "quickstart $mode: $(cat err.txt)"
  grep -qF "not checked against this GL (no GL context: no answer within 1 s)" err.txt && continue
  [ ! -s err.txt ] || fail "validate $mode quickstart.yaml: stderr: $(cat err.txt)"
  grep -qF "quickstart.yaml: ok, 3 runs" out.txt || fail "quickstart $mode: $(cat out.txt)"
done
# no context: --gl refuses before any manifest; the default says why and warns
expect 2 "shadesweep validate: --gl: --device 99: " "$SHADESWEEP" validate --gl --device 99 big.yaml
[ ! -s "$T/cmd.out" ] || fail "--gl --device 99: $(cat "$T/cmd.out")"
expect 0 "big.yaml: note: not checked against this GL (--device 99: " "$SHADESWEEP" validate --device 99 big.yaml
grep -qF "big.yaml: warning: forward.light_buffer: 1 run ($id)" "$T/cmd.err" ||
  fail "--device 99: no warning: $(cat "$T/cmd.err")"
# --gl and --no-gl are validate's: run and list refuse them
expect 2 "shadesweep run: --gl: unknown option here" "$SHADESWEEP" run --gl big.yaml
expect 2 "shadesweep list: --no-gl: unknown option here" "$SHADESWEEP" list --no-gl big.yaml
echo "ok"
