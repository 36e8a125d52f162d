#!/usr/bin/env bash
# Honest labels (issue 38, item 5): every answer made on a software rasterizer says so in
# one line, and passes.csv says its pass times are not the passes' own. A tiny llvmpipe
# sweep (16x16, two frames, two renderers): summary.md before its first table,
# summary.json, run's terminal answer (above the verdicts), compare and report carry it, and passes.csv's
# gpu_us_attributed and cpu_us_attributed are 0 with the counters kept. A GPU folder says
# nothing: the committed H200 data (docs/results/2026-12-04-h200) through report, compare
# and ratios, and this sweep's folder with its meta.yaml's GL strings made the H200's,
# merged (summary.md and summary.json again); with one run's only, the merge names both.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
H200="$SOURCE_ROOT/docs/results/2026-12-04-h200/data/renderers-deferred"
LINE="measured on llvmpipe (LLVM"
CPU="a CPU rasterizer, so these rankings measure a CPU, not a GPU, and per-pass times are not attributed"
cat >tiny.yaml <<'YAML'
shadesweep: 1
name: tiny
scene: shapes
renderers: [deferred, forward-spml]
resolution: 16x16
trials: 1
warmup: {frames: 0}
duration: {frames: 2}
clock: fixed
lights: {count: 2, radius: 4}
outputs: {seconds: false}
YAML
"$SHADESWEEP" run -o sw tiny.yaml >run.out 2>run.err || fail "run: $(cat run.err)"
grep -q "llvmpipe" sw/runs/*/meta.yaml || { echo "SKIP: not on llvmpipe" >&2; exit 77; }

# the terminal: once, between the table's "ranked:" line and the verdicts (last)
grep -A1 "^ranked: " run.out | grep -q "^device: $LINE.*$CPU" || fail "terminal: $(tail -n 4 run.out)"
tail -n 1 run.out | grep -q "^verdict: " || fail "terminal: the verdict not last: $(tail -n 1 run.out)"
[ "$(grep -c "CPU rasterizer" run.out)" -eq 1 ] || fail "terminal: not one line"
# summary.md: one line, before the first table
grep -q "^\*\*Device:\*\* $LINE.*$CPU" sw/summary.md || fail "summary.md: no device line"
dl=$(grep -n "^\*\*Device:\*\*" sw/summary.md | cut -d: -f1)
tl=$(grep -n "^| rank" sw/summary.md | head -n 1 | cut -d: -f1)
[ "$dl" -lt "$tl" ] || fail "summary.md: the device line ($dl) after the table ($tl)"
[ "$(grep -c "CPU rasterizer" sw/summary.md)" -eq 1 ] || fail "summary.md: not one line"
# summary.json, passes.csv
"$PYTHON" - <<'PY' || fail "summary.json or passes.csv"
import csv, glob, json
d = json.load(open("sw/summary.json"))["device"]
assert d["software_rasterizer"] is True and d["devices"] == 1, d
assert d["note"].startswith("measured on llvmpipe (LLVM") and "a CPU rasterizer" in d["note"], d
files = glob.glob("sw/runs/*/passes.csv")
assert len(files) == 2, files
for f in files:
    rows = list(csv.DictReader(open(f)))
    head = list(rows[0])
    # appended last: the earlier columns keep their names and places
    assert head[-5:] == ["gpu_us_attributed", "cpu_us_attributed", "bound_us", "limiter",
                         "bound_pct"], head
    assert head[:6] == ["run_id", "trial", "frame", "pass", "gpu_us", "cpu_us"], head
    assert len(rows) >= 4, (f, len(rows))   # 2 frames x at least 2 passes
    for r in rows:
        assert r["gpu_us_attributed"] == "0" and r["cpu_us_attributed"] == "0", r
        assert int(r["draw_calls"]) >= 1 and float(r["fragments"]) > 0, r   # counters kept
PY
# compare: one line for both sides when they agree; JSON: both fields
"$SHADESWEEP" compare sw sw >cmp.md 2>cmp.err || fail "compare: $(cat cmp.err)"
grep -q "^\*\*Device of BASE and NEW:\*\* $LINE.*$CPU" cmp.md || fail "compare: $(cat cmp.md)"
[ "$(grep -c "CPU rasterizer" cmp.md)" -eq 1 ] || fail "compare: not one line"
"$SHADESWEEP" compare --json sw sw >cmp.json 2>cmp.err || fail "compare --json: $(cat cmp.err)"
"$PYTHON" -c '
import json, sys
d = json.load(open("cmp.json"))
assert d["base_device"] == d["new_device"] and "a CPU rasterizer" in d["base_device"], d
' || fail "compare --json: $(cat cmp.json)"
# the report: its head and its stdout
"$SHADESWEEP" report -o rep sw >rep.out 2>rep.err || fail "report: $(cat rep.err)"
grep -q "^- \*\*Device:\*\* $LINE.*$CPU" rep/report.md || fail "report.md: no device line"
grep -q "^report: device: $LINE" rep.out || fail "report stdout: $(cat rep.out)"

