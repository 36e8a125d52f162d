"""shadesweep report: the command line and the report's frame."""
import datetime
import os
import sys

from .loading import EXPERIMENTS, KNOWN, ME, Experiment, die, load, read_csv, reference_dir
from .outfiles import open_dir, open_subdir, refuse_link, remove, write_atomic
from .plots import PLOT_NAMES, Plots
from .reference import Reference
from .sections import SECTIONS
from .sections.base import Section
from .sections.generic import section_generic
from .text import code, md_table
from . import cross_device, verdicts


def setup_text(e):
    """Resolution, duration, trials and clock as the runs used them."""
    keys = ("resolution", "duration", "trials", "warmup", "clock")
    parts = []
    for k in keys:
        vals = sorted({r.param(k) for r in e.runs.values() if r.param(k)})
        if not vals:
            sizes = sorted({f"{r.size[0]}x{r.size[1]}" for r in e.runs.values()}) if k == "resolution" else []
            vals = sizes
        if vals:
            parts.append(f"{k} {', '.join(vals)}")
    return "; ".join(parts)


def runs_text(e, missing=None):
    """The "Runs:" line of an experiment, from each run's status (Run.status), and the
    partial runs named (their ok trials are shown)."""
    nrun, nok, nfail, part = len(e.runs), len(e.measured()), len(e.failed()), e.partial()
    text = (f"Runs: {nrun} planned, {nok} with measured trials, {nfail} failed"
            + (f", {len(part)} partial" if part else "")
            + (f", {len(missing)} without results" if missing else "") + ".\n")
    if part:
        text += ("Partial runs (their ok trials are used): " + "; ".join(
            f"{r.id} {r.renderer}: {r.status}, {len(r.ok_rows)} of {len(r.rows)} trials ok"
            for r in part[:12]) + (" ..." if len(part) > 12 else "") + ".\n")
    return text


def gather_meta(exps):
    gl, cpu, commits, started = set(), set(), set(), []
    for e in exps.values():
        for r in e.runs.values():
            m = r.meta()
            g = m.get("gl") if isinstance(m.get("gl"), dict) else {}
            if g.get("renderer"):
                gl.add(f"{g.get('renderer')} ({g.get('version', '')}; {g.get('backend', '')})")
            h = m.get("host") if isinstance(m.get("host"), dict) else {}
            if h.get("cpu"):
                cpu.add(f"{h.get('cpu')}, {h.get('threads', '?')} threads")
            sw = m.get("shadesweep") if isinstance(m.get("shadesweep"), dict) else {}
            if sw.get("commit"):
                commits.add(str(sw.get("commit")))
            for k in ("started", "finished"):
                if m.get(k):
                    started.append(str(m[k]))
    return gl, cpu, commits, sorted(started)


USAGE = ("usage: shadesweep report [-o OUTDIR] DIR...   (each DIR holds shadesweep output "
         "folders; report.md and plots/ go into OUTDIR, by default the one DIR)\n"
         "       shadesweep report --cross-device -o OUTDIR A B   (two folders of one manifest "
         "run on two devices: cross-device.md in OUTDIR)")


def parse_args(argv):
    """(dirs, outdir, cross) from the command line; exits 0 for --help, 2 with one line for
    anything else wrong."""
    dirs, outdir, i, cross = [], None, 1, False
    while i < len(argv):
        a = argv[i]
        if a in ("-h", "--help"):
            print(USAGE)
            sys.exit(0)
        if a in ("-o", "--out"):
            if i + 1 >= len(argv):
                die(f"{a}: needs a folder")
            outdir = argv[i + 1]
            i += 2
            continue
        if a == "--cross-device":
            cross = True
        elif a.startswith("--out="):
            outdir = a[len("--out="):]
        elif a.startswith("-") and a != "-":
            die(f"{a}: unknown option ({USAGE})")
        else:
            dirs.append(a)
        i += 1
    if not dirs:
        die(f"expected one or more folders ({USAGE})")
    if outdir is None:
        if len(dirs) > 1:
            die("several folders: say where the report goes with -o OUTDIR")
        outdir = dirs[0]
    return dirs, outdir, cross


