#!/usr/bin/env bash
# Progress: redrawn in place on a terminal (a bar, run k of n, renderer, lights,
# FPS, elapsed, ETA), one plain line per run otherwise.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat > p.yaml <<'YAML'
shadesweep: 1
name: p
scene: empty
renderers: [null]
resolution: 16x16
duration: {seconds: 0.6}
lights: {count: 12}
sweep:
  lights.seed: [1, 2]
YAML
# not a terminal: plain lines, no escape sequences
"$SHADESWEEP" run -o plain p.yaml 2>plain.err || fail "plain run"
! grep -q $'\033' plain.err || fail "escape sequences in a log"
[ "$(grep -c '^run [12] of 2 [0-9a-f]\{12\} null 16x16: ok, [0-9.]* fps | elapsed [0-9]*s eta ' plain.err)" -eq 2 ] \
  || fail "plain progress lines: $(cat plain.err)"
# a terminal (script(1) gives the program a pty): redrawn lines with the bar
if ! command -v script >/dev/null; then echo "SKIP: no script(1)" >&2; exit 77; fi
script -qec "'$SHADESWEEP' run -o tty p.yaml" /dev/null >tty.out 2>&1 || fail "tty run: $(cat tty.out)"
grep -q $'\r\033\[K\[\.\{20\}\] run 1 of 2 [0-9a-f]\{12\} null 16x16 trial 1, 12 lights, [0-9.]* fps | elapsed' tty.out \
  || fail "no progress bar on a terminal: $(cat -v tty.out | head -c 600)"
grep -q $'\[##########\.\{10\}\] run 2 of 2' tty.out || fail "the bar does not fill"
echo ok
