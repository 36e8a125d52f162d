#!/usr/bin/env bash
# `shadesweep report --cross-device` (issue 38, item 4) over the committed renderers-tiled
# folders of llvmpipe and the H200: it makes docs/results/cross-device.md again, byte for
# byte; the H200 folder, with no device.yaml, has its limiters unknown while the rankings
# are still compared. Given a hand-made device.yaml (a GPU's, invented), a copy of the
# H200 folder gets its winners' limiters named; the side-by-side table marks where the
# winner differs. One folder, or two of different manifests, is refused. No GL: reads
# committed data (seconds).
. "$(dirname "$0")/lib.sh"
cd "$SOURCE_ROOT"
A=docs/results/2026-12-03-llvmpipe/data/renderers-tiled
B=docs/results/2026-12-04-h200/data/renderers-tiled
SOURCE_DATE_EPOCH=1796684400 "$SHADESWEEP" report --cross-device -o "$T/again" "$A" "$B" \
  >"$T/r.out" 2>"$T/r.err" || fail "report: $(cat "$T/r.err")"
grep -q '^report: wrote .*cross-device.md: 14 sweep points' "$T/r.out" || fail "$(cat "$T/r.out")"
diff -u docs/results/cross-device.md "$T/again/cross-device.md" ||
  fail "docs/results/cross-device.md is not what the command makes (see its README for the command)"

mkdir -p "$T/h200"
cp -r "$B"/plan.csv "$B"/summary.csv "$B"/runs "$T/h200/"
cat >"$T/h200/device.yaml" <<'YAML'
key: "0000000000000000"
renderer: "a hand-made GPU"
quick: false
figures:
  fill_rgba16f_1x: {median: 100.0, spread: 1.0, unit: Gsamples/s, repeats: 9}
  bandwidth_copy: {median: 2000.0, spread: 10.0, unit: GB/s, repeats: 9}
  alu_fragment: {median: 50000.0, spread: 100.0, unit: Gflop/s, repeats: 9}
  draw_us: {median: 1.0, spread: 0.1, unit: us, repeats: 9}
  state_change_us: {median: 2.0, spread: 0.1, unit: us, repeats: 9}
  dispatch_us: {median: 5.0, spread: 0.5, unit: us, repeats: 9}
YAML
cd "$T"
"$SHADESWEEP" report --cross-device -o hand "$SOURCE_ROOT/$A" h200 >hand.out 2>hand.err ||
  fail "report: $(cat hand.err)"
"$PYTHON" - "$SOURCE_ROOT/docs/results/cross-device.md" hand/cross-device.md <<'PY' || fail "cross-device.md"
import sys
committed, hand = (open(p).read() for p in sys.argv[1:])
for text, b_known in ((committed, False), (hand, True)):
    rows = [l for l in text.splitlines() if l.startswith("| ") and not l.startswith("| point")]
    assert len(rows) == 14, len(rows)
    cells = [[c.strip() for c in r.strip("|").split("|")] for r in rows]
    # side by side: both rankings of every renderer, fastest first, with times
    for c in cells:
        assert len(c) == 6 and c[1].count(",") >= 3 and c[2].count(",") >= 3, c
    assert any(c[3] == "**winner**" for c in cells), "no difference marked"
    for c in cells:
        assert c[4].split(": ")[1].split(" ")[0] in ("bytes", "fill", "alu", "draws",
                                                     "dispatches"), c   # A has a profile
        assert ("unknown (no device.yaml)" in c[5]) != b_known, c
    assert "## Where the winner differs, and why" in text
    assert ("B: NVIDIA H200/PCIe/SSE2, ranked by gpu time; device profile: none (no "
            "device.yaml: its limiters are unknown)" in text) != b_known
w = [l for l in committed.splitlines() if l.startswith("- scene shapes, lights.count 16:")]
assert w and "deferred wins on A, its limiter bytes" in w[0], w
assert "forward-plus wins on B, its limiter unknown (no device.yaml)" in w[0], w
PY
expect 2 "--cross-device: expected two folders, got 1" \
  "$SHADESWEEP" report --cross-device -o x "$SOURCE_ROOT/$A"
expect 2 "no sweep point in common (not one manifest)" "$SHADESWEEP" report --cross-device \
  -o x "$SOURCE_ROOT/$A" "$SOURCE_ROOT/docs/results/2026-12-04-h200/data/s003-exp1"
echo ok
