"""Ours: the six renderers as lights grow (experiments/renderers-tiled.yaml): who is
fastest at each light count and where two renderers change places."""
from .. import verdicts
from ..stats import mean, num
from ..text import fmt, fmt_ci, md_table


ORDER = ["deferred", "forward-mpml", "forward-spml", "forward-plus", "clustered", "tiled-deferred",
         "deferred-lighting"]
PLOT = "renderers-tiled_frametime_lights.png"


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


METRIC_TEXT = {"wall": "frame time", "cpu": "CPU time per frame", "gpu": "GPU time per frame"}


def table(e):
    """({scene: {renderer label: {lights: (mean ms, ci ms, run, n)}}}, metrics): each
    run's value is what measure.metric chose (verdicts.values), the mean over its trials."""
    lvs = {r.param("deferred.light_volumes") for r in e.measured() if r.renderer == "deferred"}
    runs = [r for r in e.measured() if lights_of(r) is not None]
    vals = verdicts.values(runs)
    out, metrics = {}, set()
    for r in runs:
        v = vals.get(r.id)
        if not v or v["mean_us"] is None:
            continue
        metrics.add(v["metric"])
        ci = v["ci95_us"] / 1000 if v["ci95_us"] is not None else None
        out.setdefault(r.scene, {}).setdefault(label(r, lvs), {}).setdefault(
            lights_of(r), (v["mean_us"] / 1000, ci, r, v["trials"]))
    return out, metrics


def rank_key(name):
    base = name.split("/")[0]
    return (ORDER.index(base) if base in ORDER else len(ORDER), name)


def lights_text(c):
    return f"{int(c)}" if c == int(c) else fmt(c, 1)


def _side(rt):
    r = rt.get("ratio")
    if r is None or not r > 0 or r == 1:
        return 0
    return -1 if r < 1 else 1


def _decided(rt, side):
    if rt.get("lo") is None or rt.get("hi") is None:
        return False
    return rt["hi"] < 1 if side < 0 else rt["lo"] > 1


def _worth(ans, x, lead, counts, first, then):
    """The rule of runner/answer/crossovers.c's worth_reporting: the one faster below leads at
    the lower count and the one faster above at the higher, and the evidence holds (both
    ratios' intervals on their side of 1, or a second count on each side agrees)."""
    i, j = x["i"], x["j"]
    if lead.get(counts[i]) != first or lead.get(counts[j]) != then:
        return False
    r = ans["ratios"]
    s0, s1 = _side(r[i]), _side(r[j])
    if _decided(r[i], s0) and _decided(r[j], s1):
        return True
    return i > 0 and _side(r[i - 1]) == s0 and j + 1 < len(r) and _side(r[j + 1]) == s1


def crossovers(by, rens):
    """The crossings worth reporting, as the terminal's (runner/answer/crossovers.c): between
    the renderers that lead on either side, with the evidence to hold them. Returns
    ([(c1, c2, faster before, faster then, answer, crossing)], how many others were
    left out); the crossing lies between light counts c1 and c2, with the interval of
    where it lies (results/verdict.c's verdict_crossover: log time ratio interpolated
    linearly in log lights), and the pair's per-count ratios in answer."""
    lead = {}
    for c in sorted({c for r in rens for c in by[r]}):
        have = sorted((by[r][c][0], r) for r in rens if c in by[r])
        lead[c] = have[0][1]
    pairs, series = [], []
    for i, a in enumerate(rens):
        for b in rens[i + 1:]:
            counts = sorted(set(by[a]) & set(by[b]))
            if len(counts) >= 2:
                pairs.append((a, b, counts))
                series.append([(c, by[a][c][2], by[b][c][2]) for c in counts])
    out, pruned = [], 0
    for (a, b, counts), ans in zip(pairs, verdicts.crossovers(series)):
        for x in ans.get("crossings", []):
            first, then = (a, b) if x["dir"] > 0 else (b, a)
            if _worth(ans, x, lead, counts, first, then):
                out.append((counts[x["i"]], counts[x["j"]], first, then, ans, x))
            else:
                pruned += 1
    return out, pruned


def crossing_text(x):
    est = f"~{fmt(x['x'], 0)}"
    if x["lo"] is None or x["hi"] is None:
        return est + " (interval: beyond the counts run)"
    return est + f" (95%: {fmt(x['lo'], 0)}-{fmt(x['hi'], 0)})"


