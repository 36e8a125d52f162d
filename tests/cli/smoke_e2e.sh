#!/usr/bin/env bash
# End to end: `shadesweep run experiments/smoke.yaml` and every file and column it leaves.
. "$(dirname "$0")/lib.sh"
need_gl
cd "$T"
"$SHADESWEEP" run --debug-gl "$SOURCE_ROOT/experiments/smoke.yaml" >run.out 2>run.err \
  || { cat run.err >&2; fail "smoke run exited $?"; }
# two trials a run: a progress line per trial, the run's trials interleaved with the
# other renderers' of its sweep point
grep -q "^32 of 32: run [0-9a-f]\{12\} [a-z-]* [0-9]*x[0-9]* trial 2 of 2: ok" run.err ||
  fail "progress lines missing: $(cat run.err)"
grep -q "^16 runs, 0 failed (32 trials), in" run.err || fail "no closing count: $(cat run.err)"
"$PYTHON" - out/smoke <<'PY'
import csv, glob, math, os, struct, sys
import yaml
ncpus = len(os.sched_getaffinity(0))   # as results/contention.c: the CPUs it may run on
out = sys.argv[1]
def fail(msg):
    print("FAIL:", msg, file=sys.stderr); sys.exit(1)
def rows(path, want_cols):
    with open(path, newline="") as f:
        r = list(csv.reader(f))
    if r[0] != want_cols:
        fail(f"{path}: columns {r[0]} != {want_cols}")
    return [dict(zip(r[0], x)) for x in r[1:]]

summary_cols = ["experiment","run_id","renderer","scene","width","height","gbuffer",
  "lights_placement","lights_rng","lights_seed","lights_count","lights_radius","trial",
  "frames","measured_s","fps_mean","frametime_mean_us","frametime_sd_us","frametime_ci95_us",
  "frametime_p50_us","frametime_p99_us","fps_1pct_low","gpu_mean_us","draw_calls_mean","state_changes_mean",
  "fragments_mean","samples_mean","gbuffer_bytes","image_rmse","image_psnr_db","image_max_abs",
  "nonfinite_pixels","harness_us_mean","ci1pct_after_s","dispatches_mean","cell_lights_mean",
  "cell_lights_max","light_evals_per_pixel","gbuffer_bytes_per_frame","gbuffer_write_bytes_mean",
  "gbuffer_read_bytes_mean","image_edge_rmse","image_edge_pixels","samples_shaded_mean",
  "edge_fraction_mean","cpu_mean_us","cpu_p50_us","cpu_share_mean","invol_csw","vol_csw",
  "steal_frac","loadavg_1m","coverage","lights_reaching_mean",
  "lights_reaching_p50","lights_reaching_p99","lights_reaching_max","sm_clock_mhz","light_struct_bytes_mean","order","metric","metric_us","bound_us","limiter","bound_pct","status","message"]
frames_cols = ["run_id","trial","frame","t_wall_s","t_scene_s","lights","frametime_us",
  "gpu_us","draw_calls","state_changes","fragments","samples","gbuffer_bytes_per_frame",
  "gbuffer_write_bytes","gbuffer_read_bytes","cpu_us","cpu_share"]
seconds_cols = ["run_id","trial","second","complete","lights_min","lights_max","frames","fps",
  "frametime_mean_us","frametime_sd_us","frametime_p50_us","frametime_p99_us","draw_calls_mean"]
passes_cols = ["run_id","trial","frame","pass","gpu_us","cpu_us","draw_calls","state_changes",
  "fragments","samples","primitives","dispatches","cell_lights_mean","cell_lights_max",
  "light_evals_per_pixel","scissor_pixels","samples_shaded","edge_fraction",
  "gpu_us_attributed","cpu_us_attributed","bound_us","limiter","bound_pct"]
convergence_cols = ["run_id","trial","elapsed_s","frames","frametime_mean_us","frametime_ci95_us",
  "ci95_rel"]

with open(os.path.join(out, "plan.csv"), newline="") as f:
    plan = list(csv.DictReader(f))
