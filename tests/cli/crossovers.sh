#!/usr/bin/env bash
# A manifest of one's own, named like no paper experiment, asks "which renderer, and
# where do they change places?": the run names the crossover along lights.count last on
# the terminal, in summary.md and in summary.json, with its interval. The crossing is
# made certain by debug.busy_us: 10 ms of CPU in every forward-spml frame makes it the
# slower at 1 light and still the faster at 512 lights, where deferred's light volumes
# cost more. Measured CPU a frame, ratios of the slower: plain 6.4x at 1 light, 2.5x at
# 512; sanitizer build 3.0x and 3.1x. With 20 ms the 512 side had ~1.7x (plain, from
# the frame costs) and 2.6x (sanitizer, measured), and a
# loaded sanitizer run once saw its interval hold 1 (0.98-2.65): no crossing with
# evidence, a failure of this test, not of the code.
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
debug: {busy_us: 10000, busy_renderer: forward-spml}
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
# a verdict per sweep point, by the metric that ranks, just before the crossover: on the
# terminal and under each point's table in summary.md
verdict_re='fastest deferred, then forward-spml at [0-9.]+x \([0-9.]+-[0-9.]+\)'
tail -n 3 run.out | head -n 2 | grep -qE "^verdict: lights.count=1: $verdict_re$" ||
  fail "no verdict at 1 light: $(tail -n 3 run.out)"
tail -n 2 run.out | head -n 1 | grep -qE "^verdict: lights.count=512: fastest forward-spml, then deferred at [0-9.]+x \([0-9.]+-[0-9.]+\)$" ||
  fail "no verdict at 512 lights: $(tail -n 3 run.out)"
grep -qE "^Verdict: $verdict_re\.$" out/summary.md || fail "summary.md: no verdict: $(grep -n Verdict out/summary.md)"
[ "$(grep -c '^crossover' run.out)" -eq 1 ] || fail "the crossover is printed more than once"
# One trial a run: no interval, and never "nan" (the busy-machine warning's median, a
# ratio's bounds) on the terminal, in summary.md or in report.md. A key only
# forward-spml reads is swept too: deferred's line in the report's plot does not name it.
sed -e 's/^trials: 3/trials: 1/' -e 's/^  lights.count: \[1, 512\]/  lights.count: [1, 512]\n  forward.light_buffer: [uniform, storage]/' \
  mine.yaml >one.yaml
grep -q "forward.light_buffer" one.yaml || fail "one.yaml: $(cat one.yaml)"
"$SHADESWEEP" run -o one one.yaml >one.out 2>one.err || fail "run one: $(cat one.err)"
grep -qE "^verdict: lights.count=1: fastest deferred, then forward-spml (uniform|storage) at [0-9.]+x \(no interval: fewer than 3 trials\)$" one.out ||
  fail "one trial: $(grep verdict one.out)"
grep -iwq nan one.out one.err one/summary.md && fail "nan: $(grep -iw nan one.out one.err one/summary.md)"
if "$PYTHON" -c 'import matplotlib' 2>/dev/null; then
  SHADESWEEP_EXE="$SHADESWEEP" "$SHADESWEEP" report one >report.out 2>&1 || fail "report: $(cat report.out)"
  grep -iwq nan one/report.md && fail "report.md: $(grep -iw nan one/report.md)"
  grep -qE "^- lights.count=512: fastest forward-spml (uniform|storage), " one/report.md ||
    fail "report.md: no verdict: $(grep -n 'lights.count=' one/report.md)"
  PYTHONPATH="$SOURCE_ROOT/python" SHADESWEEP_EXE="$SHADESWEEP" "$PYTHON" - one <<'PY' ||
import os, sys
from shadesweep_report.loading import Experiment, read_csv
from shadesweep_report.sections.generic import growth_series, line_labels, metric_of
e = Experiment("my-question", ["my-question"])
f = sys.argv[1]
e.add_folder(f, read_csv(os.path.join(f, "summary.csv")), read_csv(os.path.join(f, "plan.csv")))
runs = e.measured()
got = sorted(set(line_labels(runs).values()))
assert got == ["deferred", "forward-spml forward.light_buffer=storage",
               "forward-spml forward.light_buffer=uniform"], got
assert {metric_of(r) for r in runs} == {"cpu"}, [metric_of(r) for r in runs]
assert all(growth_series(r, "cpu") == [] for r in runs)   # no frames.csv: a point a run
PY
    fail "the plot's lines"
  [ -s one/plots/my-question_frametime_lights.png ] || fail "no plot"
fi
