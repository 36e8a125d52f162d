"""Ours: anti-aliasing and translucency (experiments/aa-translucency.yaml, issue 12, and
experiments/aa-cost.yaml, its cost table): frame time against the error left on the
edges, the cost of MSAA per renderer family, and what translucency costs (the frame time
of `translucency: blend` against `opaque` where the sweep has both, else the translucent
pass's timer)."""
import math

from ..stats import mean, num
from ..text import fmt, fmt_ci, md_table


ORDER = ["forward-spml", "forward-mpml", "deferred", "deferred-lighting", "forward-plus",
         "clustered", "tiled-deferred"]
# seed 000 6.5 and seed 003 section 2 name AA as deferred's cost; Olsson and Assarsson's
# tiled study (ANCHORS.md) split tiled shading into forward and deferred
FAMILY = {"forward-spml": "forward", "forward-mpml": "forward", "deferred": "deferred",
          "forward-plus": "tiled forward", "clustered": "tiled forward",
          "tiled-deferred": "tiled deferred", "deferred-lighting": "deferred"}
FAMILIES = ["forward", "deferred", "tiled forward", "tiled deferred"]
PLOT = "aa-translucency_error_time.png"


def rank(r):
    return ORDER.index(r) if r in ORDER else len(ORDER)


def config(run):
    """(msaa, aa) of a run; msaa as an int (1 when the plan has no msaa column)."""
    m = num(run.param("msaa"))
    return (int(m) if m is not None else 1, run.param("aa") or "none")


def collect(e, translucency="blend"):
    """{scene: {renderer: {(msaa, aa): (ms, ci ms, rmse, edge rmse, translucent ms)}}} of
    the runs with that `translucency` (blend, the default, or opaque)"""
    out = {}
    for r in e.measured():
        if (r.param("translucency") or "blend") != translucency:
            continue
        ms, ci, _ = r.frametime_ms()
        if ms is None:
            continue
        rmse = mean(v for v in r.col("image_rmse") if v is not None)
        edge = mean(v for v in r.col("image_edge_rmse") if v is not None)
        p = r.passes() or {}
        tr = p.get("translucent", {}).get("gpu_us")
        out.setdefault(r.scene, {}).setdefault(r.renderer, {})[config(r)] = (
            ms, ci, rmse, edge, tr / 1000 if tr is not None else None)
    return out


def err_text(v):
    return "-" if v is None else f"{v * 255:.2f}"


