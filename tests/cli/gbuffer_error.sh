#!/usr/bin/env bash
# The G-buffer study (experiments/gbuffer-error.yaml, issue 5) as a smoke run in a
# debug context: shard 1 of 2 of its 120 runs. Shards hold whole sweep points, and the
# study has two (its scenes: the G-buffer keys are deferred's configuration, ranked
# together), so the shard is canyon's 60 runs, every value of every other axis. Each
# run must end ok with a finite image error against forward-spml and no
# non-finite value; scripts/report must draw the study from the shard's folder.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
M="$SOURCE_ROOT/experiments/gbuffer-error.yaml"
# draw_limit 0.1 s: each run draws its first frames and its error times, no more (the
# checks below read no frame count; the smoke default of 2 s a run tripled this test).
"$SHADESWEEP" run --smoke --debug-gl --set draw_limit=0.1 --shard 1/2 \
  --out out/gbuffer-error-smoke "$M" \
  >ge.out 2>ge.err || { tail -n 30 ge.err >&2; fail "gbuffer-error --smoke --shard 1/2 exited non-zero"; }

"$PYTHON" - out/gbuffer-error-smoke <<'PY'
import csv, os, sys
d = sys.argv[1]
def fail(msg):
    print("FAIL:", msg, file=sys.stderr); sys.exit(1)
def table(name):
    with open(os.path.join(d, name), newline="") as f:
        return list(csv.DictReader(f))
plan = {p["run_id"]: p for p in table("plan.csv") if p["shard"] == "1"}  # the whole plan, shard marked
summ = table("summary.csv")
if len(summ) != 60 or {s["run_id"] for s in summ} != set(plan):
    fail(f"{len(summ)} summary rows for a plan of {len(plan)} (want 60)")
want = {"scene": {"canyon"},
        "gbuffer.preset": {"curtis", "fat", "compact", "spheremap", "reference"},
        "gbuffer.position": {"preset", "stored16", "depth"},
        "deferred.light_volumes": {"stencil", "stencil-two-pass", "volume", "fullscreen"}}
for key, values in want.items():
    have = {p[key] for p in plan.values()}
    if have != values:
        fail(f"the shard's {key}: {sorted(have)}, want {sorted(values)}")
for s in summ:
    if s["status"] != "ok":
        fail(f"run {s['run_id']} {s['status']} {s['message']}")
    if s["width"] != "160" or s["height"] != "120":
        fail(f"not a smoke run: {s['width']}x{s['height']}")
    if s["image_rmse"] in ("", "nan") or s["nonfinite_pixels"] != "0":
        fail(f"{s['run_id']}: rmse {s['image_rmse']} nonfinite {s['nonfinite_pixels']}")
print("gbuffer-error: ok")
PY

if "$PYTHON" -c 'import matplotlib' 2>/dev/null; then
  "$SOURCE_ROOT/scripts/report" out >report.out 2>report.err \
    || { cat report.err >&2; fail "scripts/report exited non-zero"; }
  grep -q "gbuffer-error" out/report.md || fail "report.md does not mention gbuffer-error"
fi
echo "gbuffer-error: ok"
