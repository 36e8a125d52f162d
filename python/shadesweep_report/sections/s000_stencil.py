"""Seed 000: the stencil-masked light hull (5.5)."""
from ..text import fmt, fmt_ci, md_table, ratio
from .. import verdicts


# ---- seed 000 stencil

def section_s000_stencil(s):
    e, ref = s.e, s.ref
    tab = "5.5 Deferred Shading Stencil Lighting Optimisation"
    s.w("Ours: the spot-light pass of passes.csv (median GPU time, mean draw calls and mean shaded "
        "samples per frame, the samples from GL_SAMPLES_PASSED, which counts on every driver); where "
        "the driver gave no timer results the difference of the mean frame times stands in. The "
        "paper's baseline without the stencil mask is its unoptimised hull (4.5.8): our `hull` mode "
        "(`volume`, which rejects by depth, where an older folder has no `hull`).\n")
    modes = [m for m in e.values("deferred.light_volumes") if m]
    rows, got = [], {}
    timer_missing = False
    no_spot = []
    for mode in modes:
        runs = e.select(renderer="deferred", deferred__light_volumes=mode)
        base = "hull" if "hull" in modes else "volume"
        cond = {"stencil-two-pass": "stencil=on", "stencil": "stencil=on", base: "stencil=off"}.get(mode)
        pg = ref.value(experiment="s000-stencil", table=tab, condition=cond, metric="gpu_ms") if cond else None
        pdc = ref.value(experiment="s000-stencil", table=tab, condition=cond, metric="draw_calls") if cond else None
        if mode == "stencil" and "stencil-two-pass" in modes:
            pg = pdc = None   # the paper's two-pass hull is stencil-two-pass
        if not runs:
            rows.append([mode, fmt(pg, 2), fmt(pdc, 0), "not run", "-", "-", "-", "-"])
            continue
        r = runs[0]
        p = r.passes() or {}
        spot = p.get("spot")
        if spot is None:
            no_spot.append(mode)
        gpu = spot["gpu_us"] / 1000 if spot and spot["gpu_us"] is not None else None
        dc = spot["draw_calls"] if spot else None
        smp = spot.get("samples") if spot else None
        timer_missing |= spot is not None and gpu is None
        ft, ci, _ = r.frametime_ms()
        w, h = r.size
        rows.append([mode, fmt(pg, 2), fmt(pdc, 0), f"{w}x{h}", fmt(gpu, 3), fmt(dc, 1),
                     fmt(smp, 0), fmt_ci(ft, ci, 3)])
        got[mode] = (gpu, dc, ft, ci, smp)
    soft = any(not verdicts.pass_times_attributed(r) for m in modes
               for r in e.select(renderer="deferred", deferred__light_volumes=m)[:1] if r.passes())
    s.w(md_table(["light volumes (ours)", "GPU ms (paper, 1024x768)", "draw calls (paper)",
                  "ours at", "spot pass GPU ms (ours" + (", not attributed)" if soft else ")"),
                  "spot pass draw calls (ours)", "spot pass samples (ours)",
                  "frame time ms (ours)"], rows))
    if soft:
        s.w(verdicts.UNATTRIBUTED + "\n")
    on = got.get("stencil-two-pass") or got.get("stencil")
    off = got.get("hull") or got.get("volume")
    pg_on = ref.value(experiment="s000-stencil", table=tab, condition="stencil=on", metric="gpu_ms")
    pg_off = ref.value(experiment="s000-stencil", table=tab, condition="stencil=off", metric="gpu_ms")
    if no_spot:
        s.w(f"No \"spot\" pass in passes.csv of {', '.join(no_spot)} (a scene without a spot "
            "light, or outputs.frames off): the spot-pass claims cannot be checked.\n")
    if on and off and no_spot:
        v, otxt = "n/a (no spot pass)", "-"
    elif on and off:
        if on[0] is not None and off[0] is not None:
            rr, how = ratio(off[0], on[0]), f"spot pass {fmt(off[0], 3)} vs {fmt(on[0], 3)} ms"
        else:
            d = off[2] - on[2]
            rr = ratio(off[2], on[2])
            how = (f"no timer results: frame time {fmt(off[2], 3)} vs {fmt(on[2], 3)} ms "
                   f"(difference {fmt(d, 3)} ms)")
        v = "yes" if rr is not None and rr >= 2 else "partly" if rr is not None and rr > 1 else "no"
        if timer_missing and rr is not None and 1 < rr < 2:
            v = "partly"
        otxt = f"x{fmt(rr, 2)}: {how}"
        # the pixels shaded decide the claim's cause: the mask must remove (nearly) all of
        # the hull's samples, whatever the timer says
        if on[4] is not None and off[4] is not None:
            otxt += f"; samples {fmt(off[4], 0)} vs {fmt(on[4], 0)}"
            if not off[4] >= 10 * on[4] or off[4] == 0:
                v = "no" if v == "no" else "partly"
    else:
        v, otxt = "n/a (not run)", "-"
    s.claim("the stencil mask makes a floating spot light's hull far cheaper (0.16 vs ~2 ms; "
            "yes: x2 or more in time and 10x fewer shaded samples, partly: faster by less, or "
            "the samples not 10x fewer)", f"x{fmt(ratio(pg_off, pg_on), 1)}", otxt, v)
    pd_on = ref.value(experiment="s000-stencil", table=tab, condition="stencil=on", metric="draw_calls")
    pd_off = ref.value(experiment="s000-stencil", table=tab, condition="stencil=off", metric="draw_calls")
    if no_spot:
        v, otxt = "n/a (no spot pass)", "-"
    elif on and off and on[1] is not None and off[1] is not None:
        v = ("yes" if round(on[1]) == pd_on and round(off[1]) == pd_off
             else "partly" if on[1] > off[1] else "no")
        otxt = f"{fmt(on[1], 1)} vs {fmt(off[1], 1)}"
    else:
        v, otxt = "n/a (not run)", "-"
    s.claim("the stencil hull takes 2 draw calls, the plain one 1 (per light)",
            f"{fmt(pd_on, 0)} vs {fmt(pd_off, 0)}", otxt, v)
    s.claims_table()
