"""Ours: G-buffer layout, image error against frame time."""
import os

from ..loading import read_csv
from ..stats import linfit, mean, num
from ..text import fmt, fmt_ci, md_table, nan


# ---- ours: G-buffer error against frame time

def pareto(points):
    """Indices of the points no other point beats in both coordinates (lower is better)."""
    front = []
    for i, (x, y) in enumerate(points):
        if x is None or y is None:
            continue
        if not any((x2 <= x and y2 <= y) and (x2 < x or y2 < y)
                   for j, (x2, y2) in enumerate(points) if j != i and x2 is not None and y2 is not None):
            front.append(i)
    return front


def own_position(runs):
    """How a preset keeps the position when gbuffer.position is `preset`, from the G-buffer
    targets its runs' meta.yaml lists (pass_plan.targets: "gbuffer.<fields>" and their
    formats): stored (the formats of the attachments with position fields), as linear depth
    in an attachment, or rebuilt from the depth buffer."""
    for r in runs:
        plan = r.meta().get("pass_plan")
        targets = plan.get("targets") if isinstance(plan, dict) else None
        if not isinstance(targets, list):
            continue
        gb = [(str(t.get("name", "")), str(t.get("format", "")).upper()) for t in targets
              if isinstance(t, dict) and str(t.get("name", "")).startswith("gbuffer.")]
        fields = [(name[len("gbuffer."):].split("+"), fmt_) for name, fmt_ in gb]
        stored = [f for fl, f in fields if any(x.startswith("position") for x in fl)]
        if stored:
            return "stored, " + " + ".join(stored)
        depth = [f for fl, f in fields if "depth" in fl]
        if depth:
            return "linear depth, " + depth[0]
        return "rebuilt from the depth buffer"
    return "unknown (no meta.yaml)"


def errors_rows(run):
    """errors.csv rows of the run's ok trials."""
    rows = read_csv(os.path.join(run.dir, "errors.csv")) or []
    ok = {r.get("trial") for r in run.ok_rows}
    return [r for r in rows if r.get("trial") in ok]


def position_storage(s, e):
    """The position axis of the study: per scene and preset, the error with the position
    as the preset keeps it, stored in 16-bit floats, and rebuilt from the depth buffer;
    the worst over light-volume modes and comparisons."""
    acc, own = {}, {}
    for r in e.measured():
        pos = r.param("gbuffer.position")
        if r.renderer != "deferred" or pos not in ("preset", "stored16", "depth"):
            continue
        preset = r.param("gbuffer.preset")
        if pos == "preset":
            own.setdefault(preset, []).append(r)
        a = acc.setdefault((r.scene, preset, pos), [[], [], []])
        for x in errors_rows(r):
            a[0].append(num(x.get("rmse")))
            a[1].append(num(x.get("max_abs")))
            a[2].append(num(x.get("frac_over_1_255")))
    if not acc:
        return
    s.w("**Where the position comes from.** The same presets with the position as the preset "
        "keeps it, stored in 16-bit floats (`gbuffer.position: stored16`) and rebuilt from the "
        "24-bit depth buffer (`depth`): the worst RMSE and the largest error (in 1/255 steps) "
        "over every comparison and light-volume mode, and the largest fraction of pixels off by "
        "more than 1/255.\n")
    # the worst RMSE, max error and fraction over 1/255 of each (scene, preset, position)
    worst = {k: tuple(max((v for v in col if v is not None), default=None) for col in a)
             for k, a in acc.items()}

    def cell(k):
        rm, mx, fr = worst.get(k, (None, None, None))
        if rm is None:
            return "-"
        return f"{rm:.3g} / {round((mx or 0) * 255)} / {100 * (fr or 0):.3f}%"
    for scene in sorted({k[0] for k in acc}):
        presets = sorted({k[1] for k in acc if k[0] == scene})
        rows = [[p, own_position(own.get(p, [])), cell((scene, p, "preset")),
                 cell((scene, p, "stored16")), cell((scene, p, "depth"))] for p in presets]
        s.w(f"*{scene}* (RMSE / max error in 1/255 / pixels over 1/255)\n")
        s.w(md_table(["preset", "its own position", "as the preset keeps it", "stored16",
                      "depth"], rows))
        ratios = []
        for p in presets:
            r16 = worst.get((scene, p, "stored16"), (None,))[0]
            rd = worst.get((scene, p, "depth"), (None,))[0]
            if r16 and rd:
                ratios.append((p, r16 / rd))
        if ratios:
            s.w(f"On {scene}, a 16-bit stored position gives "
                + ", ".join(f"{q:.2f}x ({p})" for p, q in ratios)
                + " the RMSE of the position rebuilt from depth.\n")


# ---- seed 002's bandwidth model beside the frame time

MB = 1e6   # bytes; seed 002's GB/s are 10^9 bytes (1024 x 768 x 60 = 0.05 G)


def follows(fit):
    """The answer to "does time follow the bytes?" from a fit (a, b, r2) of frame time on
    G-buffer bytes: yes when the bytes explain at least 80% of the variance with a positive
    slope, partly from 50%, else no; None without a fit."""
    if fit is None:
        return None
    a, b, r2 = fit
    if b > 0 and r2 >= 0.8:
        return "yes"
    if b > 0 and r2 >= 0.5:
        return "partly"
    return "no"


