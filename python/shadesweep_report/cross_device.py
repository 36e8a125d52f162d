"""shadesweep report --cross-device -o OUTDIR A B (issue 38, item 4): two output folders
of one manifest, run on two devices, ranked side by side per sweep point; where the
rankings differ, the limiter of each device's winner (its bound, from
`shadesweep bound`: runner/answer/summary_bound.c) names what explains it, or says it is
unknown where a folder has no device.yaml. Written as OUTDIR/cross-device.md."""
import csv
import io
import os
import subprocess

from .loading import ME, die, read_csv, read_yaml
from .outfiles import open_dir, refuse_link, write_atomic
from .text import code, md_table
from . import verdicts

# plan.csv columns that are no parameter of a sweep point: the run's place, and how
# long and how often it was measured (two devices may be given other durations)
NOT_POINT = {"index", "run_id", "shard", "folded", "renderer", "trials", "warmup",
             "duration", "clock", "step", "sync", "timeout", "outputs.frames",
             "outputs.seconds", "outputs.screenshots"}


def _num(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return None


class Folder:
    """One folder: its runs' times (the mean over ok trials of what ranks them: summary.csv
    `metric_us`, else `frametime_mean_us`), its points, its device and its bounds."""

    def __init__(self, path):
        self.path = path
        self.plan = read_csv(os.path.join(path, "plan.csv"))
        summary = read_csv(os.path.join(path, "summary.csv"))
        if self.plan is None or summary is None:
            die(f"{path}: not a shadesweep output folder (no plan.csv and summary.csv)")
        sums, self.metric = {}, None
        for r in summary:
            if r.get("status") != "ok":
                continue
            t = _num(r.get("metric_us"))
            if t is not None:
                self.metric = r.get("metric") or self.metric
            else:
                t = _num(r.get("frametime_mean_us"))
            if t is not None:
                s = sums.setdefault(r["run_id"], [0.0, 0])
                s[0] += t
                s[1] += 1
        self.time = {k: s[0] / s[1] for k, s in sums.items()}
        self.metric = self.metric or "wall"
        self.device = "unknown (no meta.yaml)"
        for r in self.plan:
            m = read_yaml(os.path.join(path, "runs", r["run_id"], "meta.yaml"))
            g = m.get("gl") if isinstance(m.get("gl"), dict) else {}
            if g.get("renderer"):
                self.device = str(g["renderer"])
                break
        self.has_profile = os.path.isfile(os.path.join(path, "device.yaml"))
        self.bounds = self._bounds() if self.has_profile else {}

    def _bounds(self):
        """{run_id: row of `shadesweep bound`}."""
        try:
            p = subprocess.run([verdicts._exe(), "bound", self.path], capture_output=True,
                               text=True, check=False)
        except OSError as e:
            die(f"cannot run shadesweep bound: {e.strerror}")
        if p.returncode != 0:
            die(f"shadesweep bound {self.path} failed: "
                f"{(p.stderr.strip().splitlines() or [p.returncode])[-1]}")
        return {r["run_id"]: r for r in csv.DictReader(io.StringIO(p.stdout))}

    def points(self, columns):
        """{point key: {configuration: run_id}}, the keys in plan order. A point is the
        runs equal in `columns` that every renderer reads; a key only some renderers read
        (folded to its default for the others) names the configuration instead, beside
        the renderer, where that renderer's runs take more than one value of it."""
        every = [k for k in columns if "*" in verdicts.readers().get(k, {"*"})]
        own = [k for k in columns if k not in every]
        swept = {(r["renderer"], k) for k in own for r in self.plan
                 if verdicts.reads(r["renderer"], k)
                 and len({q[k] for q in self.plan if q["renderer"] == r["renderer"]}) > 1}
        out = {}
        for r in self.plan:
            key = tuple((k, r.get(k, "")) for k in every)
            extra = [f"{k} {r[k]}" for k in own if (r["renderer"], k) in swept]
            name = r["renderer"] + (f" ({', '.join(extra)})" if extra else "")
            out.setdefault(key, {})[name] = r["run_id"]
        return out

    def limiter(self, run_id):
        """The limiter of a run, in words."""
        if not self.has_profile:
            return "unknown (no device.yaml)"
        b = self.bounds.get(run_id) or {}
        if not b.get("limiter"):
            return "unknown (no bound)"
        return (f"{b['limiter']} (bound {float(b['bound_us']) / 1e3:.3g} of "
                f"{float(b['measured_us']) / 1e3:.3g} ms"
                + (", a model error" if b.get("model_error") == "yes" else "") + ")")


def _ranking(folder, runs):
    """[(renderer, ms)] fastest first, of the runs with a time."""
    have = [(r, folder.time[i] / 1e3) for r, i in runs.items() if i in folder.time]
    return sorted(have, key=lambda x: x[1])


def _cell(ranking):
    return ", ".join(f"{r} {t:.3g}" for r, t in ranking) or "-"


def write(dirs, outdir, now):
    if len(dirs) != 2:
        die(f"--cross-device: expected two folders, got {len(dirs)}")
    a, b = Folder(dirs[0]), Folder(dirs[1])
    # the parameters both plans have (a later version adds columns: measure.*, schedule)
    columns = [k for k in (a.plan[0] if a.plan else {}) if k not in NOT_POINT
               and b.plan and k in b.plan[0]]
    pa, pb = a.points(columns), b.points(columns)
    keys = [k for k in pa if k in pb]
    if not keys:
        die(f"{dirs[0]} and {dirs[1]}: no sweep point in common (not one manifest)")
    # the parameters that tell the points apart
    varies = [k for k, _ in keys[0] if len({dict(p)[k] for p in keys}) > 1]
    rows, notes, ndiff, nwin = [], [], 0, 0
    for key in keys:
        d = dict(key)
        label = ", ".join(f"{k} {d[k]}" for k in varies) or "the one point"
        runs = {r: i for r, i in pa[key].items() if r in pb[key]}
        ra, rb = _ranking(a, runs), _ranking(b, {r: pb[key][r] for r in runs})
        if not ra or not rb:
            rows.append([label, _cell(ra), _cell(rb), "-", "-", "-"])
            continue
        differs = [r for r, _ in ra] != [r for r, _ in rb]
        wa, wb = ra[0][0], rb[0][0]
        la, lb = a.limiter(runs[wa]), b.limiter(pb[key][wb])
        ndiff += differs
        nwin += wa != wb
        mark = "**winner**" if wa != wb else "**order**" if differs else "same"
        rows.append([label, _cell(ra), _cell(rb), mark, f"{wa}: {la}", f"{wb}: {lb}"])
        if wa != wb:
            notes.append(f"- {label}: {wa} wins on A, its limiter {la}; {wb} wins on B, "
                         f"its limiter {lb}.")
    head = [
        "# Cross-device: one manifest's rankings on two devices\n",
        f"- Report written: {now} by `shadesweep report --cross-device` from "
        f"{code(dirs[0])} (A) and {code(dirs[1])} (B)",
        f"- A: {a.device}, ranked by {a.metric} time; device profile: "
        + ("device.yaml" if a.has_profile else "none (no device.yaml: its limiters are unknown)"),
        f"- B: {b.device}, ranked by {b.metric} time; device profile: "
        + ("device.yaml" if b.has_profile else "none (no device.yaml: its limiters are unknown)"),
        f"- {len(keys)} sweep points; the ranking differs at {ndiff}, the winner at {nwin}.",
        "- Each ranking: the renderers fastest first, with the mean over their ok trials "
        "in ms. `differs`: **winner** where the fastest differs, **order** where only the "
        "order below it does. The limiter of each device's winner is its bound's resource "
        "(`shadesweep bound`: the time its counted work needs of each resource, by the "
        "device profile; docs/notes/device-profile.md \"The bound\"), with the bound and "
        "the measured time: a bound far below the measured time leaves most of that time "
        "unexplained by the resources the model counts (on a CPU rasterizer, most of it).\n",
    ]
    body = [md_table(["point", "A: ranking (ms)", "B: ranking (ms)", "differs",
                      "A's winner: limiter", "B's winner: limiter"], rows)]
    if notes:
        body += ["## Where the winner differs, and why\n", "\n".join(notes) + "\n"]
    text = "\n".join(head + body).rstrip() + "\n"
    fd = open_dir(outdir)
    path = os.path.join(outdir, "cross-device.md")
    refuse_link(fd, "cross-device.md", path)
    write_atomic(fd, "cross-device.md", text.encode("utf-8"), path)
    os.close(fd)
    print(f"{ME}: wrote {path}: {len(keys)} sweep points, the ranking differs at {ndiff}, "
          f"the winner at {nwin}")
    return 0