RENDERERS = ["null", "deferred", "forward-mpml", "forward-spml"]
if len(plan) != 16:
    fail(f"plan has {len(plan)} runs, want 16 (2 resolutions x 2 sync modes x 4 renderers)")
# sweep order: first axis slowest, renderers fastest
order = [(p["resolution"], p["sync"], p["renderer"]) for p in plan]
if order != [(r, s, k) for r in ("64x64", "160x120") for s in ("finish", "fence") for k in RENDERERS]:
    fail(f"plan order {order}")
ids = [p["run_id"] for p in plan]
if len(set(ids)) != 16 or not all(len(i) == 12 and all(c in "0123456789abcdef" for c in i) for i in ids):
    fail(f"run ids {ids}")

summary = rows(os.path.join(out, "summary.csv"), summary_cols)
if len(summary) != 32:
    fail(f"summary has {len(summary)} rows, want 16 runs x 2 trials")
for s, want_id in zip(summary, [i for i in ids for _ in (1, 2)]):
    if s["run_id"] != want_id: fail(f"summary order: {s['run_id']} != {want_id}")
    if s["status"] != "ok" or s["message"] != "": fail(f"status {s['status']} {s['message']}")
    if s["frames"] != "30": fail(f"frames {s['frames']}")
    if s["experiment"] != "smoke" or s["renderer"] not in RENDERERS or s["scene"] != "shapes":
        fail(f"labels {s}")
    if s["renderer"] == "null":
        if s["draw_calls_mean"] != "0.000" or s["state_changes_mean"] != "0.000":
            fail(f"null renderer draws nothing: {s}")
    elif not (float(s["draw_calls_mean"]) > 0 and float(s["fragments_mean"]) > 0):
        fail(f"{s['renderer']} drew nothing: {s}")
    # the G-buffer belongs to deferred runs alone
    if (s["gbuffer"] == "curtis") != (s["renderer"] == "deferred"): fail(f"gbuffer {s}")
    if (int(s["gbuffer_bytes"]) > 0) != (s["renderer"] == "deferred"): fail(f"gbuffer_bytes {s}")
    if (s["gbuffer_bytes_per_frame"] != "") != (s["renderer"] == "deferred") or \
            (s["renderer"] == "deferred" and abs(float(s["gbuffer_bytes_per_frame"]) - float(s["gbuffer_write_bytes_mean"])
                                              - float(s["gbuffer_read_bytes_mean"])) > 0.2):
        fail(f"gbuffer_bytes_per_frame {s}")
    if s["lights_count"] != "8":   # 30 frames at 0.1 s: t < 3, so 4 * 2 lights at most
        fail(f"lights_count {s['lights_count']}")
    for k in ("fps_mean","frametime_mean_us","frametime_p50_us","frametime_p99_us","measured_s"):
        v = float(s[k])
        if not (math.isfinite(v) and v > 0): fail(f"{k} = {s[k]}")
    mean, p50, p99 = (float(s[k]) for k in ("frametime_mean_us","frametime_p50_us","frametime_p99_us"))
    if not p50 <= p99: fail("p50 > p99")
    if abs(float(s["fps_1pct_low"]) - 1e6 / p99) > 0.0005 + 1e-6 * 1e6 / p99:
        fail(f"fps_1pct_low {s['fps_1pct_low']} != 1e6 / p99 {p99}")
    if not math.isfinite(float(s["frametime_ci95_us"])): fail("ci95")
    # how much of the machine the trial got (results/contention.c)
    for k in ("cpu_mean_us", "cpu_p50_us", "cpu_share_mean"):
        v = float(s[k])
        if not (math.isfinite(v) and v > 0): fail(f"{k} = {s[k]}")
    for k in ("invol_csw", "vol_csw"):
        if not s[k].isdigit(): fail(f"{k} = {s[k]!r}")
    if not float(s["loadavg_1m"]) >= 0: fail(f"loadavg_1m {s['loadavg_1m']!r}")
    # the scene covers part of the screen; null has no depth target (empty_frame.sh)
    if (s["coverage"] == "") != (s["renderer"] == "null") or \
            (s["coverage"] != "" and not 0 < float(s["coverage"]) <= 1):
        fail(f"coverage {s['coverage']!r} of {s['renderer']}")
    if s["steal_frac"] != "" and not 0 <= float(s["steal_frac"]) <= 1:
        fail(f"steal_frac {s['steal_frac']}")
    # what decides: the process's CPU time on llvmpipe (measure.metric: auto), and each
    # trial's value of it
    if s["metric"] != "cpu" or abs(float(s["metric_us"]) - float(s["cpu_mean_us"])) > 0.01:
        fail(f"metric {s['metric']} {s['metric_us']} (cpu_mean_us {s['cpu_mean_us']})")
    # 30 frames in measured_s seconds
    if abs(float(s["fps_mean"]) - 30 / float(s["measured_s"])) > 0.01 * float(s["fps_mean"]) + 0.002:
        fail("fps_mean != frames / measured_s")
