"""Reading shadesweep output folders: plan.csv, summary.csv, sweep.yaml, runs/<id>/{meta.yaml,seconds.csv,passes.csv,errors.csv,coverage.csv}."""
import csv
import io
import math
import os
import re
import sys

from .stats import ci95, mean, median, num
from .text import md, md_values


ME = "report"


def reference_dir():
    """The papers' tables: $SHADESWEEP_REFERENCE, else beside the installed package
    (DATADIR/shadesweep/reference), else the source tree's results/reference."""
    env = os.environ.get("SHADESWEEP_REFERENCE")
    if env:
        return env
    here = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
    for cand in (os.path.join(here, "..", "reference"),
                 os.path.join(here, "..", "results", "reference")):
        if os.path.isdir(cand):
            return os.path.normpath(cand)
    return os.path.normpath(os.path.join(here, "..", "results", "reference"))


SEED3 = "seed 003 (Curtis 2014)"
SEED0 = "seed 000 (chapter 5)"

# Every experiment the report knows, in report order: name -> (title, source).
EXPERIMENTS = [
    ("s003-exp1", "Experiment 1: three scenes, 160 lights (Tables 1-6)", SEED3),
    ("s003-exp2", "Experiment 2: lights growing 10 per second (appendix 10.2, 8.2)", SEED3),
    ("s000-resolution", "Frame time against resolution (5.3.1, 5.3.2)", SEED0),
    ("s000-drawcalls", "Draw calls with and without shadows (5.3.1-5.3.3, 6.3)", SEED0),
    ("s000-spot-coverage", "One spot light, small and large coverage (5.4.1)", SEED0),
    ("s000-two-spots", "Two overlapping spot lights (5.4.2)", SEED0),
    ("s000-stencil", "Stencil-masked light hull (5.5)", SEED0),
    ("s000-illumination-sets", "Forward illumination sets (5.6)", SEED0),
    ("gbuffer-error", "G-buffer layout: image error against frame time (ours only)", "ours"),
    ("renderers-tiled", "Six renderers as lights grow: the fastest and the crossovers (ours only)",
     "ours"),
    ("aa-translucency", "Anti-aliasing and translucency: frame time against edge error (ours only)",
     "ours"),
]
KNOWN = [e[0] for e in EXPERIMENTS]


def die(msg):
    print(f"{ME}: {msg}", file=sys.stderr)
    sys.exit(2)

# ---- reading our outputs

def read_csv(path):
    """The rows of a CSV as dicts, None when there is no such file. A file shadesweep
    did not write whole (not UTF-8, empty, a last line without its line end, a row of
    another width than the header, an unclosed quote) ends the report with one line
    naming it and exit 2: its numbers cannot be trusted, and a half-read table would
    fail later with a traceback or, worse, report what is not there."""
    if not os.path.isfile(path):
        return None
    try:
        with open(path, newline="", encoding="utf-8") as f:
            text = f.read()
    except UnicodeDecodeError as e:
        die(f"{path}: not UTF-8 text (byte 0x{e.object[e.start]:02x} at offset {e.start}); "
            "not a file shadesweep wrote")
    except OSError as e:
        die(f"{path}: cannot read: {e.strerror or e}")
    if not text:
        die(f"{path}: empty (no header line): cut off or damaged")
    if not text.endswith("\n"):
        die(f"{path}: cut off (its last line has no line end)")
    reader = csv.reader(io.StringIO(text, newline=""), strict=True)
    rows = []
    try:
        header = next(reader)
        for row in reader:
            if not row:
                continue
            if len(row) != len(header):
                die(f"{path}:{reader.line_num}: {len(row)} fields, the header has {len(header)} "
                    "(a cut-off or damaged file)")
            # values as Markdown text (text.md): names and messages go into report.md
            rows.append(dict(zip(header, (md(v) for v in row))))
    except csv.Error as e:
        die(f"{path}:{reader.line_num}: not CSV ({e})")
    return rows


def _scalar(s):
    s = s.strip()
    if len(s) >= 2 and s[0] == s[-1] and s[0] in "\"'":
        return s[1:-1]
    return s


