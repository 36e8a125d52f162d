"""The report's statistics. Every ratio, significance and crossover the report prints is
asked of shadesweep itself (`shadesweep ratios`, runner/answer/ratios.c over results/verdict.c):
the module the ranking, summary.md and compare use, so that the report cannot say
"cannot say" where the ranking says "differs: yes" on the same data. The trial is the
unit: two runs of one folder and one sweep point are paired round by round, others are
compared by Welch's interval on the logs; each run's value is its summary.csv metric_us
(what measure.metric chose; frametime_mean_us for folders written before it)."""
import json
import os
import shutil
import subprocess

from .loading import die


def _exe():
    env = os.environ.get("SHADESWEEP_EXE")
    if env:
        return env
    found = shutil.which("shadesweep")
    if found:
        return found
    here = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
    built = os.path.normpath(os.path.join(here, "..", "build", "runner", "shadesweep"))
    if os.access(built, os.X_OK):
        return built
    die("the statistics need the shadesweep program: run the report as `shadesweep report`, "
        "or set SHADESWEEP_EXE")


def _ask(requests):
    """Answers (dicts) to requests (tuples of fields), in order, from one process."""
    if not requests:
        return []
    text = "".join("\t".join(str(f) for f in r) + "\n" for r in requests)
    try:
        p = subprocess.run([_exe(), "ratios"], input=text, capture_output=True, text=True,
                           check=False)
    except OSError as e:
        die(f"cannot run shadesweep ratios: {e.strerror}")
    if p.returncode != 0:
        die(f"shadesweep ratios failed: {p.stderr.strip().splitlines()[-1:] or p.returncode}")
    out = [json.loads(line) for line in p.stdout.splitlines()]
    if len(out) != len(requests):
        die(f"shadesweep ratios answered {len(out)} of {len(requests)} requests")
    return out


_READERS = {}


def readers():
    """{key: set of the renderers that read it ("*": every run)} from `shadesweep params
    --json` (runner/manifest/params.def), asked once; {} when it cannot say (every key kept)."""
    if "keys" not in _READERS:
        try:
            p = subprocess.run([_exe(), "params", "--json"], capture_output=True, text=True,
                               check=False)
            keys = json.loads(p.stdout)["keys"] if p.returncode == 0 else []
        except (OSError, ValueError, KeyError):
            keys = []
        _READERS["keys"] = {k["key"]: set(k["read_by"]) for k in keys}
    return _READERS["keys"]


def reads(renderer, key):
    """Whether a run of renderer reads key (a key shadesweep does not know: kept)."""
    r = readers().get(key)
    return r is None or "*" in r or renderer in r


def _folder(run):
    return os.path.dirname(os.path.dirname(run.dir))


def values(runs):
    """{run id: {"metric", "mean_us", "ci95_us", "trials"}} of each run (None values for
    a run with no ok trial)."""
    ans = _ask([("run", _folder(r), r.id) for r in runs])
    return {r.id: (a if "error" not in a else None) for r, a in zip(runs, ans)}


def ratios(pairs):
    """[answer of A / B] for each (run A, run B): ratio, lo, hi, paired, n, differs
    ("yes", "no", "n/a" with fewer than 3 trials), or {"error": ...}."""
    return _ask([("ratio", _folder(a), a.id, _folder(b), b.id) for a, b in pairs])


def crossovers(series):
    """For each series [(x, run A, run B), ...] (x ascending): {"crossings": [{i, j, dir,
    x, lo, hi}], "ratios": [{ratio, lo, hi, differs}]} where A / B crosses 1 (i, j index
    the series' points; lo, hi where the interval's bounds cross, None where they do not
    within the data), or {"error": ...}."""
    reqs = []
    for pts in series:
        f = ["crossover"]
        for x, a, b in pts:
            f += [repr(float(x)), _folder(a), a.id, _folder(b), b.id]
        reqs.append(tuple(f))
    return _ask(reqs)


def differs_text(a):
    """"yes (x1.04, 1.03-1.05)" from a ratio answer: the interval and whether it
    excludes 1."""
    if not a or "error" in a:
        return "-"
    if a["differs"] == "n/a":
        return "n/a (fewer than 3 trials)"
    lo, hi = a["lo"], a["hi"]
    return f"{a['differs']} (95%: {lo:.3f}-{hi:.3f}{', paired' if a['paired'] else ''})"


def within_text(a):
    """"" when the ratio's interval excludes 1; else why the two cannot be told apart."""
    if not a or "error" in a:
        return ""
    if a["differs"] == "n/a":
        return " (no verdict: fewer than 3 trials)"
    if a["differs"] == "no":
        return f" (not told apart: the ratio's 95% interval {a['lo']:.2f}-{a['hi']:.2f} holds 1)"
    return ""


_DEVICES = {}


def devices(folders):
    """{folder: {"software_rasterizer", "devices", "note"}}: whether a CPU rasterizer
    measured the folder's runs and the line summary.md says of them (None on one GPU),
    from `shadesweep ratios` (runner/answer/device_note.c; the detection is
    results/gl_device.c), asked once a folder."""
    ask = [f for f in dict.fromkeys(folders) if f not in _DEVICES]
    for f, a in zip(ask, _ask([("device", f) for f in ask])):
        _DEVICES[f] = a if "error" not in a else {"software_rasterizer": False, "devices": 0,
                                                  "note": None}
    return {f: _DEVICES[f] for f in folders}


def pass_times_attributed(run):
    """Whether run's per-pass times are the passes' own: passes.csv's gpu_us_attributed,
    or, in a folder written before it, whether its device is a GPU. On a CPU rasterizer
    only the frame total is trusted (llvmpipe rasterizes where it flushes)."""
    a = (run.passes() or {}).get("_attributed")
    if a is not None:
        return a
    return not devices([_folder(run)])[_folder(run)]["software_rasterizer"]


UNATTRIBUTED = ("Measured on a CPU rasterizer, these per-pass times are not the passes' own "
                "(it runs the work where it flushes, not in the pass that issued it): only the "
                "frame total is trusted; the counts per pass are.")