def section_renderers_tiled(s):
    e = s.e
    data, metrics = table(e)
    what = " or ".join(sorted(METRIC_TEXT.get(m, m) for m in metrics)) or "frame time"
    s.w("No paper table: our own question, which of the renderers is fastest as the lights "
        "grow, and where two of them change places. Tiled and clustered shading as in Harada "
        "2012 (Forward+) and Olsson 2012 (clustered) are context only; no number of theirs is "
        f"compared. Ranked by {what} (measure.metric): the mean over the trials ± 95% CI. "
        "\"Differs\": the ratio of the second fastest to the fastest with its 95% interval, "
        "from shadesweep's trial-level statistics (results/verdict.c, as the ranking and "
        "compare): paired round by round within a sweep point; yes when the interval "
        "excludes 1.\n")
    if not data:
        s.w("No run with a numeric lights.count and a frame time.\n")
        return
    for scene in sorted(data):
        by = data[scene]
        rens = sorted(by, key=rank_key)
        counts = sorted({c for r in rens for c in by[r]})
        rows, wins, asks = [], {}, []
        for c in counts:
            have = sorted((by[r][c][0], r) for r in rens if c in by[r])
            if len(have) >= 2:
                asks.append((by[have[1][1]][c][2], by[have[0][1]][c][2]))
        answers = iter(verdicts.ratios(asks))
        for c in counts:
            have = sorted((by[r][c][0], r) for r in rens if c in by[r])
            cells = [fmt_ci(by[r][c][0], by[r][c][1], 3) if c in by[r] else "-" for r in rens]
            r1 = have[0][1]
            if len(have) >= 2:
                r2 = have[1][1]
                a = next(answers)
                ratio = a.get("ratio") if "error" not in a else None
                extra = [f"**{r1}**", f"{r2} (x{fmt(ratio, 2)})", verdicts.differs_text(a)]
            else:
                extra = [f"**{r1}**", "-", "-"]
            wins.setdefault(r1, []).append(c)
            rows.append([lights_text(c)] + cells + extra)
        s.w(f"**{scene}** ({what}, ms)\n")
        s.w(md_table(["lights"] + rens + ["fastest", "second (its time / fastest's)",
                                          "differs (95% interval)"], rows))
        s.w(f"Fastest on {scene}: " + "; ".join(
            f"{r} at {', '.join(lights_text(c) for c in wins[r])} lights"
            for r in sorted(wins, key=lambda r: min(wins[r]))) + ".\n")
        found = []
        kept, pruned = crossovers(by, rens)
        left = (f" {pruned} other crossing{'s' if pruned != 1 else ''} of renderers that "
                f"do not lead, or with too little evidence, {'is' if pruned == 1 else 'are'} "
                "left out.") if pruned else ""
        for c1, c2, first, then, ans, x in kept:
            f1, t1 = by[first][c1], by[then][c1]
            f2, t2 = by[first][c2], by[then][c2]
            found.append([f"{first} -> {then}", f"{lights_text(c1)}-{lights_text(c2)}",
                          f"{fmt_ci(f1[0], f1[1], 3)} vs {fmt_ci(t1[0], t1[1], 3)}",
                          f"{fmt_ci(f2[0], f2[1], 3)} vs {fmt_ci(t2[0], t2[1], 3)}",
                          " / ".join(ans["ratios"][k]["differs"] for k in (x["i"], x["j"])),
                          crossing_text(x)])
        if found:
            s.w(f"Crossovers on {scene}: where the fastest renderer changes, between the last "
                "light count where the first leads and the next count where the second does "
                "(both intervals on their side of 1, or a second count on each side agrees; the "
                "times ms, first vs second, at both counts). The crossing interpolates the log "
                "time ratio linearly in log(lights) between those two counts, an estimate, "
                "not a measurement; its 95% interval is where the ratio's interval bounds "
                f"cross 1, interpolated the same way.{left}\n")
            s.w(md_table(["faster first -> faster then", "between lights",
                          "at the lower count", "at the higher count",
                          "differs at lower / higher", "crossing (interpolated) lights"], found))
        else:
            s.w(f"Crossovers on {scene}: none; the fastest renderer does not change over the "
                f"light counts run.{left}\n")
    if s.plots.plt:
        plt = s.plots.plt
        scenes = sorted(data)
        fig, axes = plt.subplots(1, len(scenes), figsize=(6.5 * len(scenes), 4.8), squeeze=False)
        cmap = plt.get_cmap("tab10")
        names = sorted({r for sc in scenes for r in data[sc]}, key=rank_key)
        color = {r: cmap(i % 10) for i, r in enumerate(names)}
        for ax, scene in zip(axes[0], scenes):
            for r in sorted(data[scene], key=rank_key):
                pts = sorted(((c, v) for c, v in data[scene][r].items() if c > 0),
                             key=lambda p: p[0])
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
            ax.set_ylabel(f"{what} ms (log; band = 95% CI)")
            ax.grid(alpha=0.3, which="both")
            ax.legend(fontsize=7)
        s.w(s.plots.save(fig, PLOT))
