"""Any other experiment (the quick-start, the renderer benchmark, a user's sweep): where
shadesweep's ranked table is, and frame time against lights per renderer when the lights
vary within or across its runs."""
import json
import os

from ..plots import styles
from ..text import code, fmt, md_table, md_values
from ..stats import mean, num
from .s003_exp2 import exp2_series


def read_json(path):
    """The object in path, {} when there is none or it is not JSON (an older folder)."""
    try:
        with open(path, encoding="utf-8") as f:
            d = json.load(f)
        return md_values(d) if isinstance(d, dict) else {}   # names go into report.md
    except (OSError, ValueError):
        return {}


def lights_series(run):
    """[(lights, frame time ms, 95% CI ms or None)]: per complete second of seconds.csv
    (mean over trials) when the lights grow within the run, else one point for the run
    from summary.csv (its mean frame time over the trials at lights_count, with its CI)."""
    pts = [(s[1], s[4] / 1000, None) for s in exp2_series(run)
           if s[1] is not None and s[4] is not None]
    if len({x for x, _, _ in pts}) > 1:
        return pts
    m, ci, _ = run.frametime_ms()
    lights = mean(num(r.get("lights_count")) for r in run.ok_rows)
    return [(lights, m, ci)] if m is not None and lights is not None else []


def span(vals):
    """max / min of the positive values (1 with fewer than two)."""
    pos = [v for v in vals if v and v > 0]
    return max(pos) / min(pos) if len(pos) > 1 else 1


def section_generic(s):
    e = s.e
    for f in e.folders:
        md = os.path.join(f, "summary.md")
        js = os.path.join(f, "summary.json")
        if os.path.isfile(md):
            s.w(f"The renderers ranked per sweep point, and where they change places: {code(md)}"
                + (f" (and {code(js)} for scripts)" if os.path.isfile(js) else "") + ".\n")
    for f in e.folders:   # the crossovers, as summary.json has them (runner/crossovers.c)
        cx = read_json(os.path.join(f, "summary.json")).get("crossovers", [])
        if cx:
            s.w(md_table(["along", "where", "faster below", "faster above", "crossing",
                          "95% interval", "differs below / above"],
                         [[c["along"], c["where"] or "-", c["faster_below"], c["faster_above"],
                           f"~{fmt(c['x'], 1)}", f"{fmt(c['x_lo'], 1)} to {fmt(c['x_hi'], 1)}",
                           f"{c['differs_below']} / {c['differs_above']}"] for c in cx]))
    runs = e.measured()
    failed = e.failed()
    if failed:
        s.w("Failed runs (not plotted): " + "; ".join(
            f"{r.id} {r.renderer}: {r.status or 'no result'}"
            for r in failed[:12]) + (" ..." if len(failed) > 12 else "") + ".\n")
    # one line per renderer and value of every other parameter that varies (the lights'
    # count excepted: it is the x axis)
    keys = sorted({k for r in runs for k in r.params})
    vary = [k for k in keys if k not in ("renderer", "lights.count")
            and len({r.param(k) for r in runs}) > 1]
    by, ren = {}, {}
    for r in runs:
        label = " ".join([r.renderer] + [f"{k}={r.param(k)}" for k in vary])
        by.setdefault(label, []).extend(lights_series(r))
        ren[label] = r.renderer
    if not s.plots.plt or not any(len({x for x, _, _ in v}) > 1 for v in by.values()):
        return
    plt = s.plots.plt
    look = styles(list(by), lambda lab: ren[lab])
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for label in sorted(by):
        pts = sorted(by[label], key=lambda p: p[0])
        xs, ys = [x for x, _, _ in pts], [y for _, y, _ in pts]
        colour, marker, line = look[label]
        ax.plot(xs, ys, line, marker=marker, markersize=4, color=colour, label=label)
        if any(c for _, _, c in pts):
            ax.fill_between(xs, [max(y - (c or 0), y * 0.01) for _, y, c in pts],
                            [y + (c or 0) for _, y, c in pts], color=colour, alpha=0.2)
    xs = [x for v in by.values() for x, _, _ in v]
    ys = [y for v in by.values() for _, y, _ in v]
    logx, logy = span(xs) > 10, span(ys) > 10
    if logx:   # lights from 0: symlog keeps the 0 point
        ax.set_xscale("symlog", linthresh=1) if min(xs) <= 0 else ax.set_xscale("log")
    if logy:
        ax.set_yscale("log")
    ax.set_xlabel("lights" + (" (log)" if logx else ""))
    ax.set_ylabel("frame time (ms" + (", log" if logy else "") + "; band = 95% CI)")
    ax.set_title(f"{e.name}: frame time against lights")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    s.w(s.plots.save(fig, f"{e.name}_frametime_lights.png"))
