"""The papers' numbers: results/reference/*.csv."""
import csv
import os

from .loading import die
from .stats import num


class Reference:
    def __init__(self, folder):
        if not os.path.isdir(folder):
            die(f"{folder}: the papers' tables (results/reference) are missing")
        self.rows = []
        for name in sorted(os.listdir(folder)):
            if name.endswith(".csv"):
                with open(os.path.join(folder, name), newline="") as f:
                    for r in csv.DictReader(f):
                        r["_file"] = name
                        self.rows.append(r)

    def get(self, **want):
        """Rows whose columns equal every given value (renderer=None: any)."""
        out = []
        for r in self.rows:
            if r.get("note", "").startswith("suspect:"):
                continue
            if all(v is None or r.get(k, "") == str(v) for k, v in want.items()):
                out.append(r)
        return out

    def value(self, **want):
        rows = self.get(**want)
        return num(rows[0]["value"]) if rows else None