# A GPU: the committed H200 folder says nothing
"$SHADESWEEP" report -o h200 "$H200" >h200.out 2>h200.err || fail "report H200: $(cat h200.err)"
grep -qi "rasterizer\|device:" h200/report.md h200.out && fail "H200 report: $(grep -i "rasterizer\|device:" h200/report.md h200.out)"
grep -q "^- GL renderer: NVIDIA H200/PCIe/SSE2" h200/report.md || fail "H200 report: meta.yaml not read"
"$SHADESWEEP" compare "$H200" "$H200" >h200cmp.md 2>/dev/null || fail "compare H200"
grep -q "Device" h200cmp.md && fail "compare H200: $(grep Device h200cmp.md)"
printf 'device\t%s\n' "$H200" | "$SHADESWEEP" ratios >h200.json || fail "ratios device"
grep -qx '{"software_rasterizer": false, "devices": 1, "note": null}' h200.json ||
  fail "ratios device H200: $(cat h200.json)"

# ... and so does this sweep, its GL strings made the H200's (files.txt kept in step), as
# merge writes its summaries again; with one run's strings only, the merge names both
gpuify() {  # gpuify DIR [RUN]
  "$PYTHON" - "$@" <<'PY'
import os, re, sys
d, only = sys.argv[1], sys.argv[2:]
def fnv(b):   # files.txt's checksum: FNV-1a 64
    h = 0xcbf29ce484222325
    for c in b:
        h = ((h ^ c) * 0x100000001b3) & 0xffffffffffffffff
    return f"{h:016x}"
for rid in sorted(os.listdir(f"{d}/runs")):
    if only and rid not in only:
        continue
    m = f"{d}/runs/{rid}/meta.yaml"
    t = open(m).read()
    a = t.index("\ngl:\n") + 5
    z = re.compile(r"\n(?! )").search(t, a).start()
    g = re.sub(r"(?m)^  vendor: .*$", "  vendor: NVIDIA Corporation", t[a:z])
    g = re.sub(r"(?m)^  renderer: .*$", "  renderer: NVIDIA H200/PCIe/SSE2", g)
    g = re.sub(r"(?m)^  version: .*$", '  version: "4.5.0 NVIDIA 580.159.04"', g)
    open(m, "w").write(t[:a] + g + t[z:])
    b = open(m, "rb").read()
    ft = f"{d}/runs/{rid}/files.txt"
    lines = [f"meta.yaml {len(b)} {fnv(b)}" if l.startswith("meta.yaml ") else l
             for l in open(ft).read().splitlines()]
    open(ft, "w").write("\n".join(lines) + "\n")
PY
}
cp -r sw gpu && gpuify gpu
"$SHADESWEEP" merge -o gm gpu >gm.out 2>gm.err || fail "merge: $(cat gm.err)"
grep -qi "rasterizer\|device" gm.out gm/summary.md && fail "GPU: $(grep -i "rasterizer\|device" gm.out gm/summary.md)"
"$PYTHON" -c '
import json
d = json.load(open("gm/summary.json"))["device"]
assert d == {"software_rasterizer": False, "devices": 1, "note": None}, d
' || fail "GPU summary.json"
cp -r sw mix && gpuify mix "$(ls sw/runs | head -n 1)"
"$SHADESWEEP" merge -o mm mix >mm.out 2>mm.err || fail "merge mixed: $(cat mm.err)"
grep -q "^\*\*Device:\*\* measured on 2 devices, .*: llvmpipe (LLVM [^)]*) (1 run, a CPU rasterizer); NVIDIA H200/PCIe/SSE2 (1 run); on a CPU rasterizer these rankings measure a CPU" mm/summary.md ||
  fail "mixed: $(grep Device mm/summary.md)"
grep -q "^device: measured on 2 devices" mm.out || fail "mixed terminal: $(tail -n 3 mm.out)"
echo "device_labels: ok"
