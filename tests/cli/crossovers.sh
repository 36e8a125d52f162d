#!/usr/bin/env bash
# A manifest of one's own, named like no paper experiment, asks "which renderer, and
# where do they change places?": the run names the crossover along lights.count last on
# the terminal, in summary.md and in summary.json, with its interval. The crossing is
# made certain by debug.busy_us: 20 ms of CPU in every forward-spml frame makes it the
# slower at 1 light (deferred's frames: ~1.5 ms at 64x64, ~5 ms in the sanitizer build)
# and still the faster at 512 lights, where deferred's light volumes cost ~60 ms (~400
# ms in the sanitizer build) against forward-spml's ~15 (a 2x margin or more either side).
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat >mine.yaml <<'YAML'
shadesweep: 1
name: my-question
description: forward or deferred, and from how many lights
scene: shapes
renderers: [forward-spml, deferred]
resolution: 64x64
trials: 3
warmup: {frames: 2}
duration: {frames: 6}
clock: fixed
outputs: {frames: false, seconds: false}
debug: {busy_us: 20000, busy_renderer: forward-spml}
sweep:
  lights.count: [1, 512]
YAML
"$SHADESWEEP" run -o out mine.yaml >run.out 2>run.err || fail "run: $(cat run.err)"
tail -n 1 run.out | grep -qE "^crossover: deferred is the fastest below lights.count ~[0-9.]+ \((95%: [0-9.?]+ to [0-9.?]+|no interval: .*)\), forward-spml above$" ||
  fail "the run does not end with the crossover: $(tail -n 3 run.out)"
grep -qE "^\| lights.count \| - \| deferred \| forward-spml \| 1-512 \| ~[0-9.]+ \|" out/summary.md ||
  fail "summary.md: $(sed -n '/## Crossovers/,$p' out/summary.md)"
"$PYTHON" - out/summary.json <<'PY' || fail "summary.json: $(cat out/summary.json)"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["experiment"] == "my-question"
(c,) = d["crossovers"]
assert (c["along"], c["where"], c["faster_below"], c["faster_above"]) == \
    ("lights.count", "", "deferred", "forward-spml"), c
assert (c["between_lo"], c["between_hi"]) == (1, 512) and 1 < c["x"] < 512, c
assert (c["x_lo"] is None or c["x_lo"] <= c["x"]) and (c["x_hi"] is None or c["x"] <= c["x_hi"]), c
PY
# the same sweep with the busy loop on deferred: no crossing, and the run says so
sed 's/busy_renderer: forward-spml/busy_renderer: deferred/' mine.yaml >none.yaml
"$SHADESWEEP" run -o none none.yaml >none.out 2>none.err || fail "run none: $(cat none.err)"
tail -n 1 none.out | grep -qx "crossovers: none: along the numeric parameters the sweep varies, the fastest configuration does not change" ||
  fail "no-crossing run: $(tail -n 3 none.out)"
