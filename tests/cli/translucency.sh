#!/usr/bin/env bash
# translucency: blend | opaque on the glass scene: with opaque, the same scene without
# its translucent pass (the panes and particles drawn in the opaque passes), meta.yaml
# saying how many materials it made opaque; the two are one sweep, so their difference
# is what translucency costs. Every renderer that draws; 32x24, one frame.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
cat > t.yaml <<YAML
shadesweep: 1
name: t
scene: glass
renderers: [forward-spml, deferred, tiled-deferred, deferred-lighting]
resolution: 32x24
duration: {frames: 1}
clock: fixed
lights: {count: 4, radius: 8, attenuation: linear-range}
sweep:
  translucency: [blend, opaque]
YAML
"$SHADESWEEP" run t.yaml >out.txt 2>err.txt || fail "run: $(cat err.txt)"
# the default is not part of the run id: blend's ids are those of before the key
sed '/^sweep:/,$d' t.yaml > plain.yaml
for id in $("$SHADESWEEP" list plain.yaml | awk '{print $1}'); do
  grep -q "^$id " <("$SHADESWEEP" list t.yaml) || fail "translucency: blend changed id $id"
done
"$PYTHON" - <<'PY'
import csv, glob, os, sys, yaml
def fail(m):
    print("FAIL: " + m, file=sys.stderr); sys.exit(1)
runs = {}
for d in glob.glob("out/t/runs/*"):
    m = yaml.safe_load(open(os.path.join(d, "meta.yaml")))
    p = m["parameters"]
    mode = p.get("translucency", "blend")
    passes = {r["pass"] for r in csv.DictReader(open(os.path.join(d, "passes.csv")))}
    plan = {e["name"]: e for e in m["pass_plan"]["passes"]}
    runs[(p["renderer"], mode)] = (m, passes, plan)
if len(runs) != 8:
    fail(f"{len(runs)} runs, want 8: {sorted(runs)}")
for (ren, mode), (m, passes, plan) in sorted(runs.items()):
    if mode == "blend":
        if "translucent" not in passes or not plan["translucent"]["run"]:
            fail(f"{ren} blend: no translucent pass ({sorted(passes)})")
        if "made_opaque" in m:
            fail(f"{ren} blend: made_opaque in meta.yaml")
    else:
        if "translucent" in passes or plan["translucent"]["run"]:
            fail(f"{ren} opaque: the translucent pass ran ({sorted(passes)})")
        if "no translucent materials" not in plan["translucent"]["reason"]:
            fail(f"{ren} opaque: reason {plan['translucent']['reason']!r}")
        # glass: its four panes' materials and the two particle materials
        if m.get("made_opaque") != 6:
            fail(f"{ren} opaque: made_opaque {m.get('made_opaque')!r}, want 6")
# the opaque passes draw what the translucent pass drew: the frame's draws are as many,
# moved between passes; deferred-lighting draws its opaque objects twice (G-buffer and
# material passes), so opaque has one more draw per object the translucent pass drew
def translucent_draws(ren):
    plan = {r["run_id"]: r for r in csv.DictReader(open("out/t/plan.csv"))}
    for r in csv.DictReader(open("out/t/summary.csv")):
        if r["renderer"] == ren and (plan[r["run_id"]].get("translucency") or "blend") == "blend":
            rows = [p for p in csv.DictReader(open(f"out/t/runs/{r['run_id']}/passes.csv"))
                    if p["pass"] == "translucent"]
            return sum(float(p["draw_calls"]) for p in rows) / len(rows)
    fail(f"{ren}: no blend run")
for ren in ("forward-spml", "deferred", "tiled-deferred", "deferred-lighting"):
    plan = {r["run_id"]: r for r in csv.DictReader(open("out/t/plan.csv"))}
    rows = {plan[r["run_id"]].get("translucency") or "blend": r
            for r in csv.DictReader(open("out/t/summary.csv")) if r["renderer"] == ren}
    if sorted(rows) != ["blend", "opaque"] or any(r["status"] != "ok" for r in rows.values()):
        fail(f"{ren}: {[(k, r['status']) for k, r in rows.items()]}")
    extra = translucent_draws(ren) if ren == "deferred-lighting" else 0.0
    if ren == "deferred-lighting" and not extra > 0:
        fail(f"{ren}: the translucent pass drew nothing")
    if float(rows["blend"]["draw_calls_mean"]) + extra != float(rows["opaque"]["draw_calls_mean"]):
        fail(f"{ren}: draws {rows['blend']['draw_calls_mean']} (blend) vs "
             f"{rows['opaque']['draw_calls_mean']} (opaque)")
print("ok")
PY
