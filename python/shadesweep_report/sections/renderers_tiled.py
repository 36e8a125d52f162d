"""Ours: the six renderers as lights grow (experiments/renderers-tiled.yaml): who is
fastest at each light count and where two renderers change places."""
import math

from ..stats import mean, num, sd, t975
from ..text import fmt, fmt_ci, md_table
from .base import ci_overlap


ORDER = ["deferred", "forward-mpml", "forward-spml", "forward-plus", "clustered", "tiled-deferred"]
PLOT = "renderers-tiled_frametime_lights.png"


def welch(a, b):
    """Welch's t-test on two samples (the trial means): (t, df, significant at 5%, two-sided).
    None with fewer than two values in either. Two samples without spread are significantly
    different when their means differ."""
    a = [x for x in a if x is not None]
    b = [x for x in b if x is not None]
    if len(a) < 2 or len(b) < 2:
        return None
    qa, qb = sd(a) ** 2 / len(a), sd(b) ** 2 / len(b)
    diff = mean(a) - mean(b)
    if qa + qb == 0:
        return (math.inf if diff else 0.0), None, diff != 0
    t = diff / math.sqrt(qa + qb)
    den = (qa * qa / (len(a) - 1) if qa else 0.0) + (qb * qb / (len(b) - 1) if qb else 0.0)
    df = (qa + qb) ** 2 / den
    return t, df, abs(t) > t975(df)


def welch_text(w):
    if w is None:
        return "cannot say (fewer than 2 trials)"
    t, df, sig = w
    return (f"{'yes' if sig else 'no'} (t = {fmt(abs(t), 2)}"
            + (f", df = {fmt(df, 1)}" if df is not None else ", no spread") + ")")


def sig(a, b):
    """yes / no / ? for Welch's test of two samples of trial means."""
    w = welch(a, b)
    return "?" if w is None else ("yes" if w[2] else "no")


def label(run, lvs):
    """The renderer, with deferred's light-volume mode when the study has several."""
    if run.renderer == "deferred" and len(lvs) > 1:
        return f"deferred/{run.param('deferred.light_volumes')}"
    return run.renderer


def lights_of(run):
    c = num(run.param("lights.count"))
    if c is None:
        c = mean(num(r.get("lights_count")) for r in run.ok_rows)
    return c


def table(e):
    """{scene: {renderer label: {lights: (mean ms, ci ms, [trial means ms], n)}}}."""
    lvs = {r.param("deferred.light_volumes") for r in e.measured() if r.renderer == "deferred"}
    out = {}
    for r in e.measured():
        c = lights_of(r)
        if c is None:
            continue
        m, ci, n = r.frametime_ms()
        if m is None:
            continue
        trials = [v / 1000 for v in r.col("frametime_mean_us") if v is not None]
        out.setdefault(r.scene, {}).setdefault(label(r, lvs), {}).setdefault(c, (m, ci, trials, n))
    return out


def rank_key(name):
    base = name.split("/")[0]
    return (ORDER.index(base) if base in ORDER else len(ORDER), name)


def lights_text(c):
    return f"{int(c)}" if c == int(c) else fmt(c, 1)


def crossovers(by, a, b):
    """Where a and b change places: [(c1, c2, faster before, faster after, est)] over the
    light counts both ran, in order (equal means are skipped); est interpolates log frame
    time linearly on log(lights) (on lights when c1 is 0)."""
    counts = sorted(set(by[a]) & set(by[b]))
    pts = [(c, by[a][c][0], by[b][c][0]) for c in counts if by[a][c][0] != by[b][c][0]]
    out = []
    for (c1, a1, b1), (c2, a2, b2) in zip(pts, pts[1:]):
        if (a1 < b1) == (a2 < b2):
            continue
        d1, d2 = math.log(a1 / b1), math.log(a2 / b2)
        f = d1 / (d1 - d2)
        if c1 > 0:
            est = math.exp(math.log(c1) + f * (math.log(c2) - math.log(c1)))
        else:
            est = c1 + f * (c2 - c1)
        first, then = (a, b) if a1 < b1 else (b, a)
        out.append((c1, c2, first, then, est))
    return out


