"""Seed 000: frame time against resolution (5.3.1, 5.3.2)."""
from ..plots import COLORS, paper_vs_ours
from ..stats import linfit, num
from ..text import fmt, fmt_ci, md_table, nan, ratio
from .. import verdicts


# ---- seed 000 resolution

S0_RES_TABLES = [("canyon", "5.3.1 Exterior Scene", ""),
                 ("interior", "5.3.2 Interior Scene (Shadows Enabled)", "shadows=on")]


def sorted_sizes(runs):
    return sorted({r.size for r in runs}, key=lambda wh: (wh[0] * wh[1], wh[0]))


def section_s000_resolution(s):
    e, ref = s.e, s.ref
    fwd = e.renderer_for("forward-mpml")
    paper_res = [(800, 600), (1024, 768), (1280, 960), (1600, 1200)]
    s.w("Rows are matched by position in each list of resolutions sorted by pixel count: "
        "our smallest with the paper's 800x600, and so on. Ours: mean over trials of fps_mean "
        "and of the mean frame time ± its 95% CI (see the top of the report).\n")
    data = {}
    for scene, tab, cond in S0_RES_TABLES:
        runs = e.select(scene=scene)
        sizes = sorted_sizes(runs)
        if sizes and sizes != paper_res:
            s.w(f"{scene}: ours at {', '.join(f'{w}x{h}' for w, h in sizes)} "
                f"(the paper: {', '.join(f'{w}x{h}' for w, h in paper_res)}).\n")
        if len(sizes) > len(paper_res):
            s.w(f"{scene}: more resolutions than the paper's; the extra ones have no paper row.\n")
        rows = []
        d = {"paper": {}, "ours": {}}
        for i in range(max(len(paper_res), len(sizes))):
            row = []
            if i < len(paper_res):
                pw, ph = paper_res[i]
                row.append(f"{pw} x {ph}" + (f" / ours {sizes[i][0]}x{sizes[i][1]}" if i < len(sizes) else ""))
            else:
                pw = ph = None
                row.append(f"- / ours {sizes[i][0]}x{sizes[i][1]}")
            for pren, ren in (("deferred", "deferred"), ("forward-mpml", fwd)):
                g = lambda m: ref.value(experiment="s000-resolution", table=tab, scene=scene,
                                        renderer=pren, width=pw, height=ph, metric=m) if pw else None
                pf, pm = g("fps"), g("frametime_ms")
                row.append("-" if pf is None else f"{fmt(pf, 0)} fps / {fmt(pm, 1)} ms")
                d["paper"].setdefault(pren, []).append((pw * ph if pw else None, pf, pm))
                rr = [r for r in runs if r.renderer == ren and i < len(sizes) and r.size == sizes[i]]
                if rr:
                    f, _, _ = rr[0].fps()
                    m, ci, n = rr[0].frametime_ms()
                    row.append(f"{fmt(f, 1)} fps / {fmt_ci(m, ci, 2)} ms")
                    d["ours"].setdefault(pren, []).append((sizes[i][0] * sizes[i][1], f, m, ci))
                else:
                    row.append("-")
            rows.append(row)
        data[scene] = d
        s.w(f"**{tab}** ({scene})\n")
        s.w(md_table(["Resolution (paper / ours)", "Deferred (paper)", "Deferred (ours)",
                      "Forward (paper)", "Forward (ours)"], rows))

    def ratios(d):
        """forward/deferred FPS per position."""
        dd, ff = d.get("deferred", []), d.get("forward-mpml", [])
        return [ratio(f[1], x[1]) for x, f in zip(dd, ff)]

    def r2(d):
        pts = [(p[0], p[2]) for p in d.get("deferred", []) if p[0] and p[2] is not None]
        fit = linfit([p[0] for p in pts], [p[1] for p in pts])
        return fit[2] if fit else None

    for scene, tab, _ in S0_RES_TABLES:
        pr = ratios(data[scene]["paper"])
        orr = [x for x in ratios(data[scene]["ours"]) if x is not None]
        ptxt = "forward/deferred FPS: " + ", ".join("x" + fmt(x, 2) for x in pr)
        otxt = "forward/deferred FPS: " + ", ".join("x" + fmt(x, 2) for x in orr) if orr else "not run"
        if scene == "canyon":
            if not orr:
                v = "n/a (not run)"
            elif all(x > 1 for x in orr):
                v = "yes" if len(orr) >= 2 and orr[-1] > orr[0] else "partly"
            else:
                v = "partly" if any(x > 1 for x in orr) else "no"
            s.claim("canyon: forward faster at every resolution, by more as resolution grows "
                    "(x2.78, 'almost three times', at 1600x1200) (yes: faster everywhere and the "
                    "ratio at the highest above that at the lowest; partly: faster everywhere but "
                    "the gap does not grow, or faster only at some)", ptxt, otxt, v)
        else:
            if not orr:
                v = "n/a (not run)"
            elif all(x < 1 for x in orr):
                inv = [1 / x for x in orr]
                v = "yes" if len(inv) >= 2 and inv[-1] < max(inv[:-1]) else "partly"
            else:
                v = "partly" if any(x < 1 for x in orr) else "no"
            s.claim("interior: deferred faster at every resolution, the gap narrowing at the highest "
                    "(6.4: 'begin to converge' beyond 1280x960) (yes: faster everywhere and the "
                    "deferred/forward ratio at the highest below its largest at a lower one; partly: "
                    "faster everywhere but no narrowing, or faster only at some)", ptxt, otxt, v)
        pr2, or2 = r2(data[scene]["paper"]), r2(data[scene]["ours"])
        if or2 is None:
            v = "n/a (not run)" if not orr else "n/a (fewer than 3 resolutions)"
        else:
            v = "yes" if or2 >= 0.9 else "partly" if or2 >= 0.75 else "no"
        s.claim(f"{scene}: deferred's frame time grows about linearly with the pixel count "
                "(R² of a line through frame time against pixels; yes: >= 0.9)",
                f"R² {fmt(pr2, 3)}", f"R² {fmt(or2, 3)}" if or2 is not None else "-", v)
    s.claims_table()

    # breakdowns: the paper's per unit, ours per pass
    s.w("**Performance breakdowns.** The paper's NVPerfHUD times per pipeline unit have no "
        "counterpart here (no vertex/pixel/texture/raster-op counters); ours are the median GPU "
        "time per frame of each pass (passes.csv, timer queries), by the same positions.\n")
    any_soft = False
    for scene, tab, _ in S0_RES_TABLES:
        for pren in ("deferred", "forward-mpml"):
            ren = "deferred" if pren == "deferred" else fwd
            rows = []
            prows = ref.get(experiment="s000-resolution", table=tab + " breakdown", scene=scene, renderer=pren)
            runs = e.select(scene=scene, renderer=ren)
            sizes = sorted_sizes(e.select(scene=scene))
            passes_by = []
            for sz in sizes:
                rr = [r for r in runs if r.size == sz]
                passes_by.append(rr[0].passes() if rr else None)
            names = []
            for p in passes_by:
                for k in (p or {}):
                    if not k.startswith("_") and k not in names:
                        names.append(k)
            for i, (pw, ph) in enumerate(paper_res):
                row = [f"{pw} x {ph}"]
                for m in ("vertex_shader_ms", "pixel_shader_ms", "texture_unit_ms", "raster_ops_ms"):
                    vv = [num(r["value"]) for r in prows if r["metric"] == m and r["width"] == str(pw)]
                    row.append(fmt(vv[0], 1) if vv else "-")
                row.append(f"{sizes[i][0]}x{sizes[i][1]}" if i < len(sizes) else "-")
                p = passes_by[i] if i < len(passes_by) else None
                row.append(", ".join(f"{k} {fmt(p[k]['gpu_us'] / 1000, 2) if p[k]['gpu_us'] is not None else '-'}"
                                     for k in names if k in p) if p else "-")
                rows.append(row)
            # a CPU rasterizer's pass times are marked (verdicts.UNATTRIBUTED)
            soft = any(not verdicts.pass_times_attributed(r) for r in runs if r.passes())
            s.w(f"{scene}, {pren}{'' if ren == pren else ' (ours: ' + ren + ')'}:\n")
            s.w(md_table(["Resolution", "Vertex Shader ms", "Pixel Shader ms", "Texture Unit ms",
                          "Raster Ops ms", "ours at", "ours: GPU ms per pass"
                          + (" (not attributed)" if soft else "")], rows))
            any_soft |= soft
    if any_soft:
        s.w(verdicts.UNATTRIBUTED + "\n")

    if s.plots.plt:
        plt = s.plots.plt
        fig, axes = plt.subplots(1, 2, figsize=(11, 4))
        for scene, _, _ in S0_RES_TABLES:
            for pren in ("deferred", "forward-mpml"):
                ls = "-" if scene == "canyon" else "--"
                p = data[scene]["paper"].get(pren, [])
                axes[0].plot([x[0] / 1e6 for x in p if x[0]], [nan(x[2]) for x in p if x[0]], ls,
                             marker="o", color=COLORS[pren], label=f"{scene} {pren}")
                o = data[scene]["ours"].get(pren, [])
                if o:
                    axes[1].errorbar([x[0] / 1e6 for x in o], [nan(x[2]) for x in o],
                                     yerr=[x[3] or 0 for x in o], fmt=ls + "o", color=COLORS[pren],
                                     capsize=3, label=f"{scene} {pren if pren == 'deferred' else fwd}")
        paper_vs_ours(axes, "paper (seed 000, GeForce 6800)", "ours (error bars: 95% CI)",
                      "megapixels", "frame time (ms)")
        s.w(s.plots.save(fig, "s000-resolution_frametime.png"))