def read_yaml(path):
    """meta.yaml and sweep.yaml as nested dicts (PyYAML when present, else the subset
    shadesweep writes: block mappings and block sequences of scalars or mappings)."""
    try:
        text = open(path, encoding="utf-8", errors="replace").read()
    except OSError:
        return {}
    try:
        import yaml
    except ImportError:
        yaml = None
    if yaml is not None:
        try:
            d = yaml.safe_load(text)
        except yaml.YAMLError as e:
            mark = getattr(e, "problem_mark", None)
            where = f"line {mark.line + 1}: " if mark is not None else ""
            what = getattr(e, "problem", None) or str(e).splitlines()[0]
            die(f"{path}: not valid YAML ({where}{what}); not a file shadesweep wrote")
        return md_values(d) if isinstance(d, dict) else {}
    root = {}
    stack = [(-1, root)]
    for line in text.splitlines():
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        ind = len(line) - len(line.lstrip())
        body = line.strip()
        while stack and stack[-1][0] >= ind and len(stack) > 1:
            stack.pop()
        cont = stack[-1][1]
        if body.startswith("- "):
            continue  # sequences (the pass plan) are not needed here
        m = re.match(r'^("[^"]*"|[^:]+):(?:\s+(.*))?$', body)
        if not m or not isinstance(cont, dict):
            continue
        key = _scalar(m.group(1))
        if m.group(2) is None or m.group(2) == "":
            cont[key] = {}
            stack.append((ind, cont[key]))
        else:
            cont[key] = _scalar(m.group(2))
    return md_values(root)


def norm(v):
    """A parameter value as comparable text: numbers as floats, booleans as true/false."""
    if v is None:
        return ""
    if isinstance(v, bool):
        return "true" if v else "false"
    s = str(v).strip()
    try:
        f = float(s)
        if not math.isnan(f):
            return repr(f)
    except ValueError:
        pass
    return s.lower()