def report_time():
    """When the report was written: $SOURCE_DATE_EPOCH when set (a reproducible
    report), else now."""
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    t = (datetime.datetime.fromtimestamp(int(epoch), datetime.timezone.utc)
         if epoch and epoch.isdigit() else datetime.datetime.now(datetime.timezone.utc))
    return t.strftime("%Y-%m-%d %H:%M UTC")


def main(argv):
    dirs, outdir, cross = parse_args(argv)
    for d in dirs:
        if not os.path.exists(d):
            die(f"{d}: no such folder")
        if not os.path.isdir(d):
            die(f"{d}: not a folder")
    if os.path.exists(outdir) and not os.path.isdir(outdir):
        die(f"{outdir}: not a folder")
    try:
        os.makedirs(outdir, exist_ok=True)
    except OSError as e:
        die(f"{outdir}: cannot make the folder ({e.strerror or e}; report.md goes there)")
    if not os.access(outdir, os.W_OK):
        die(f"{outdir}: not writable (report.md goes there)")
    if cross:   # two devices side by side, instead of report.md
        return cross_device.write(dirs, outdir, report_time())
    ref = Reference(reference_dir())
    exps, unknown, broken = load(dirs)
    if not exps and not unknown:
        die(f"{', '.join(dirs)}: no shadesweep output folder in it (none with plan.csv and "
            "summary.csv)")
    # Nothing below OUTDIR is written through a link (outfiles.py); the links in the way
    # are refused before anything is written.
    out_fd = open_dir(outdir)
    refuse_link(out_fd, "report.md", os.path.join(outdir, "report.md"))
    plots_fd = open_subdir(out_fd, "plots", os.path.join(outdir, "plots"), create=False)
    if plots_fd is not None:
        for name in PLOT_NAMES:
            refuse_link(plots_fd, name, os.path.join(outdir, "plots", name))
        for name in PLOT_NAMES:   # a plot of an earlier report must not outlive its data
            remove(plots_fd, name)
        os.close(plots_fd)
    plots = Plots(out_fd, outdir)
    # the experiments of no paper: read like the others, their meta.yaml included
    others = {}
    for raw, folders in sorted(unknown.items()):
        e = Experiment(raw, [raw])
        for f in folders:
            e.add_folder(f, read_csv(os.path.join(f, "summary.csv")) or [],
                         read_csv(os.path.join(f, "plan.csv")))
        others[raw] = e
    gl, cpu, commits, times = gather_meta({**exps, **others})
    now = report_time()
    papers = bool(exps)
    title = ("shadesweep against the papers" if papers
             else ", ".join(sorted(others)) + ": shadesweep report")
    head = [f"# {title}\n",
            f"- Report written: {now} by shadesweep report from "
            + ", ".join(code(d) for d in dirs),
            f"- Runs: {times[0]} to {times[-1]}" if times else "- Runs: times unknown (no meta.yaml)",
            "- GL renderer: " + ("; ".join(sorted(gl)) if gl else "unknown (no meta.yaml)"),
            "- CPU: " + ("; ".join(sorted(cpu)) if cpu else "unknown"),
            "- shadesweep commit: " + (", ".join(sorted(commits)) if commits else "unknown")]
    if papers:
        head.append("- The papers: seed 000 measured on a GeForce 6800 (Direct3D 9, NVPerfHUD), seed "
                    "003 on a GeForce GTX 870M (Direct3D 11, Intel GPA). Absolute numbers do not "
                    "transfer between machines; the claims (which renderer wins, by what ratio, "
                    "where the lines cross) are what is compared.")
    # the device of each folder, as summary.md says it (results/gl_device.c decides)
    dev = verdicts.devices([f for e in {**exps, **others}.values() for f in e.folders])
    notes = {f: d["note"] for f, d in dev.items() if d["note"]}
    if len(set(notes.values())) == 1:
        head.append(f"- **Device:** {next(iter(notes.values()))}.")
    else:
        head += [f"- **Device of {code(f)}:** {n}." for f, n in notes.items()]
    soft = any(d["software_rasterizer"] for d in dev.values())
    if soft:
        head.append("- **Software rendering.** These runs used a CPU rasteriser (llvmpipe), which "
                    "shades pixels far slower than " + ("the papers' GPUs" if papers else "a GPU")
                    + ", so runs on it may be scaled down "
                    "(`run --scale`, `--smoke`); each section says the resolution and duration used.")
    head.append("- Our numbers: the mean over a run's trials; \"± x\" is the half-width of the 95% "
                "confidence interval of that mean: over the trial means (Student t) with three or "
                "more trials, else the mean of the trials' `frametime_ci95_us` from summary.csv "
                "(batch means over each trial's frames). SDs are named where given.")
    if papers:
        head.append("- Verdicts: **yes** the claim holds for ours as the paper states it, **partly** "
                    "the direction holds but not the size or place (each claim says its rule), "
                    "**no** it does not; n/a where ours was not run.\n")
    else:
        head[-1] += "\n"
    body, summary = [], []
    for name, title, src in (EXPERIMENTS if papers else []):
        e = exps.get(name)
        body.append(f"## {name}: {title}\n")
        if src != "ours":
            body.append(f"Source: {src}.\n")
        if e is None:
            body.append("**Not run**: no output folder of this experiment under OUTDIR.\n")
            summary.append([name, "not run", "-", "-"])
            continue
        alias = [n for n in e.raw_names if n != name]
        body.append(f"Output: {', '.join(code(f) for f in e.folders)}"
                    + (f" (experiment {', '.join(alias)})" if alias else "") + ".\n")
        body.append(f"Used: {setup_text(e)}.\n")
        nok = len(e.measured())
        body.append(runs_text(e, [r.id for r in e.runs.values() if not r.rows]))
        bad = [row for r in e.runs.values() for row in r.rows if row.get("status") != "ok"]
        if bad:
            body.append("Failed trials (left out): " + "; ".join(
                f"{b['run_id']} {b.get('renderer', '')} trial {b.get('trial')}: {b.get('status')}"
                for b in bad[:12]) + (" ..." if len(bad) > 12 else "") + "\n")
        sec = Section(e, ref, plots)
        if nok == 0:
            sec.w("No run of this experiment has a measured trial; nothing to compare.\n")
        else:
            SECTIONS[name](sec)
        for n in e.notes:
            body.append(f"Note: {n}\n")
        body.append(sec.text())
        counts = {}
        for c in sec.claims:
            k = c[3] if c[3] in ("yes", "partly", "no") else "n/a"
            counts[k] = counts.get(k, 0) + 1
        summary.append([name, "run", nok,
                        ", ".join(f"{counts[k]} {k}" for k in ("yes", "partly", "no", "n/a") if k in counts) or "-"])
    for raw, e in others.items():
        summary.append([raw, "not recognised (no paper table)" if papers else "run",
                        len(e.measured()) if not papers else "-", "-"])
        sec = Section(e, ref, plots)
        if e.measured():
            section_generic(sec)
        if sec.out or not papers:
            body.append(f"## {raw}" + (": not a paper experiment\n" if papers else "\n"))
            body.append(f"Output: {', '.join(code(f) for f in e.folders)}.\n")
            body.append(f"Used: {setup_text(e)}.\n")
            body.append(runs_text(e))
            body.append(sec.text())
    if broken:
        summary.append([", ".join(broken), "unreadable summary.csv", "-", "-"])
    lines = head + ["## Summary\n",
                    md_table(["experiment", "status", "runs measured"]
                             + (["claims reproduced"] if papers else []),
                             [row if papers else row[:3] for row in summary])]
    if plots.error:
        lines.append(f"Plots not made: {plots.error}.\n")
    lines += body
    path = os.path.join(outdir, "report.md")
    write_atomic(out_fd, "report.md", ("\n".join(lines).rstrip() + "\n").encode("utf-8"), path)
    ran = [n for n in KNOWN if n in exps]
    if papers:
        print(f"{ME}: wrote {path}: {len(ran)} of {len(KNOWN)} experiments "
              f"({', '.join(ran)}), {len(plots.made)} plot(s)"
              + (f"; not recognised: {', '.join(sorted(unknown))}" if unknown else ""))
    else:   # the user's own manifests: nothing to recognise
        print(f"{ME}: wrote {path}: {', '.join(sorted(others))}, {len(plots.made)} plot(s)")
    for n in dict.fromkeys(notes.values()):   # the device, as report.md's head says it
        print(f"{ME}: device: {n}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
