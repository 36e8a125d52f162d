"""What the CLI tests read back from an output folder's runs: each run's summary row,
meta.yaml and screenshots (read_png: shading_model.py's PNG reader)."""
import csv
import glob
import sys

import yaml

from shading_model import read_png


def runs_with_shots(d, times):
    """Each run of output folder d, in summary.csv's order, as (row, meta, images): its
    trial row (status ok, else exit with FAIL), its meta.yaml as a dict, and a list of
    its screenshot at each of times (strings as the file names write them: "0", "0.5";
    H x W x C int, exactly one file each, else exit with FAIL)."""
    out = []
    for r in csv.DictReader(open(f"{d}/summary.csv")):
        if r["status"] != "ok":
            sys.exit(f"FAIL: {r['renderer']}: {r['status']}")
        run = f"{d}/runs/{r['run_id']}"
        images = []
        for t in times:
            f = glob.glob(f"{run}/screenshot-*-t{t}.png")
            if len(f) != 1:
                sys.exit(f"FAIL: {r['renderer']}: screenshot at {t}: {f}")
            images.append(read_png(f[0]).astype(int))
        out.append((r, yaml.safe_load(open(f"{run}/meta.yaml")), images))
    return out
