#!/usr/bin/env bash
# Output for scripts (issue 24): summary_long.csv and summary.json read with pandas, and
# nothing else known. The swept keys are typed columns (a number int64, a boolean bool, a
# span split into _frames/_s, a resolution also as width_px/height_px), every value equals
# summary.csv's and plan.csv's, no number is written with an exponent, an empty field is
# NaN, and a pivot (renderer x lights.count -> frame time) needs no join. run --resume
# and merge write the same table.
. "$(dirname "$0")/lib.sh"
need_gl
# scripts/setup.sh installs python3-pandas: missing, it is a broken setup, not a skip
"$PYTHON" -c 'import pandas' 2>/dev/null || fail "python3-pandas missing: run scripts/setup.sh"
cd "$T"
cat >tidy.yaml <<'EOF'
shadesweep: 1
name: tidy
scene: shapes
renderers: [forward-mpml, deferred]
duration: {frames: 2}
clock: fixed
step: 0.1
lights: {placement: random, seed: 1337, rng: msvc, radius: 10}
sweep:
  resolution: [64x64, 32x32]
  lights.count: [1, 40]
  deferred.sky_stencil: [false, true]
  warmup: [{frames: 1}, {seconds: 0.001}]
EOF
"$SHADESWEEP" run tidy.yaml -o out >run.out 2>run.err || fail "run: $(cat run.err)"
"$PYTHON" - out <<'PY'
import csv, json, math, os, re, sys
import pandas as pd
out = sys.argv[1]
def fail(msg):
    print("FAIL:", msg, file=sys.stderr); sys.exit(1)
# every file a script reads: no number in exponent form, no word for a missing value
# (run ids aside: 12 hex digits such as 09424e199791 may look like one)
exp = re.compile(r"-?[0-9.]+[eE][+-]?[0-9]+")
for name in ("summary_long.csv", "summary.csv"):
    with open(os.path.join(out, name), newline="") as f:
        rows = list(csv.reader(f))
    skip = rows[0].index("run_id")
    for row in rows[1:]:
        for i, v in enumerate(row):
            if i != skip and (exp.fullmatch(v) or v in ("never", "n/a", "-")):
                fail(f"{name}: {rows[0][i]} is {v!r}")

ids = {"run_id": str}   # 12 hex digits may read as a number
long = pd.read_csv(os.path.join(out, "summary_long.csv"), dtype=ids)
summ = pd.read_csv(os.path.join(out, "summary.csv"), dtype=ids)
plan = pd.read_csv(os.path.join(out, "plan.csv"), dtype=ids)
want = {"lights.count": "int64", "width_px": "int64", "height_px": "int64", "trial": "int64",
        "deferred.sky_stencil": "bool", "warmup_frames": "float64", "warmup_s": "float64",
        "value": "float64", "resolution": "object", "measure": "object", "unit": "object"}
for col, dt in want.items():
    if col not in long.columns: fail(f"summary_long.csv has no {col}: {list(long.columns)}")
    if str(long[col].dtype) != dt: fail(f"summary_long.csv {col}: {long[col].dtype}, want {dt}")
head = ["experiment", "run_id", "renderer", "scene", "resolution", "width_px", "height_px",
        "warmup_frames", "warmup_s", "deferred.sky_stencil", "lights.count", "trial", "status",
        "measure", "unit", "value"]
if list(long.columns) != head: fail(f"summary_long.csv columns {list(long.columns)}")
# summary.csv itself: its numbers read as numbers, its missing values as NaN
for col in ("lights_radius", "ci1pct_after_s", "image_rmse", "gbuffer_write_bytes_mean"):
    if summ[col].dtype.kind not in "iuf": fail(f"summary.csv {col}: {summ[col].dtype}")
fwd = summ[summ.renderer == "forward-mpml"]
if not fwd.gbuffer_write_bytes_mean.isna().all(): fail("forward-mpml has G-buffer bytes")

