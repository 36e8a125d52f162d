"""Stochastic light culling's trade (lights.culling, docs/notes/stochastic-culling.md): when
a sweep varies lights.culling_error, each run's image error against its `error:` reference
(summary.csv's image_rmse, the mean over its ok trials) against its time (the metric that
ranks), one line per renderer (and the other keys that vary and it reads) through its
errors in order; an exact run (lights.culling: exact, or an error of 0) is its line's 0."""
from .. import verdicts
from ..plots import styles
from ..stats import mean, num
from ..text import fmt, md_table

KEY = "lights.culling_error"


def culling_error(run):
    """The error the run culled with: 0 when exact; None when its renderer reads no such key."""
    if not verdicts.reads(run.renderer, KEY):
        return None
    if run.param("lights.culling") != "stochastic":
        return 0.0
    return num(run.param(KEY)) or 0.0


def error_against_time(s, runs, values, labels, metric_text):
    """The figure and its table, when the runs vary the culling error; nothing otherwise.
    labels: {run id: its line's label}, made without the culling keys."""
    pts = {}
    for r in runs:
        err, v = culling_error(r), values.get(r.id)
        rmse = mean(num(row.get("image_rmse")) for row in r.ok_rows)
        if err is None or not v or v.get("mean_us") is None:
            continue
        evals = mean(num(row.get("light_evals_per_pixel")) for row in r.ok_rows)
        pts.setdefault(labels[r.id], []).append((err, v["mean_us"] / 1000, rmse, evals,
                                                 r.renderer))
    if len({p[0] for v in pts.values() for p in v}) < 2:
        return
    rows = [[label, fmt(e, 4), fmt(ms, 2), fmt(rm * 255, 3) if rm is not None else "-",
             fmt(ev, 1) if ev is not None else "-"]
            for label in sorted(pts) for e, ms, rm, ev, _ in sorted(pts[label])]
    s.w(f"Stochastic light culling: image error against {metric_text} as "
        f"lights.culling_error varies (0: exact; RMSE against the `error:` reference, in "
        f"1/255):\n")
    s.w(md_table(["line", "culling_error", f"{metric_text} (ms)", "RMSE (1/255)",
                  "light evaluations a pixel"], rows))
    have = {label: sorted(p for p in v if p[2] is not None) for label, v in pts.items()}
    if not any(have.values()):
        s.w("No run has an image error: an `error:` block in the manifest measures it.\n")
        return
    if not s.plots.plt:
        return
    plt = s.plots.plt
    look = styles(list(have), lambda lab: pts[lab][0][4])
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for label in sorted(have):
        line = have[label]
        if not line:
            continue
        colour, marker, dash = look[label]
        ax.plot([p[1] for p in line], [p[2] * 255 for p in line], dash, marker=marker,
                markersize=4, color=colour, label=label)
        for e, ms, rm, _, _ in line:
            ax.annotate(f"{e:g}", (ms, rm * 255), fontsize=6, xytext=(3, 3),
                        textcoords="offset points")
    ax.set_xlabel(f"{metric_text} (ms)")
    ax.set_ylabel("image RMSE against the reference (1/255)")
    ax.set_title(f"{s.e.name}: error against time over lights.culling_error")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    s.w(s.plots.save(fig, f"{s.e.name}_culling_error.png"))
