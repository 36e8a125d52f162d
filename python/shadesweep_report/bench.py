"""What the README's benchmark scripts (scripts/bench-*.sh) share: their output folders
read back, the line that names the machine, and a mean with its 95% interval."""
import csv
import glob
import os

import yaml

from .stats import ci95, mean, num


def load(out, parts=("",)):
    """summary.csv rows and plan.csv rows by run id, of OUT/PART for each part that ran."""
    rows, plans = [], {}
    for part in parts:
        summary = os.path.join(out, part, "summary.csv")
        if not os.path.exists(summary):
            continue
        with open(summary, newline="") as f:
            rows += list(csv.DictReader(f))
        with open(os.path.join(out, part, "plan.csv"), newline="") as f:
            plans.update({p["run_id"]: p for p in csv.DictReader(f)})
    return rows, plans


def print_machine(out):
    """The GL renderer, CPU and commit of the first run under OUT, then a blank line."""
    metas = sorted(glob.glob(os.path.join(out, "**", "runs", "*", "meta.yaml"), recursive=True))
    if not metas:
        return
    with open(metas[0]) as f:
        meta = yaml.safe_load(f)
    print(f"GL renderer: {meta['gl']['renderer']}; CPU: {meta['host']['cpu']}, "
          f"{meta['host']['threads']} threads; shadesweep {meta['shadesweep']['commit']}")
    print()


def mean_ci(values):
    """(mean, 95% half-width) of the CSV fields VALUES; NaN for what cannot be had."""
    xs = [num(v) for v in values]
    m, ci = mean(xs), ci95(xs)
    return (float("nan") if m is None else m, float("nan") if ci is None else ci)


def print_header(*columns):
    """A markdown table's header row and rule."""
    print("| " + " | ".join(columns) + " |")
    print("|" + "---|" * len(columns))


def grouped(rows, key):
    """(k, the rows of k that ran ok, the status of its first row) for each k = KEY(row),
    in order of k: a group with no ok row is a failed row of the table."""
    groups = {}
    for r in rows:
        groups.setdefault(key(r), []).append(r)
    for k in sorted(groups):
        yield k, [r for r in groups[k] if r["status"] == "ok"], groups[k][0]["status"]
