"""Seed 003, experiment 1: three scenes at 160 lights (Tables 1-6)."""
from ..stats import ci95, mean, num, sd
from ..text import fmt, md_table, ratio


# ---- seed 003, experiment 1

S3_TABLES = [("curtis-scene1", "Table 1", "Table 2"), ("curtis-scene2", "Table 3", "Table 4"),
             ("curtis-scene3", "Table 5", "Table 6")]


def per_second_stats(run):
    """Per trial: mean and SD of the per-second FPS and frame time (complete seconds);
    falls back to summary.csv when there is no seconds.csv. Returns ({trial: (fps_m, fps_sd,
    ft_m, ft_sd)}, method)."""
    secs = run.seconds()
    out = {}
    if secs:
        for t, rows in secs.items():
            use = [r for r in rows if r.get("complete") == "1"]
            if not use:
                use = [r for r in rows if (num(r.get("frames")) or 0) > 0]
            fps = [num(r.get("fps")) for r in use]
            ft = [num(r.get("frametime_mean_us")) for r in use]
            out[t] = (mean(fps), sd(fps), mean(ft), sd(ft))
        return out, "seconds.csv"
    for r in run.ok_rows:
        out[int(r["trial"])] = (num(r.get("fps_mean")), None, num(r.get("frametime_mean_us")),
                                num(r.get("frametime_sd_us")))
    return out, "summary.csv (no seconds.csv: SD per frame, not per second)"


