#!/usr/bin/env bash
# scripts/build.sh (and run.sh, setup.sh, test.sh through scripts/say.sh) say what they
# do on a terminal, ninja's progress included; not in a log, nor with CI=true. ninja
# here is a stand-in that prints one progress line (or fails), so nothing is built.
. "$(dirname "$0")/lib.sh"
cd "$T"
if ! command -v script >/dev/null; then echo "SKIP: no script(1)" >&2; exit 77; fi
mkdir -p bin b
touch b/build.ninja
printf '#!/bin/sh\necho "[1/1] Linking target stand-in"\n[ -z "$NINJA_FAILS" ] || { echo "error: stand-in"; exit 1; }\n' > bin/ninja
chmod +x bin/ninja
build="$SOURCE_ROOT/scripts/build.sh"
export PATH="$T/bin:$PATH"
# not a terminal: silent
env -u CI "$build" "$T/b" >log.out 2>log.err || fail "build.sh: $(cat log.err)"
[ ! -s log.out ] && [ ! -s log.err ] || fail "build.sh talks to a log: $(cat log.out log.err)"
# a terminal: what it does, and ninja's line
env -u CI script -qec "'$build' '$T/b'" /dev/null >tty.out 2>&1 || fail "build.sh on a tty: $(cat tty.out)"
grep -q "^build: building $T/b (ninja" tty.out && grep -q '\[1/1\] Linking target stand-in' tty.out \
  || fail "build.sh on a terminal: $(cat -v tty.out)"
# CI=true on a terminal: silent again
CI=true script -qec "'$build' '$T/b'" /dev/null >ci.out 2>&1 || fail "build.sh CI: $(cat ci.out)"
[ ! -s ci.out ] || fail "build.sh with CI=true: $(cat -v ci.out)"
# a failure in a log: the log, then what failed
rc=0; NINJA_FAILS=1 env -u CI "$build" "$T/b" >/dev/null 2>fail.err || rc=$?
[ $rc -eq 1 ] && grep -q "error: stand-in" fail.err && grep -q "build: ninja -C $T/b failed" fail.err \
  || fail "a failed build: rc $rc: $(cat fail.err)"
echo ok
