"""Any other experiment (the quick-start, the renderer benchmark, a user's sweep): where
shadesweep's ranked table is, and frame time against lights per renderer when the lights
vary within or across its runs."""
import os

from ..plots import COLORS
from ..stats import mean, num
from .s003_exp2 import exp2_series


def lights_series(run):
    """[(lights, frame time ms)]: per complete second of seconds.csv (mean over trials)
    when the lights grow within the run, else one point for the run from summary.csv
    (its mean frame time at lights_count)."""
    pts = [(s[1], s[4] / 1000) for s in exp2_series(run) if s[1] is not None and s[4] is not None]
    if len({x for x, _ in pts}) > 1:
        return pts
    m, _, _ = run.frametime_ms()
    lights = mean(num(r.get("lights_count")) for r in run.ok_rows)
    return [(lights, m)] if m is not None and lights is not None else []


def section_generic(s):
    e = s.e
    for f in e.folders:
        md = os.path.join(f, "summary.md")
        if os.path.isfile(md):
            s.w(f"The renderers ranked per sweep point: `{md}`.\n")
    runs = e.measured()
    # one line per renderer and value of every other parameter that varies (the lights'
    # count excepted: it is the x axis)
    keys = sorted({k for r in runs for k in r.params})
    vary = [k for k in keys if k not in ("renderer", "lights.count")
            and len({r.param(k) for r in runs}) > 1]
    by, color = {}, {}
    for r in runs:
        label = " ".join([r.renderer] + [f"{k}={r.param(k)}" for k in vary])
        by.setdefault(label, []).extend(lights_series(r))
        color[label] = COLORS.get(r.renderer) if not vary else None
    if not s.plots.plt or not any(len({x for x, _ in v}) > 1 for v in by.values()):
        return
    plt = s.plots.plt
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for label in sorted(by):
        pts = sorted(by[label])
        ax.plot([x for x, _ in pts], [y for _, y in pts], "o-", markersize=3,
                color=color[label], label=label)
    ax.set_xlabel("lights")
    ax.set_ylabel("frame time (ms)")
    ax.set_title(f"{e.name}: frame time against lights")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    s.w(s.plots.save(fig, f"{e.name}_frametime_lights.png"))
