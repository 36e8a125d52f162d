"""Any other experiment (the quick-start, the renderer benchmark, a user's sweep): who
wins at each sweep point and where they change places (summary.json, as the run printed
them), and the metric that ranks against lights per configuration when the lights vary
within or across its runs, and (culling_error.py) image error against time when the
runs vary lights.culling_error."""
import json
import os

from .. import verdicts
from .culling_error import error_against_time
from ..loading import read_csv
from ..plots import styles
from ..text import code, fmt, md_table, md_values
from ..stats import ci95, mean, num


METRIC_TEXT = {"wall": "frame time", "cpu": "CPU time per frame", "gpu": "GPU time per frame"}
FRAME_COLUMN = {"cpu": "cpu_us", "gpu": "gpu_us", "wall": "frametime_us"}


def read_json(path):
    """The object in path, {} when there is none or it is not JSON (an older folder)."""
    try:
        with open(path, encoding="utf-8") as f:
            d = json.load(f)
        return md_values(d) if isinstance(d, dict) else {}   # names go into report.md
    except (OSError, ValueError):
        return {}


def metric_of(run):
    """What ranks the run: summary.csv's `metric` (wall in a folder written before it)."""
    return next((r["metric"] for r in run.rows if r.get("metric")), "wall")


def growth_series(run, metric):
    """[(lights, ms, 95% CI ms or None)] when the lights grow within the run, as the
    crossovers read it (runner/answer/crossovers.c): per trial, the mean of the metric's
    frames.csv column over the frames drawn at each count; per count, the mean over the
    trials and its t interval over them (none under 3 trials). [] without frames.csv or
    with one count."""
    rows = read_csv(os.path.join(run.dir, "frames.csv")) or []
    col = FRAME_COLUMN.get(metric, "frametime_us")
    ok = {r.get("trial") for r in run.ok_rows}
    acc = {}
    for r in rows:
        lights, v = num(r.get("lights")), num(r.get(col))
        if r.get("trial") in ok and lights is not None and v is not None:
            acc.setdefault(lights, {}).setdefault(r.get("trial"), []).append(v)
    if len(acc) < 2:
        return []
    out = []
    for lights in sorted(acc):
        per = [mean(v) for v in acc[lights].values()]
        ci = ci95(per) if len(per) >= 3 else None
        out.append((lights, mean(per) / 1000, ci / 1000 if ci is not None else None))
    return out


def lights_series(run, metric, value):
    """[(lights, ms, 95% CI ms or None)] of the metric that ranks: per light count when the
    lights grow within the run, else one point for the run: value, shadesweep's mean over
    its trials and 95% t interval (verdicts.values: the table's numbers) at lights_count."""
    pts = growth_series(run, metric)
    if pts:
        return pts
    lights = mean(num(r.get("lights_count")) for r in run.ok_rows)
    if not value or value.get("mean_us") is None or lights is None:
        return []
    ci = value.get("ci95_us")
    return [(lights, value["mean_us"] / 1000, ci / 1000 if ci is not None else None)]


def line_labels(runs, axes=("lights.count",)):
    """{run id: its line's label}: the renderer and the values of the keys that vary across
    runs (but the axes: the lights' count, the x axis) and that it reads; a key only other
    renderers read would name a difference that is not there."""
    keys = sorted({k for r in runs for k in r.params})
    vary = [k for k in keys if k != "renderer" and k not in axes
            and len({r.param(k) for r in runs}) > 1]
    return {r.id: " ".join([r.renderer] + [f"{k}={r.param(k)}" for k in vary
                                           if verdicts.reads(r.renderer, k)]) for r in runs}


def span(vals):
    """max / min of the positive values (1 with fewer than two)."""
    pos = [v for v in vals if v and v > 0]
    return max(pos) / min(pos) if len(pos) > 1 else 1


def section_generic(s):
    e = s.e
    for f in e.folders:
        ranked = os.path.join(f, "summary.md")
        js = os.path.join(f, "summary.json")
        if os.path.isfile(ranked):
            s.w(f"The renderers ranked per sweep point, and where they change places: "
                f"{code(ranked)}"
                + (f" (and {code(js)} for scripts)" if os.path.isfile(js) else "") + ".\n")
    for f in e.folders:   # who wins and where that changes, as summary.json has them
        d = read_json(os.path.join(f, "summary.json"))
        said = [(p.get("label", ""), p["verdict"]) for p in d.get("points", [])
                if p.get("verdict")]
        if said:
            s.w(f"Verdicts, by {METRIC_TEXT.get(d.get('metric'), 'the metric that ranks')}:\n")
            s.w("".join(f"- {label}: {v}\n" for label, v in said))
        cx = d.get("crossovers", [])
        if cx:
            s.w(md_table(["along", "where", "fastest below", "fastest above", "crossing",
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
    metrics = {metric_of(r) for r in runs}   # one, but for folders measured apart
    metric = metrics.pop() if len(metrics) == 1 else "wall"
    values = verdicts.values(runs)
    error_against_time(s, runs, values,
                       line_labels(runs, ("lights.culling", "lights.culling_error")),
                       METRIC_TEXT.get(metric, metric))
    by, ren, labels = {}, {}, line_labels(runs)
    for r in runs:
        label = labels[r.id]
        by.setdefault(label, []).extend(lights_series(r, metric, values.get(r.id)))
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
    what = METRIC_TEXT.get(metric, metric)
    ax.set_xlabel("lights" + (" (log)" if logx else ""))
    ax.set_ylabel(f"{what} (ms" + (", log" if logy else "") + "; band = 95% CI over trials)")
    ax.set_title(f"{e.name}: {what} against lights")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    s.w(s.plots.save(fig, f"{e.name}_frametime_lights.png"))