# the schedule: each sweep point's runs in rounds, each round's order a permutation of
# 1..runs of the point (4 renderers a point), recorded in `order`
plan_rows = {p["run_id"]: p for p in csv.DictReader(open(os.path.join(out, "plan.csv")))}
rounds = {}
for s in summary:
    p = plan_rows[s["run_id"]]
    rounds.setdefault((p["resolution"], p["sync"], s["trial"]), []).append(int(s["order"]))
if len(rounds) != 8 or any(sorted(v) != [1, 2, 3, 4] for v in rounds.values()):
    fail(f"rounds are not permutations: {rounds}")

work = {}   # (renderer, resolution) -> per-frame work counts, the same in every run
for p in plan:
    d = os.path.join(out, "runs", p["run_id"])
    w, h = (int(x) for x in p["resolution"].split("x"))
    null = p["renderer"] == "null"
    fr = rows(os.path.join(d, "frames.csv"), frames_cols)
    if len(fr) != 60: fail(f"{d}: {len(fr)} frame rows, want 60")
    for i, r in enumerate(fr):
        trial, k = 1 + i // 30, i % 30
        if (r["trial"], r["frame"]) != (str(trial), str(k)): fail(f"frame numbering {r}")
        if abs(float(r["t_scene_s"]) - 0.1 * k) > 1e-6: fail(f"fixed clock t_scene {r}")
        if int(r["lights"]) != 4 * (k // 10): fail(f"light growth at frame {k}: {r['lights']}")
        if null and (r["draw_calls"] != "0" or r["state_changes"] != "0"): fail("work counts")
        if null and r["fragments"] not in ("0", ""): fail(f"fragments of a clear: {r['fragments']}")
        if not null and int(r["draw_calls"]) <= 0: fail(f"no draws: {r}")
        # GL_SAMPLES_PASSED is core GL: counted on every driver, none for a clear
        if r["samples"] == "" or (null and r["samples"] != "0") or \
                (not null and int(r["samples"]) <= 0): fail(f"samples: {r}")
        if float(r["frametime_us"]) <= 0: fail("frame time")
        # the process's CPU time over the frame, and its share of the usable CPUs
        # (a frame shorter than a scheduler tick can show a share above 1: the kernel
        # accounts llvmpipe's threads late; the trial's sums below may not)
        cpu, share = float(r["cpu_us"]), float(r["cpu_share"])
        if not (math.isfinite(cpu) and cpu > 0): fail(f"cpu_us {r}")
        if not (math.isfinite(share) and share > 0): fail(f"cpu_share {r}")
        if abs(share - cpu / (float(r["frametime_us"]) * ncpus)) > 1e-3 * share + 1e-4:
            fail(f"cpu_share != cpu_us / (frametime_us x {ncpus} CPUs): {r}")
    # over a trial the process cannot use more than the CPUs it may run on: two ticks of
    # late accounting (4 ms at HZ=250) on each CPU at most at the ends
    for t in ("1", "2"):
        tr = [r for r in fr if r["trial"] == t]
        cpu = sum(float(r["cpu_us"]) for r in tr)
        wall = sum(float(r["frametime_us"]) for r in tr)
        if cpu > 1.05 * ncpus * wall + 2 * 2 * 4000 * ncpus:
            fail(f"{d} trial {t}: {cpu:.0f} us of CPU in {wall:.0f} us on {ncpus} CPUs")
    # clock: fixed makes the work of frame k the same in both trials and both sync modes
    counts = [(r["lights"], r["draw_calls"], r["state_changes"], r["fragments"], r["samples"])
              for r in fr]
    if counts[:30] != counts[30:]: fail(f"{p['renderer']}: work counts differ between trials")
    k = (p["renderer"], p["resolution"])
    if work.setdefault(k, counts) != counts: fail(f"{k}: work counts differ between sync modes")
    tw = [float(r["t_wall_s"]) for r in fr[:30]]
    if tw != sorted(tw): fail("t_wall_s not increasing")
    sec = rows(os.path.join(d, "seconds.csv"), seconds_cols)
    for trial in ("1", "2"):
        bins = [b for b in sec if b["trial"] == trial]
        if sum(int(b["frames"]) for b in bins) != 30: fail("bins do not hold every frame")
        if [int(b["second"]) for b in bins] != list(range(len(bins))): fail("bins not contiguous")
        for b in bins:
            if b["fps"] != b["frames"]: fail("fps of a second is its frame count")
    pa = rows(os.path.join(d, "passes.csv"), passes_cols)
    if null and (len(pa) != 60 or any(r["pass"] != "clear" for r in pa)): fail("passes.csv")
    if not null:
        if len({(r["trial"], r["frame"]) for r in pa}) != 60: fail("passes.csv frames")
        # the passes' draws add up to the frame's
        for f in fr:
            mine = [r for r in pa if (r["trial"], r["frame"]) == (f["trial"], f["frame"])]
            if sum(int(r["draw_calls"]) for r in mine) != int(f["draw_calls"]): fail("pass sums")
            # seed 002's G-buffer traffic: the layout's bytes per pixel (summary's
            # gbuffer_bytes / pixels) x the G-buffer pass's samples written, x the
            # ambient and light passes' samples read; empty without a G-buffer
            gb = [f[k] for k in ("gbuffer_bytes_per_frame", "gbuffer_write_bytes", "gbuffer_read_bytes")]
            if p["renderer"] != "deferred":
                if gb != ["", "", ""]: fail(f"G-buffer traffic of {p['renderer']}: {gb}")
                continue
            srow = next(s for s in summary if s["run_id"] == p["run_id"])
            bpp = int(srow["gbuffer_bytes"]) // (w * h)
            samp = {r["pass"]: int(r["samples"]) for r in mine}
            want_w = bpp * samp["gbuffer"]
            want_r = bpp * sum(samp.get(k, 0) for k in ("ambient", "directional", "point", "spot"))
            if [int(x) for x in gb] != [want_w + want_r, want_w, want_r]:
                fail(f"G-buffer traffic {gb} != {bpp} B x samples {samp}")
        if not {r["pass"] for r in pa} >= {"sky", "resolve"}: fail(f"passes {sorted({r['pass'] for r in pa})}")
    # convergence.csv: the last point of each trial holds all its frames, and its
    # mean and CI are the summary's
    conv = rows(os.path.join(d, "convergence.csv"), convergence_cols)
    for t in ("1", "2"):
        pts = [c for c in conv if c["trial"] == t]
        if not pts or pts[-1]["frames"] != "30": fail(f"convergence of trial {t}: {pts}")
        if [int(c["frames"]) for c in pts] != sorted(int(c["frames"]) for c in pts):
            fail("convergence frames must grow")
        srow = [r for r in rows(os.path.join(d, "summary.csv"), summary_cols) if r["trial"] == t][0]
        if pts[-1]["frametime_mean_us"] != srow["frametime_mean_us"] or \
           pts[-1]["frametime_ci95_us"] != srow["frametime_ci95_us"]:
            fail(f"convergence end {pts[-1]} vs summary {srow}")
        after = srow["ci1pct_after_s"]
        if after != "" and not (0 < float(after) <= float(pts[-1]["elapsed_s"])):
            fail(f"ci1pct_after_s {after}")
    rs = rows(os.path.join(d, "summary.csv"), summary_cols)
    if len(rs) != 2: fail("per-run summary")
    meta = yaml.safe_load(open(os.path.join(d, "meta.yaml")))
    if meta["run_id"] != p["run_id"] or meta["status"] != "ok": fail(f"meta.yaml {meta}")
    if len(meta["manifest"]["hash"]) != 16: fail("manifest hash")
    if meta["gl"]["backend"] != "egl-surfaceless" or not meta["gl"]["renderer"]: fail("meta gl")
    if not meta["gl"]["debug_context"]: fail("tests run in a debug context")
    if not meta["host"]["cpu"] or meta["host"]["threads"] < 1: fail("meta host")
    if meta["parameters"]["resolution"] != p["resolution"]: fail("meta parameters")
    if meta["parameters"] != {k: v for k, v in p.items() if k not in ("index", "run_id", "shard", "folded")}:
        fail(f"meta parameters differ from plan.csv: {meta['parameters']}")
    for k in ("started", "finished"):
        if not str(meta[k]).endswith("Z"): fail(f"meta {k}")
    # provenance: the manifest verbatim, the command line, the environment that matters,
    # the kernel, the machine's load and memory when the trial started
    src = os.path.join(os.environ["SOURCE_ROOT"], "experiments", "smoke.yaml")
    if meta["manifest"]["text"] != open(src).read(): fail("meta manifest text")
    if meta["manifest"]["description"] != yaml.safe_load(open(src)).get("description", ""):
        fail(f"meta manifest description {meta['manifest']['description']!r}")
    inv = meta["invocation"]
    if not inv["command"].endswith(" run --debug-gl " + src) or inv["cwd"] != os.getcwd():
        fail(f"meta invocation {inv}")
    if meta["environment"].get("SHADESWEEP_GL_DEBUG") != os.environ.get("SHADESWEEP_GL_DEBUG") \
            or "PATH" in meta["environment"] or "HOME" in meta["environment"]:
        fail(f"meta environment {meta['environment']}")
    host = meta["host"]
    if host["kernel"] != os.uname().release or host["cpus_usable"] != ncpus or \
            not host["load_1m_at_start"] >= 0 or \
            not 0 < host["mem_available_mb_at_start"] <= host["mem_total_mb"]:
        fail(f"meta host {host}")
    if not isinstance(meta["shadesweep"]["dirty"], bool): fail("meta shadesweep.dirty")
    pp = meta["pass_plan"]
    if null:
        if pp["passes"] != [{"name": "clear", "run": True, "reason": "clears the output framebuffer"}]:
            fail(f"pass plan {pp}")
        if pp["programs"] != [] or pp["targets"] != [] or pp["gbuffer_bytes"] != 0: fail("pass plan")
    else:
        if not pp["programs"] or not pp["targets"]: fail(f"{p['renderer']} pass plan {pp}")
        if not all(x["reason"] for x in pp["passes"]): fail("every planned pass says why")
        # the scene has point lights only: no spot or directional work is planned
        ran = {x["name"] for x in pp["passes"] if x["run"]}
        if ran & {"spot", "directional"}: fail(f"{p['renderer']} runs passes for absent lights: {ran}")
        if any("spot" in prog or "directional" in prog for prog in pp["programs"]):
            fail(f"{p['renderer']} compiled programs for absent lights: {pp['programs']}")
    for trial in (1, 2):
        png = os.path.join(d, f"screenshot-trial{trial}-t1.5.png")
        with open(png, "rb") as f:
            head = f.read(24)
        if head[:8] != b"\x89PNG\r\n\x1a\n": fail(f"{png} is not a PNG")
        if struct.unpack(">II", head[16:24]) != (w, h): fail(f"{png} size")
left = [p for p in glob.glob(out + "/**", recursive=True) if ".tmp." in p]
if left: fail(f"temporary files left: {left}")
PY
echo "ok"