class Run:
    def __init__(self, exp, run_id, folder):
        self.exp = exp
        self.id = run_id
        self.dir = os.path.join(folder, "runs", run_id)
        self.rows = []          # summary rows, every trial
        self.params = {}
        self._cache = {}

    @property
    def ok_rows(self):
        return [r for r in self.rows if r.get("status") == "ok"]

    @property
    def renderer(self):
        return self.rows[0]["renderer"] if self.rows else self.params.get("renderer", "")

    @property
    def scene(self):
        return self.rows[0]["scene"] if self.rows else self.params.get("scene", "")

    @property
    def size(self):
        r = self.rows[0] if self.rows else {}
        w, h = num(r.get("width")), num(r.get("height"))
        if w is None or h is None:
            m = re.match(r"(\d+)x(\d+)", str(self.params.get("resolution", "")))
            if m:
                w, h = float(m.group(1)), float(m.group(2))
        return (int(w), int(h)) if w is not None and h is not None else (0, 0)

    def param(self, key):
        return self.params.get(key, "")

    @property
    def status(self):
        """The run's status as shadesweep wrote it in meta.yaml (runner/folder/trials.c
        trials_run_status: ok, partial:<reason> or the failure); "" without results. A
        meta.yaml with no status (a folder not written by shadesweep) gets the same rule
        applied to the rows."""
        if not self.rows:
            return ""
        st = self.meta().get("status")
        if isinstance(st, str) and st:
            return st
        bad = [r.get("status") or "unknown" for r in self.rows if r.get("status") != "ok"]
        if not bad:
            return "ok"
        reason = bad[0][len("failed:"):] if bad[0].startswith("failed:") else bad[0]
        return f"partial:{reason}" if self.ok_rows else bad[0]

    @property
    def measured(self):
        """Whether the run has trials to show: its status is ok or partial."""
        return self.status == "ok" or self.status.startswith("partial:")

    def meta(self):
        if "meta" not in self._cache:
            self._cache["meta"] = read_yaml(os.path.join(self.dir, "meta.yaml"))
        return self._cache["meta"]

    def col(self, name):
        """A summary column over the run's ok trials."""
        return [num(r.get(name)) for r in self.ok_rows]

    def agg(self, name, ci_col=None):
        """(mean over trials, 95% CI half-width, n). With three or more trials the CI is
        over the trial means (Student t); with fewer, the mean of the trials' own CI column
        (summary.csv's batch-means CI) when one is named, else none."""
        vals = [v for v in self.col(name) if v is not None]
        if not vals:
            return None, None, 0
        if len(vals) >= 3:
            return mean(vals), ci95(vals), len(vals)
        ci = mean(self.col(ci_col)) if ci_col else None
        return mean(vals), ci, len(vals)

    def frametime_ms(self):
        m, ci, n = self.agg("frametime_mean_us", "frametime_ci95_us")
        return (m / 1000 if m is not None else None, ci / 1000 if ci is not None else None, n)

    def fps(self):
        m, ci, n = self.agg("fps_mean")
        return m, ci, n

    def seconds(self):
        """seconds.csv grouped by trial: {trial: [rows]} of ok trials, or None."""
        if "seconds" not in self._cache:
            rows = read_csv(os.path.join(self.dir, "seconds.csv"))
            out = None
            if rows is not None:
                ok = {r.get("trial") for r in self.ok_rows}
                out = {}
                for r in rows:
                    if r.get("trial") in ok:
                        out.setdefault(int(r["trial"]), []).append(r)
                for t in out:
                    out[t].sort(key=lambda r: int(r["second"]))
            self._cache["seconds"] = out
        return self._cache["seconds"]

    def passes(self):
        """passes.csv of ok trials: {pass: {gpu_us, draw_calls, samples, frames_with_pass}}:
        the median GPU time per frame (robust to a wild timer result; None when the driver
        gave none), the mean draw calls and the mean shaded samples (GL_SAMPLES_PASSED)
        per frame (None when the folder has no samples column); "_attributed": whether the
        times are the passes' own (gpu_us_attributed: 0 on a software rasterizer; None
        for a folder written before the column)."""
        if "passes" not in self._cache:
            path = os.path.join(self.dir, "passes.csv")
            out = None
            if os.path.isfile(path):
                ok = {r.get("trial") for r in self.ok_rows}
                acc = {}
                frames = set()
                attributed = None
                for r in read_csv(path) or []:
                    if r.get("trial") not in ok:
                        continue
                    if r.get("gpu_us_attributed") in ("0", "1"):
                        attributed = (attributed is not False) and r["gpu_us_attributed"] == "1"
                    frames.add((r["trial"], r["frame"]))
                    a = acc.setdefault(r["pass"], [[], None, 0.0, 0])
                    g = num(r.get("gpu_us"))
                    if g is not None:
                        a[0].append(g)
                    smp = num(r.get("samples"))
                    if smp is not None:
                        a[1] = (a[1] or 0.0) + smp
                    a[2] += num(r.get("draw_calls")) or 0.0
                    a[3] += 1
                nf = len(frames)
                out = {p: {"gpu_us": median(a[0]),
                           "draw_calls": a[2] / nf if nf else None,
                           "samples": a[1] / nf if nf and a[1] is not None else None,
                           "frames_with_pass": a[3]} for p, a in acc.items()}
                out["_frames"] = nf
                out["_attributed"] = attributed
            self._cache["passes"] = out
        return self._cache["passes"]

    def coverage(self):
        """Mean screen coverage per light from coverage.csv (or a frames.csv column)."""
        if "coverage" not in self._cache:
            out = None
            rows = read_csv(os.path.join(self.dir, "coverage.csv"))
            ok = {r.get("trial") for r in self.ok_rows}
            if rows:
                per = {}
                for r in rows:
                    if r.get("trial") in ok and num(r.get("coverage")) is not None:
                        per.setdefault(r.get("light", "0"), []).append(num(r["coverage"]))
                out = {k: mean(v) for k, v in per.items()} or None
            else:
                fr = read_csv(os.path.join(self.dir, "frames.csv"))
                if fr and "coverage" in fr[0]:
                    out = {"all": mean(num(r["coverage"]) for r in fr if r.get("trial") in ok)}
            self._cache["coverage"] = out
        return self._cache["coverage"]