# the keys: plan.csv's values, typed
p = plan.set_index("run_id")
for rid, g in long.groupby("run_id"):
    r = p.loc[rid]
    k = g.iloc[0]
    if (g[["lights.count", "resolution", "deferred.sky_stencil"]].nunique() != 1).any():
        fail(f"{rid}: keys differ between its rows")
    w, h = (int(x) for x in r["resolution"].split("x"))
    if k["lights.count"] != int(r["lights.count"]) or k.resolution != r["resolution"] \
       or (k.width_px, k.height_px) != (w, h) \
       or k["deferred.sky_stencil"] != (str(r["deferred.sky_stencil"]).lower() == "true"):
        fail(f"{rid}: keys {k.to_dict()} vs plan {r.to_dict()}")
    unit, num = r["warmup"].split(":")
    got = k.warmup_frames if unit == "frames" else k.warmup_s
    other = k.warmup_s if unit == "frames" else k.warmup_frames
    if got != float(num) or not math.isnan(other):
        fail(f"{rid}: warmup {r['warmup']} as {k.warmup_frames} frames, {k.warmup_s} s")
if set(long.run_id) != set(plan.run_id): fail("summary_long.csv lacks runs of the plan")

# the values: summary.csv's, each non-empty measured cell once, with its unit
measures = sorted(set(long.measure))
cells = summ.melt(id_vars=["run_id", "trial"], value_vars=measures, var_name="measure").dropna()
both = cells.merge(long, on=["run_id", "trial", "measure"], how="outer", indicator=True)
if (both._merge != "both").any(): fail(f"unmatched cells: {both[both._merge != 'both'].head()}")
if not (both.value_x == both.value_y).all(): fail("values differ from summary.csv")
units = dict(zip(long.measure, long.unit))
if units["frametime_mean_us"] != "us" or units["gbuffer_write_bytes_mean"] != "bytes":
    fail(f"units {units}")
if "gbuffer_write_bytes_mean" in set(long[long.renderer == "forward-mpml"].measure):
    fail("a missing value has a row")

# the pivot the issue asks for, no join
ft = long[long.measure == "frametime_mean_us"]
pv = ft.pivot_table(index="renderer", columns="lights.count", values="value", aggfunc="mean")
if pv.shape != (2, 2) or pv.isna().any().any() or list(pv.columns) != [1, 40]:
    fail(f"pivot\n{pv}")
ref = summ.merge(plan[["run_id", "lights.count"]], on="run_id") \
          .groupby(["renderer", "lights.count"]).frametime_mean_us.mean()
if not all(math.isclose(pv.loc[a, b], ref[(a, b)]) for a, b in ref.index):
    fail(f"pivot\n{pv}\nvs summary.csv\n{ref}")

# summary.json alone: each run's parameters and each trial's measures, with units
d = json.load(open(os.path.join(out, "summary.json")))
rows = [{"run_id": run["run_id"], "renderer": run["renderer"], **run["parameters"],
         "trial": t["trial"], "status": t["status"], **t["measures"]}
        for pt in d["points"] for run in pt["runs"] for t in run["trial_results"]]
js = pd.DataFrame(rows)
if len(js) != len(summ) or set(js.run_id) != set(plan.run_id): fail(f"summary.json has {len(js)} trials")
if js["lights.count"].dtype != "int64" or js["deferred.sky_stencil"].dtype != "bool":
    fail(f"summary.json parameters {js.dtypes.to_dict()}")
if set(d["units"]) < set(measures) or d["units"]["frametime_mean_us"] != "us":
    fail(f"summary.json units {d['units']}")
m = js.merge(summ, on=["run_id", "trial"], suffixes=("", "_csv"))
for col in measures:
    a, b = m[col], m[col + "_csv"]
    if not ((a.isna() & b.isna()) | ((a - b).abs() <= 1e-8 * b.abs())).all():
        fail(f"summary.json {col} differs from summary.csv")
print("tidy: ok")
PY
# run --resume and merge write the same table
cp out/summary_long.csv first.csv
rm out/summary_long.csv
"$SHADESWEEP" run --resume tidy.yaml -o out >resume.out 2>resume.err || fail "resume: $(cat resume.err)"
cmp -s first.csv out/summary_long.csv || fail "run --resume wrote another summary_long.csv"
"$SHADESWEEP" merge -o merged out 2>merge.err || fail "merge: $(cat merge.err)"
cmp -s first.csv merged/summary_long.csv || fail "merge wrote another summary_long.csv"