def follows_sentence(where, n, fit):
    """One sentence with the verdict and the numbers it comes from."""
    if fit is None:
        return (f"Does time follow the bytes {where}? Cannot say: fewer than three "
                "configurations, or all with the same bytes per frame.")
    a, b, r2 = fit
    v = follows(fit)
    head = {"yes": "Yes", "partly": "Partly", "no": "No"}[v]
    how = ("more bytes, more time" if b > 0 else "more bytes, less time" if b < 0
           else "no slope at all")
    return (f"Does time follow the bytes {where}? **{head}**: over {n} configurations the "
            f"least-squares line time = {a:.3g} ms + {b:.3g} ms per MB ({how}) explains "
            f"{100 * r2:.0f}% of the frame time's variance (R^2 = {r2:.3f}).")


def bandwidth(s, e):
    """Per configuration, seed 002's G-buffer bytes per frame (summary.csv's
    gbuffer_bytes_per_frame and its write / read split) beside the frame time; the fit of
    time on bytes per scene and over the study, and the verdict it gives."""
    pts = []   # scene, label, written MB, read MB, MB per frame, frame time ms, ci
    for r in e.measured():
        b = mean(r.col("gbuffer_bytes_per_frame"))
        if b is None:
            continue
        lv = r.param("deferred.light_volumes") if r.renderer == "deferred" else ""
        gb = r.rows[0].get("gbuffer") or r.param("gbuffer.preset")
        label = f"{gb}/{lv}" if lv else f"{r.renderer} {gb}".strip()
        m, ci, _ = r.frametime_ms()
        wr, rd = mean(r.col("gbuffer_write_bytes_mean")), mean(r.col("gbuffer_read_bytes_mean"))
        pts.append((r.scene, label, None if wr is None else wr / MB,
                    None if rd is None else rd / MB, b / MB, m, ci))
    s.w("**Seed 002's bandwidth model.** The bytes the G-buffer pass writes and the light "
        "passes read per frame, by the MRT terms of seed 002's equations 4 and 5 "
        "(n_MRT x MRT_BPP x W x H x Sorting written, n_MRT x MRT_BPP x W x H x n read): "
        "the layout's bytes per pixel times the samples (GL_SAMPLES_PASSED) of the G-buffer "
        "pass and of the light passes (summary.csv's gbuffer_bytes_per_frame = "
        "gbuffer_write_bytes_mean + gbuffer_read_bytes_mean; MB = 10^6 bytes), beside the "
        "measured frame time, and the least-squares line time = a + b x bytes.\n")
    if not pts:
        s.w("No gbuffer_bytes_per_frame in summary.csv (no G-buffer renderer, or a folder "
            "written before the column).\n")
        return
    rows = [[p[0], p[1], fmt(p[2], 3), fmt(p[3], 3), fmt(p[4], 3), fmt_ci(p[5], p[6], 3)]
            for p in sorted(pts, key=lambda p: (p[0], p[4]))]
    s.w(md_table(["scene", "configuration", "MB written", "MB read", "MB per frame",
                  "frame time ms"], rows))
    fits = []
    for scene in sorted({p[0] for p in pts}) + [None]:
        sel = [p for p in pts if scene is None or p[0] == scene]
        fit = linfit([p[4] for p in sel], [p[5] for p in sel])
        n = len([p for p in sel if p[5] is not None])
        fits.append((scene, n, fit))
    s.w(md_table(["scene", "configurations", "a (ms)", "b (ms per MB)", "R^2", "time follows the bytes"],
                 [["all" if sc is None else sc, n, "-" if f is None else f"{f[0]:.3g}",
                   "-" if f is None else f"{f[1]:.3g}", "-" if f is None else f"{f[2]:.3f}",
                   follows(f) or "-"] for sc, n, f in fits]))
    scenes = [f for f in fits if f[0] is not None]
    _, n_all, fit_all = fits[-1]
    s.w(follows_sentence("across the study", n_all, fit_all)
        + ("" if len(scenes) < 2 else " Per scene: " + "; ".join(
            f"{sc} {follows(f) or 'cannot say'}" + ("" if f is None else f" (R^2 = {f[2]:.3f})")
            for sc, _, f in scenes) + ".") + "\n")
    if s.plots.plt:
        plt = s.plots.plt
        fig, ax = plt.subplots(figsize=(7, 5))
        cmap = plt.get_cmap("tab10")
        for i, (scene, _, fit) in enumerate(scenes):
            sel = [p for p in pts if p[0] == scene and p[5] is not None]
            ax.plot([p[4] for p in sel], [p[5] for p in sel], "o", color=cmap(i % 10),
                    label=scene)
            if fit:
                xs = [min(p[4] for p in sel), max(p[4] for p in sel)]
                ax.plot(xs, [fit[0] + fit[1] * x for x in xs], "-", color=cmap(i % 10),
                        linewidth=1, label=f"{scene}: fit, R^2 = {fit[2]:.2f}")
        ax.set_xlabel("G-buffer MB per frame (seed 002 eq. 4 + 5, MRT terms)")
        ax.set_ylabel("frame time (ms)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        s.w(s.plots.save(fig, "gbuffer-error_bandwidth.png"))


def section_gbuffer_error(s):
    e = s.e
    s.w("No paper table: our own question, what each G-buffer layout and light-volume mode "
        "costs in image error against what it saves in frame time. One point per configuration "
        "(scene x G-buffer as summary.csv's gbuffer column names it, preset[/position][/normal], "
        "x light volumes): mean frame time over trials (± 95% CI) "
        "and the worst image_rmse of its trials against the error block's reference. The Pareto "
        "front (nothing both faster and more exact) is marked.\n")
    by_scene = {}
    for r in e.measured():
        lv = r.param("deferred.light_volumes") if r.renderer == "deferred" else ""
        gb = r.rows[0].get("gbuffer") or (r.param("gbuffer.preset") if r.renderer == "deferred" else "")
        label = f"{gb}/{lv}" if r.renderer == "deferred" else r.renderer
        m, ci, n = r.frametime_ms()
        rm = [x for x in r.col("image_rmse") if x is not None]
        ps = [x for x in r.col("image_psnr_db") if x is not None]
        preset = (r.param("gbuffer.preset") or gb.split("/")[0]) if r.renderer == "deferred" else r.renderer
        by_scene.setdefault(r.scene, []).append((label, m, ci, max(rm) if rm else None,
                                                 min(ps) if ps else None, n, r.size, preset, lv))
    for scene in sorted(by_scene):
        pts = by_scene[scene]
        front = set(pareto([(p[1], p[3]) for p in pts]))
        rows = [[p[0], f"{p[6][0]}x{p[6][1]}", fmt_ci(p[1], p[2], 3), "-" if p[3] is None else f"{p[3]:.3g}",
                 fmt(p[4], 1), p[5], "yes" if i in front else ""] for i, p in enumerate(pts)]
        order = sorted(range(len(pts)), key=lambda i: (i not in front, nan(pts[i][1])))
        rows = [rows[i] for i in order]
        s.w(f"**{scene}**\n")
        s.w(md_table(["configuration", "resolution", "frame time ms", "image RMSE (worst)",
                      "PSNR dB (worst)", "trials", "Pareto front"], rows))
        if all(p[3] is None for p in pts):
            s.w("No image_rmse in summary.csv (did the manifest have an error: block?).\n")
    position_storage(s, e)
    if s.plots.plt and by_scene:
        plt = s.plots.plt
        scenes = sorted(by_scene)
        fig, axes = plt.subplots(1, len(scenes), figsize=(7 * len(scenes), 5.5), squeeze=False)
        presets = sorted({p[7] for sc in scenes for p in by_scene[sc]})
        modes = sorted({p[8] for sc in scenes for p in by_scene[sc]})
        cmap = plt.get_cmap("tab10")
        color = {k: cmap(i % 10) for i, k in enumerate(presets)}
        marks = "osD^vP*X<>"
        marker = {k: marks[i % len(marks)] for i, k in enumerate(modes)}
        for ax, scene in zip(axes[0], scenes):
            pts = [p for p in by_scene[scene] if p[1] is not None and p[3] is not None]
            front = set(pareto([(p[1], p[3]) for p in pts]))
            for i, p in enumerate(pts):
                ax.errorbar([p[1]], [p[3]], xerr=[[min(p[2] or 0, p[1])], [p[2] or 0]],
                            fmt=marker[p[8]], color=color[p[7]], ecolor=color[p[7]],
                            elinewidth=0.6, alpha=1.0 if i in front else 0.45, capsize=1.5,
                            markersize=7 if i in front else 5,
                            markeredgecolor="black" if i in front else color[p[7]])
            for k, i in enumerate(sorted(front, key=lambda i: pts[i][1])):
                ax.annotate(pts[i][0], (pts[i][1], pts[i][3]), fontsize=7,
                            textcoords="offset points", xytext=(6, 6 if k % 2 == 0 else -12))
            ys = [p[3] for p in pts if p[3] > 0]
            if ys and len(ys) == len(pts) and max(ys) / min(ys) > 20:
                ax.set_yscale("log")
            fp = sorted((pts[i][1], pts[i][3]) for i in front)
            if fp:
                ax.step([x for x, _ in fp], [y for _, y in fp], where="post", color="black",
                        linewidth=1, label="Pareto front (labelled)")
            for k in presets:
                ax.plot([], [], "o", color=color[k], label=f"G-buffer {k}")
            for k in modes:
                ax.plot([], [], marker[k], color="gray", label=f"light volumes {k or '-'}")
            ax.legend(fontsize=7)
            ax.set_title(scene)
            ax.set_xlabel("frame time (ms, ± 95% CI as in the tables)")
            ax.set_ylabel("image RMSE against the reference (worst trial)")
            ax.grid(alpha=0.3)
        s.w(s.plots.save(fig, "gbuffer-error_pareto.png"))
    bandwidth(s, e)