def section_renderers_tiled(s):
    e = s.e
    s.w("No paper table: our own question, which of the renderers is fastest as the lights "
        "grow, and where two of them change places. Tiled and clustered shading as in Harada "
        "2012 (Forward+) and Olsson 2012 (clustered) are context only; no number of theirs is "
        "compared. Frame time: mean over trials ± 95% CI (as everywhere in this report). "
        "\"Significantly faster\": Welch's t-test on the trial means of the fastest and the "
        "second fastest, two-sided at 5%; whether their 95% CIs overlap is shown beside it.\n")
    data = table(e)
    if not data:
        s.w("No run with a numeric lights.count and a frame time.\n")
        return
    for scene in sorted(data):
        by = data[scene]
        rens = sorted(by, key=rank_key)
        counts = sorted({c for r in rens for c in by[r]})
        rows, wins = [], {}
        for c in counts:
            have = sorted((by[r][c][0], r) for r in rens if c in by[r])
            cells = [fmt_ci(by[r][c][0], by[r][c][1], 3) if c in by[r] else "-" for r in rens]
            if len(have) >= 2:
                (m1, r1), (m2, r2) = have[0], have[1]
                w = welch(by[r1][c][2], by[r2][c][2])
                cis = (by[r1][c][1], by[r2][c][1])
                ov = ("-" if None in cis else
                      "yes" if ci_overlap((m1, cis[0]), (m2, cis[1])) else "no")
                extra = [f"**{r1}**", f"{r2} (x{fmt(m2 / m1, 2)})", welch_text(w), ov]
            else:
                r1 = have[0][1]
                extra = [f"**{r1}**", "-", "-", "-"]
            wins.setdefault(r1, []).append(c)
            rows.append([lights_text(c)] + cells + extra)
        s.w(f"**{scene}** (frame time ms)\n")
        s.w(md_table(["lights"] + rens + ["fastest", "second (its time / fastest's)",
                                          "significantly faster (Welch)", "CIs overlap"], rows))
        s.w(f"Fastest on {scene}: " + "; ".join(
            f"{r} at {', '.join(lights_text(c) for c in wins[r])} lights"
            for r in sorted(wins, key=lambda r: min(wins[r]))) + ".\n")
        found = []
        for i, a in enumerate(rens):
            for b in rens[i + 1:]:
                for c1, c2, first, then, est in crossovers(by, a, b):
                    f1, t1 = by[first][c1], by[then][c1]
                    f2, t2 = by[first][c2], by[then][c2]
                    found.append([f"{first} -> {then}", f"{lights_text(c1)}-{lights_text(c2)}",
                                  f"{fmt_ci(f1[0], f1[1], 3)} vs {fmt_ci(t1[0], t1[1], 3)}",
                                  f"{fmt_ci(f2[0], f2[1], 3)} vs {fmt_ci(t2[0], t2[1], 3)}",
                                  " / ".join(sig(by[first][c][2], by[then][c][2]) for c in (c1, c2)),
                                  f"~{fmt(est, 0)}"])
        if found:
            s.w(f"Crossovers on {scene}: each pair whose order changes, between the last light "
                "count where the first is faster and the next count where the second is (the "
                "frame times ms, first vs second, at both counts); the crossing is an "
                "interpolation of log frame time, linear in log(lights), between those two "
                "counts, not a measurement.\n")
            s.w(md_table(["faster first -> faster then", "between lights",
                          "at the lower count", "at the higher count",
                          "significant at lower / higher (Welch)",
                          "crossing (interpolated) lights"], found))
        else:
            s.w(f"Crossovers on {scene}: none; no two renderers change places over the light "
                "counts run.\n")
    if s.plots.plt:
        plt = s.plots.plt
        scenes = sorted(data)
        fig, axes = plt.subplots(1, len(scenes), figsize=(6.5 * len(scenes), 4.8), squeeze=False)
        cmap = plt.get_cmap("tab10")
        names = sorted({r for sc in scenes for r in data[sc]}, key=rank_key)
        color = {r: cmap(i % 10) for i, r in enumerate(names)}
        for ax, scene in zip(axes[0], scenes):
            for r in sorted(data[scene], key=rank_key):
                pts = sorted((c, v) for c, v in data[scene][r].items() if c > 0)
                xs = [c for c, _ in pts]
                m = [v[0] for _, v in pts]
                ci = [v[1] or 0.0 for _, v in pts]
                ax.plot(xs, m, "o-", markersize=3, color=color[r], label=r)
                ax.fill_between(xs, [max(a - b, a * 0.01) for a, b in zip(m, ci)],
                                [a + b for a, b in zip(m, ci)], color=color[r], alpha=0.2)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_title(scene)
            ax.set_xlabel("lights (log; a count of 0 is not drawn)")
            ax.set_ylabel("frame time ms (log; band = 95% CI)")
            ax.grid(alpha=0.3, which="both")
            ax.legend(fontsize=7)
        s.w(s.plots.save(fig, PLOT))