def section_s003_exp1(s):
    e, ref = s.e, s.ref
    fwd = e.renderer_for("forward-spml")
    scenes_have = sorted({r.scene for r in e.measured()})
    mapping = {}
    for scene, _, _ in S3_TABLES:
        if scene in scenes_have:
            mapping[scene] = scene
    if not mapping and len(scenes_have) == 3:
        mapping = {p[0]: o for p, o in zip(S3_TABLES, scenes_have)}
        e.notes.append("scene names differ from curtis-scene1..3; matched by sorted order: "
                       + ", ".join(f"{a} = {b}" for a, b in mapping.items()))
    s.w("Per trial: the mean over the seconds of the run of the per-second FPS (frames that "
        "ended in the second) and of the per-second mean frame time, as the paper averages "
        "per second; \"Average Total\" is the mean of the trials; \"Average Standard Deviation\" "
        "the mean over trials of each trial's SD of its per-second values. Only complete "
        "seconds count. Ours also: the 95% CI of the mean over trials (Student t).\n")
    results = {}
    for scene, tab_fps, tab_ft in S3_TABLES:
        ours_scene = mapping.get(scene)
        stats = {}
        for ren, pren in (("deferred", "deferred"), (fwd, "forward-spml")):
            runs = e.select(renderer=ren, scene=ours_scene) if ours_scene else []
            if runs:
                st, method = per_second_stats(runs[0])
                stats[pren] = (st, method, runs[0])
        results[scene] = stats
        for tab, metric, idx, nd, label in ((tab_fps, "fps", 0, 3, "FPS average fps"),
                                            (tab_ft, "frametime_us", 2, 1, "FT average µs")):
            sdm = "fps_sd" if metric == "fps" else "frametime_sd_us"
            s.w(f"**{tab}** ({scene}{'' if ours_scene in (None, scene) else ' = ours ' + ours_scene}, "
                f"{'FPS' if metric == 'fps' else 'frame time, µs'}; paper | ours)\n")
            ntr = max([3] + [len(v[0]) for v in stats.values()])
            rows = []
            for t in range(1, ntr + 1):
                row = [str(t)]
                for pren in ("deferred", "forward-spml"):
                    row.append(fmt(ref.value(experiment="s003-exp1", table=tab, renderer=pren,
                                             condition=f"trial={t}", metric=metric), nd))
                    st = stats.get(pren)
                    row.append(fmt(st[0][t][idx], nd) if st and t in st[0] else "-")
                rows.append(row)
            avg = ["Average Total"]
            sdr = ["Average Standard Deviation"]
            cir = ["95% CI of the mean over trials"]
            for pren in ("deferred", "forward-spml"):
                avg.append(fmt(ref.value(experiment="s003-exp1", table=tab, renderer=pren,
                                         condition="trial=average", metric=metric), nd))
                sdr.append("± " + fmt(ref.value(experiment="s003-exp1", table=tab, renderer=pren,
                                               condition="trial=average", metric=sdm), nd))
                cir.append("")
                st = stats.get(pren)
                if st:
                    means = [v[idx] for v in st[0].values()]
                    sds = [v[idx + 1] for v in st[0].values()]
                    avg.append(fmt(mean(means), nd))
                    sdr.append("± " + fmt(mean(sds), nd) if mean(sds) is not None else "-")
                    cir.append("± " + fmt(ci95(means), nd) if ci95(means) is not None else "-")
                else:
                    avg.append("not run")
                    sdr.append("-")
                    cir.append("-")
            rows += [avg, sdr, cir]
            s.w(md_table(["Test Number", f"Deferred {label} (paper)", "Deferred (ours)",
                          f"Forward {label} (paper)", "Forward (ours)"], rows))
        methods = {v[1] for v in stats.values()}
        if any(m != "seconds.csv" for m in methods):
            s.w(f"Ours for {scene} from " + "; ".join(sorted(methods)) + ".\n")
        # our per-trial CIs as summary.csv gives them
        cis = []
        for pren, v in stats.items():
            run = v[2]
            for r in run.ok_rows:
                cis.append(f"{pren} trial {r['trial']}: {fmt(num(r.get('frametime_mean_us')), 1)} "
                           f"± {fmt(num(r.get('frametime_ci95_us')), 1)} µs")
        if cis:
            s.w("summary.csv, frame time per frame with its 95% CI (batch means): " + "; ".join(cis) + ".\n")

    def avgs(src, scene, pren):
        """(fps mean, fps sd, ft mean, ft sd) averaged over trials, paper or ours."""
        if src == "paper":
            tf, tt = [x for x in S3_TABLES if x[0] == scene][0][1:]
            g = lambda tab, m: ref.value(experiment="s003-exp1", table=tab, renderer=pren,
                                         condition="trial=average", metric=m)
            return g(tf, "fps"), g(tf, "fps_sd"), g(tt, "frametime_us"), g(tt, "frametime_sd_us")
        st = results.get(scene, {}).get(pren)
        if not st:
            return None
        vals = list(st[0].values())
        return tuple(mean(v[i] for v in vals) for i in range(4))

    def describe(a):
        if a is None:
            return None, "not run"
        d, f = a
        if None in (d[0], f[0], d[2], f[2]):
            return None, "-"
        win_fps = "deferred" if d[0] > f[0] else "forward"
        win_ft = "deferred" if d[2] < f[2] else "forward"
        txt = (f"deferred {fmt(d[0], 1)} vs forward {fmt(f[0], 1)} fps (x{fmt(ratio(d[0], f[0]), 2)}); "
               f"{fmt(d[2], 0)} vs {fmt(f[2], 0)} µs")
        return (win_fps, win_ft, d, f), txt

    for scene, _, _ in S3_TABLES:
        both = {}
        for src in ("paper", "ours"):
            d, f = avgs(src, scene, "deferred"), avgs(src, scene, "forward-spml")
            both[src] = describe(None if d is None or f is None else (d, f))
        (pw, ptxt), (ow, otxt) = both["paper"], both["ours"]
        if scene != "curtis-scene2":
            want = "forward" if scene == "curtis-scene1" else "deferred"
            claim = f"{scene}: {want} is faster (FPS higher and frame time lower)"
            if ow is None:
                v = "n/a (not run)"
            else:
                hits = (ow[0] == want) + (ow[1] == want)
                v = "yes" if hits == 2 else "partly" if hits == 1 else "no"
            s.claim(claim, ptxt, otxt, v)
        else:
            claim = ("curtis-scene2: deferred slightly faster, the difference within one per-second SD "
                     "(no significant difference)")

            def within(x):
                _, _, d, f = x
                sds = [d[1], f[1], d[3], f[3]]
                if None in sds:
                    return None
                return abs(d[0] - f[0]) < min(d[1], f[1]) and abs(d[2] - f[2]) < min(d[3], f[3])
            ptxt2 = ptxt + (f"; within 1 SD: {'yes' if within(pw) else 'no'}" if pw else "")
            if ow is None:
                v, otxt2 = "n/a (not run)", otxt
            else:
                wi = within(ow)
                otxt2 = otxt + f"; within 1 SD: {'-' if wi is None else 'yes' if wi else 'no'}"
                hits = (ow[0] == "deferred" and ow[1] == "deferred") + bool(wi)
                v = "yes" if hits == 2 else "partly" if hits == 1 else "no"
            s.claim(claim, ptxt2, otxt2, v)
    # consistency: deferred's per-second SD below forward's in scenes 1 and 3
    texts, oks = {}, []
    for src in ("paper", "ours"):
        parts, hits, n = [], 0, 0
        for scene in ("curtis-scene1", "curtis-scene3"):
            d, f = avgs(src, scene, "deferred"), avgs(src, scene, "forward-spml")
            if d is None or f is None or None in (d[1], f[1], d[3], f[3]):
                parts.append(f"{scene}: -")
                continue
            n += 2
            hits += (d[1] < f[1]) + (d[3] < f[3])
            parts.append(f"{scene[-6:]}: SD fps {fmt(d[1], 2)} vs {fmt(f[1], 2)}, "
                         f"SD µs {fmt(d[3], 0)} vs {fmt(f[3], 0)}")
        texts[src] = "; ".join(parts)
        oks.append((hits, n))
    hits, n = oks[1]
    v = "n/a (not run)" if n == 0 else "yes" if hits == n else "no" if hits == 0 else "partly"
    s.claim("scenes 1 and 3: deferred is more consistent (smaller per-second SD of FPS and "
            "of frame time; deferred vs forward)", texts["paper"], texts["ours"], v)
    s.claims_table()
