#!/usr/bin/env bash
# lights.culling: stochastic (docs/notes/stochastic-culling.md) end to end: a sweep over
# lights.culling_error with an error block reports each run's RMSE against forward-spml
# (0 at error 0: exact, bit for bit; above 0, off by less than 1/255 here and more the
# larger the error), fewer light evaluations a pixel the larger the error, the same
# image error on a second run (the stream is seeded), and the report's figure and table
# of error against time, one line per renderer.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat > sc.yaml <<'YAML'
shadesweep: 1
name: sc
scene: shapes
renderers: [forward-plus, clustered]
resolution: 48x32
trials: 1
duration: {frames: 3}
draw_limit: 0.1
clock: fixed
step: 0.1
lights: {count: 64, radius: 30, color_max: 0.05, culling: stochastic}
error:
  reference: {renderer: forward-spml}
  at: [0.1]
sweep:
  lights.culling_error: [0, 0.01, 0.1]
YAML
"$SHADESWEEP" run sc.yaml >out.txt 2>err.txt || fail "run: $(cat err.txt)"
"$SHADESWEEP" run sc.yaml -o again/sc >/dev/null 2>err2.txt || fail "second run: $(cat err2.txt)"
"$PYTHON" - <<'PY'
import csv, sys
def fail(m): print("FAIL:", m, file=sys.stderr); sys.exit(1)
def rows(folder):
    plan = {p["run_id"]: p for p in csv.DictReader(open(f"{folder}/sc/plan.csv"))}
    out = {}
    for r in csv.DictReader(open(f"{folder}/sc/summary.csv")):
        if r["status"] != "ok": fail(f"{r['run_id']}: {r['status']}")
        out[(r["renderer"], float(plan[r["run_id"]]["lights.culling_error"]))] = r
    return out
a, b = rows("out"), rows("again")
if len(a) != 6: fail(f"{len(a)} runs")
for ren in ("forward-plus", "clustered"):
    rm = [float(a[(ren, e)]["image_rmse"]) for e in (0, 0.01, 0.1)]
    ev = [float(a[(ren, e)]["light_evals_per_pixel"]) for e in (0, 0.01, 0.1)]
    if rm[0] != 0: fail(f"{ren} at error 0 is not exact: {rm}")
    if not (0 < rm[1] < rm[2] < 1 / 255): fail(f"{ren} RMSE {rm}")
    if not (ev[0] > ev[1] > ev[2] > 0): fail(f"{ren} evaluations {ev}")
    for e in (0.01, 0.1):   # seeded: the same image error again
        if a[(ren, e)]["image_rmse"] != b[(ren, e)]["image_rmse"]: fail(f"{ren} {e} differs")
PY
export SHADESWEEP_EXE="$SHADESWEEP"
"$SOURCE_ROOT/scripts/report" out -o rep >rep.out 2>rep.err || fail "report: $(cat rep.err)"
grep -q "image error against .* as lights.culling_error varies" rep/report.md ||
  fail "no culling error table: $(cat rep/report.md)"
grep -q "^| clustered | 0.1000 |" rep/report.md || fail "no clustered row at 0.1"
if "$PYTHON" -c "import matplotlib" 2>/dev/null; then
  [ -s rep/plots/sc_culling_error.png ] || fail "no figure: $(ls rep/plots)"
fi
echo ok