class Experiment:
    def __init__(self, name, raw_names):
        self.name = name
        self.raw_names = raw_names
        self.folders = []
        self.runs = {}          # run id -> Run, plan order
        self.sweep = {}
        self.notes = []

    def add_folder(self, folder, summary, plan):
        self.folders.append(folder)
        self.sweep = self.sweep or read_yaml(os.path.join(folder, "sweep.yaml"))
        for p in plan or []:
            rid = p.get("run_id")
            if rid and rid not in self.runs:
                run = Run(self, rid, folder)
                run.params = {k: v for k, v in p.items()
                              if k not in ("index", "run_id", "shard", "folded")}
                self.runs[rid] = run
        seen = {(r.id, row.get("trial")) for r in self.runs.values() for row in r.rows}
        for row in summary:
            rid = row.get("run_id")
            if not rid:
                continue
            if rid not in self.runs:
                self.runs[rid] = Run(self, rid, folder)
            if (rid, row.get("trial")) in seen:
                continue
            seen.add((rid, row.get("trial")))
            self.runs[rid].rows.append(row)
        # meta.yaml fills what plan.csv lacks
        for run in self.runs.values():
            params = run.meta().get("parameters")
            if isinstance(params, dict):
                for k, v in params.items():
                    run.params.setdefault(k, "" if v is None else str(v))

    def measured(self):
        return [r for r in self.runs.values() if r.measured and r.ok_rows]

    def failed(self):
        return [r for r in self.runs.values() if r.rows and not r.measured]

    def partial(self):
        return [r for r in self.runs.values() if r.status.startswith("partial:")]

    def select(self, renderer=None, scene=None, **params):
        """The runs with ok trials that match; parameter keys with '.' spelled '__'."""
        out = []
        for r in self.measured():
            if renderer is not None and r.renderer != renderer:
                continue
            if scene is not None and r.scene != scene:
                continue
            if any(norm(r.param(k.replace("__", "."))) != norm(v) for k, v in params.items()):
                continue
            out.append(r)
        return out

    def renderer_for(self, wanted):
        """The renderer to compare with the paper's `wanted`: itself when measured, else the
        other forward renderer (with a note)."""
        have = {r.renderer for r in self.measured()}
        if wanted in have or not wanted.startswith("forward"):
            return wanted
        alt = sorted(x for x in have if x.startswith("forward"))
        if alt:
            self.notes.append(f"{wanted} was not run; {alt[0]} stands in for the paper's forward renderer.")
            return alt[0]
        return wanted

    def values(self, key):
        vals = []
        for r in self.runs.values():
            v = r.param(key)
            if v not in vals:
                vals.append(v)
        return vals


# Manifests whose runs are a part of a known experiment's configurations: their section
# reads them (experiments/aa-cost.yaml: aa-translucency's msaa 1 and 4, no edge AA, no
# error reference, at full size: the README's cost table).
ALIASES = {"aa-cost": "aa-translucency"}


def canonical(name):
    if name in KNOWN:
        return name
    if name in ALIASES:
        return ALIASES[name]
    if name.endswith("-smoke") and name[:-6] in KNOWN:
        return name[:-6]
    return None


def find_folders(outdir):
    """Output folders (plan.csv and summary.csv) under outdir, three levels at most."""
    found = []

    def walk(d, depth):
        try:
            names = set(os.listdir(d))
        except OSError:
            return
        if "summary.csv" in names and "plan.csv" in names:
            found.append(d)
            return
        if depth == 3:
            return
        for n in sorted(names):
            p = os.path.join(d, n)
            if n not in ("runs", "plots") and os.path.isdir(p) and not os.path.islink(p):
                walk(p, depth + 1)

    walk(outdir, 0)
    return found


def load(dirs):
    """The experiments of the output folders under every one of dirs, named as given."""
    exps, unknown, broken = {}, {}, []
    for folder in [f for d in dirs for f in find_folders(d)]:
        summary = read_csv(os.path.join(folder, "summary.csv"))
        plan = read_csv(os.path.join(folder, "plan.csv"))
        if summary is None:
            broken.append(folder)
            continue
        names = [r.get("experiment", "") for r in summary if r.get("experiment")]
        raw = names[0] if names else read_yaml(os.path.join(folder, "sweep.yaml")).get("experiment", "")
        raw = str(raw or "")
        canon = canonical(raw)
        if canon is None:
            unknown.setdefault(raw or md(os.path.basename(folder)), []).append(folder)
            continue
        e = exps.get(canon) or Experiment(canon, [])
        exps[canon] = e
        if raw not in e.raw_names:
            e.raw_names.append(raw)
        e.add_folder(folder, summary, plan)
    return exps, unknown, broken