def section_aa_translucency(s):
    e = s.e
    data = collect(e)
    has_error = any(v[2] is not None for sc in data.values() for rr in sc.values()
                    for v in rr.values())
    s.w("No paper table: our own measurement of the two costs every seed names for deferred "
        "shading (seed 000 6.5: anti-aliasing \"trivial to enable ... using forward shading\"; "
        "seed 001 19.8.1: translucent geometry drawn forward after the deferred pass). Frame "
        "time: mean over trials ± 95% CI. "
        + ("Error: against forward-spml rendered at 4x the width and height and box-filtered "
           "down (`error.reference.supersample: 4`), in 1/255 steps: RMSE over the image and "
           "over the reference's edge pixels (`image_edge_rmse`), the mean over trials of each "
           "trial's worst comparison.\n" if has_error else
           "These runs have no error reference (experiments/aa-cost.yaml times what "
           "aa-translucency.yaml also measures the error of).\n"))
    if not data:
        s.w("No run with a frame time.\n")
        return
    for scene in sorted(data):
        by = data[scene]
        rows = []
        for ren in sorted(by, key=rank):
            for (m, aa), (ms, ci, rmse, edge, _) in sorted(by[ren].items()):
                rows.append([ren, str(m), aa, fmt_ci(ms, ci, 3), err_text(rmse), err_text(edge)])
        s.w(f"**{scene}**\n")
        s.w(md_table(["renderer", "msaa", "aa", "frame time ms", "RMSE /255",
                      "edge RMSE /255"], rows))
    # the cost of MSAA per family: frame time at msaa M over msaa 1, aa none
    ms_vals = sorted({m for sc in data.values() for rr in sc.values() for (m, _a) in rr if m > 1})
    if ms_vals:
        s.w("**The cost of MSAA per renderer family** (frame time at msaa N / at msaa 1, "
            "aa none; the family's mean over its renderers and the scenes; in brackets, "
            "edge RMSE at msaa N / at msaa 1).\n")
        rows = []
        for fam in FAMILIES:
            cells = []
            for m in ms_vals:
                t, q = [], []
                for sc in data.values():
                    for ren, rr in sc.items():
                        if FAMILY.get(ren) != fam:
                            continue
                        a, b = rr.get((1, "none")), rr.get((m, "none"))
                        if a and b and a[0] and b[0]:
                            t.append(b[0] / a[0])
                            if a[3] and b[3] is not None:
                                q.append(b[3] / a[3])
                cells.append("-" if not t else f"x{fmt(mean(t), 2)}"
                             + (f" ({fmt(mean(q), 2)})" if q else ""))
            rows.append([fam] + cells)
        s.w(md_table(["family"] + [f"msaa {m}" for m in ms_vals], rows))
        # Olsson and Assarsson: tiled forward 1.5-2x faster than tiled deferred at 4x MSAA
        if 4 in ms_vals:
            for sc_name, sc in sorted(data.items()):
                td = sc.get("tiled-deferred", {}).get((4, "none"))
                fp = [sc.get(r, {}).get((4, "none")) for r in ("forward-plus", "clustered")]
                fp = [x for x in fp if x]
                if td and fp:
                    best = min(fp, key=lambda x: x[0])
                    x = td[0] / best[0]   # yes: 1.5x or more; partly: faster, by less
                    s.claim(f"{sc_name}: tiled forward faster than tiled deferred at 4x MSAA",
                            "1.5-2x (Olsson and Assarsson, 1,024 lights, GTX 480)",
                            f"x{fmt(x, 2)}", "yes" if x >= 1.5 else "partly" if x > 1 else "no")
    # aa: edge against none at msaa 1
    rows = []
    for scene in sorted(data):
        for ren in sorted(data[scene], key=rank):
            a, b = data[scene][ren].get((1, "none")), data[scene][ren].get((1, "edge"))
            if a and b:
                rows.append([scene, ren, f"x{fmt(b[0] / a[0], 2)}",
                             f"{err_text(a[3])} -> {err_text(b[3])}"])
    if rows:
        s.w("**Edge-detect AA** (seed 001 19.5.2, msaa 1): frame time with aa: edge / without, "
            "and the edge RMSE without -> with.\n")
        s.w(md_table(["scene", "renderer", "frame time", "edge RMSE /255"], rows))
    # translucency: blend against opaque where the sweep has both
    opaque = collect(e, "opaque")
    rows = []
    for scene in sorted(set(data) & set(opaque)):
        for ren in sorted(data[scene], key=rank):
            for key in sorted(data[scene][ren]):
                a, b = data[scene][ren][key], opaque[scene].get(ren, {}).get(key)
                if b is None or key[1] != "none":
                    continue
                ci = (math.hypot(a[1], b[1]) if a[1] is not None and b[1] is not None
                      else None)   # the two means' CIs, independent
                rows.append([scene, ren, str(key[0]), fmt_ci(a[0], a[1], 1),
                             fmt_ci(b[0], b[1], 1), fmt_ci(a[0] - b[0], ci, 1),
                             f"x{fmt(a[0] / b[0], 2)}"])
    if rows:
        s.w("**What translucency costs** (aa none): the frame time with the scene's "
            "translucent materials blended (`translucency: blend`, the translucent pass) "
            "and with the same objects opaque (`translucency: opaque`, drawn in the opaque "
            "passes), and the difference. A scene without translucent materials has the "
            "same work in both: its difference is the measurement's noise.\n")
        s.w(md_table(["scene", "renderer", "msaa", "blend ms", "opaque ms",
                      "difference ms", "blend / opaque"], rows))
    # the translucent pass's share of the frame, by its timer
    rows = []
    for scene in sorted(data):
        for ren in sorted(data[scene], key=rank):
            v = data[scene][ren].get((1, "none"))
            if v and v[4] is not None:
                rows.append([scene, ren, fmt(v[4], 3), f"{fmt(100 * v[4] / v[0], 1)}%"])
    if rows:
        s.w("**The translucent pass's timer** (msaa 1, aa none): its GPU time "
            "(GL_TIME_ELAPSED, median per frame) and its share of the frame time. Every "
            "renderer draws the translucent objects with the same forward pass after its "
            "opaque work. A driver that defers its rasterisation (llvmpipe bins a frame's "
            "draws and rasterises them when it flushes) charges the work to whichever pass "
            "is open then, so on it the difference above is the measure.\n")
        s.w(md_table(["scene", "renderer", "translucent pass ms", "of the frame"], rows))
    s.claims_table()
    has_edge = any(v[3] is not None for sc in data.values() for rr in sc.values()
                   for v in rr.values())
    if not has_edge:
        s.w("No plot of frame time against edge error: these runs have no error reference.\n")
    elif s.plots.plt:
        plt = s.plots.plt
        scenes = sorted(data)
        fig, axes = plt.subplots(1, len(scenes), figsize=(6 * len(scenes), 4.6), squeeze=False)
        cmap = plt.get_cmap("tab10")
        rens = sorted({r for sc in data.values() for r in sc}, key=rank)
        color = {r: cmap(i % 10) for i, r in enumerate(rens)}
        marker = {"none": "o", "edge": "^"}
        for ax, scene in zip(axes[0], scenes):
            for ren in sorted(data[scene], key=rank):
                pts = sorted(data[scene][ren].items())
                for aa in ("none", "edge"):
                    xy = [(v[3] * 255, v[0], m) for (m, a), v in pts if a == aa and v[3] is not None]
                    if not xy:
                        continue
                    ax.plot([p[0] for p in xy], [p[1] for p in xy], marker[aa] + "-",
                            color=color[ren], markersize=4, alpha=0.85,
                            label=f"{ren} ({'edge AA' if aa == 'edge' else 'no AA'})")
                    for x, y, m in xy:
                        ax.annotate(f"{m}x", (x, y), fontsize=6, xytext=(2, 2),
                                    textcoords="offset points")
            ax.set_yscale("log")
            ax.set_title(scene)
            ax.set_xlabel("edge RMSE against the 4x supersampled reference (1/255)")
            ax.set_ylabel("frame time ms (log)")
            ax.grid(alpha=0.3, which="both")
            ax.legend(fontsize=6)
        s.w(s.plots.save(fig, PLOT))
