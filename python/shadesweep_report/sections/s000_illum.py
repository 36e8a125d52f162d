"""Seed 000: forward illumination sets (5.6)."""
from .. import verdicts
from ..text import fmt, fmt_ci, md_table, ratio


# ---- seed 000 illumination sets

def section_s000_illum(s):
    e, ref = s.e, s.ref
    fwd = e.renderer_for("forward-mpml")
    tab = "5.6 Forward Shading Illumination Sets"
    rows, got = [], {}
    for val, cond in (("true", "illumination_sets=on"), ("false", "illumination_sets=off")):
        pv = ref.value(experiment="s000-illumination-sets", table=tab, condition=cond, metric="frametime_ms")
        runs = e.select(renderer=fwd, forward__illumination_sets=val)
        if runs:
            r = runs[0]
            m, ci, n = r.frametime_ms()
            dc, _, _ = r.agg("draw_calls_mean")
            w, h = r.size
            rows.append([cond.split("=")[1], fmt(pv, 1), f"{w}x{h}", fmt_ci(m, ci, 2), fmt(dc, 1), n])
            got[val] = (pv, m, ci, dc, r)
        else:
            rows.append([cond.split("=")[1], fmt(pv, 1), "-", "not run", "-", "-"])
            got[val] = (pv, None, None, None, None)
    s.w("Ours: mean frame time over trials ± 95% CI, and draw_calls_mean.\n")
    s.w(md_table(["illumination sets", "frame time ms (paper, 1024x768)", "ours at",
                  "frame time ms (ours)", "draw calls (ours)", "trials"], rows))
    pr = ratio(got["false"][0], got["true"][0])
    on, off = got["true"], got["false"]
    if on[1] is None or off[1] is None:
        v, otxt = "n/a (not run)", "-"
    else:
        a = verdicts.ratios([(off[4], on[4])])[0]   # off / on, results/verdict.c
        rr = a.get("ratio") if "error" not in a else None
        if rr is None:
            v = "n/a (no ratio)"
        else:
            v = "yes" if rr >= 1.2 and a["differs"] == "yes" else "partly" if rr > 1 else "no"
        otxt = (f"x{fmt(rr, 2)} ({fmt(off[1], 2)} vs {fmt(on[1], 2)} ms"
                + verdicts.within_text(a).replace(" (", "; ", 1).rstrip(")") + ")")
    s.claim("illumination sets make forward faster (27 -> 19.6 ms; yes: x1.2 or more and "
            "its 95% interval excludes 1, partly: faster by less)", f"x{fmt(pr, 2)}", otxt, v)
    s.claims_table()
