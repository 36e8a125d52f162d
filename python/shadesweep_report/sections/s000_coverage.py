"""Seed 000: spot-light coverage (5.4.1, 5.4.2)."""
from ..loading import norm
from .. import verdicts
from ..text import fmt, fmt_ci, md_table


# ---- seed 000 coverage

def section_s000_coverage(s, table, scene):
    e, ref = s.e, s.ref
    fwd = e.renderer_for("forward-mpml")
    s.w("camera.hold 0 is the paper's small coverage, 1 the large. Ours: fps_mean and the mean "
        "frame time over trials ± 95% CI; coverage = mean share of the screen each light covers "
        "(coverage.csv), where recorded.\n")
    def hold_key(x):
        try:
            return (0, float(x))
        except ValueError:
            return (1, x)
    holds = sorted({norm(r.param("camera.hold")) for r in e.measured()}, key=hold_key)
    rows, got = [], {}
    label = {repr(0.0): "small", repr(1.0): "large"}
    for h in holds or [repr(0.0), repr(1.0)]:
        cov = label.get(h)
        row = [f"{cov.capitalize() if cov else '(no paper row)'} screen space coverage (hold {h})"]
        covs = []
        for pren, ren in (("deferred", "deferred"), ("forward-mpml", fwd)):
            p = [ref.value(experiment=e.name, table=table, renderer=pren, condition=f"coverage={cov}", metric=m)
                 for m in ("fps", "frametime_ms")] if cov else [None, None]
            row.append(f"{fmt(p[0], 0)} fps / {fmt(p[1], 1)} ms" if p[0] is not None else "-")
            runs = [r for r in e.select(renderer=ren) if norm(r.param("camera.hold")) == h]
            if runs:
                f, _, _ = runs[0].fps()
                m, ci, _ = runs[0].frametime_ms()
                row.append(f"{fmt(f, 1)} fps / {fmt_ci(m, ci, 2)} ms")
                c = runs[0].coverage()
                if c:
                    covs.append(f"{ren}: " + ", ".join(f"light {k} {fmt(v, 3)}" for k, v in sorted(c.items())))
                got[(cov, pren)] = (p[1], m, ci, runs[0])
            else:
                row.append("not run")
                got[(cov, pren)] = (p[1], None, None, None)
        row.append("; ".join(covs) if covs else "-")
        rows.append(row)
    s.w(f"**{table}** ({scene})\n")
    s.w(md_table(["Configuration", "Deferred (paper)", "Deferred (ours)", "Forward (paper)",
                  "Forward (ours)", "coverage (ours)"], rows))

    def get(src, cov, pren):
        x = got.get((cov, pren), (None, None, None))
        return x[0] if src == "paper" else x[1]

    def txt(src, a, b, ra, rb):
        x, y = get(src, a, ra), get(src, b, rb)
        return f"{fmt(x, 2)} vs {fmt(y, 2)} ms" if x is not None and y is not None else "-"

    def sig(a, b):   # a / b of two runs, results/verdict.c
        ra, rb = got.get(a, (None,) * 4)[3], got.get(b, (None,) * 4)[3]
        return "" if None in (ra, rb) else verdicts.within_text(verdicts.ratios([(ra, rb)])[0])
    od_s, od_l = get("ours", "small", "deferred"), get("ours", "large", "deferred")
    v = "n/a (not run)" if None in (od_s, od_l) else "yes" if od_l > od_s else "no"
    s.claim("deferred costs more with larger coverage (frame time small vs large)",
            txt("paper", "small", "large", "deferred", "deferred"),
            txt("ours", "small", "large", "deferred", "deferred") + sig(("small", "deferred"), ("large", "deferred")), v)
    for cov, want in (("small", "deferred"), ("large", "forward-mpml")):
        d, f = get("ours", cov, "deferred"), get("ours", cov, "forward-mpml")
        if None in (d, f):
            v = "n/a (not run)"
        else:
            v = "yes" if (d < f) == (want == "deferred") else "no"
        s.claim(f"{cov} coverage: {'deferred' if want == 'deferred' else 'forward'} is faster "
                "(deferred vs forward frame time)",
                txt("paper", cov, cov, "deferred", "forward-mpml"),
                txt("ours", cov, cov, "deferred", "forward-mpml") + sig((cov, "deferred"), (cov, "forward-mpml")), v)
    s.claims_table()
