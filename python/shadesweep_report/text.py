"""Markdown: numbers as the tables print them, tables, verdicts."""
import math



def nan(v):
    """None as NaN, for plotting."""
    return float("nan") if v is None else v


def fmt(v, nd=1, unit=""):
    if v is None:
        return "-"
    if isinstance(v, float) and math.isinf(v):
        return "inf"
    s = f"{v:,.{nd}f}".replace(",", "")
    return s + (f" {unit}" if unit else "")


def fmt_ci(m, ci, nd=1, unit=""):
    if m is None:
        return "-"
    s = fmt(m, nd)
    if ci is not None:
        s += f" ± {fmt(ci, nd)}"
    return s + (f" {unit}" if unit else "")


def ratio(a, b):
    if a is None or b is None or b == 0:
        return None
    return a / b


def md_table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for r in rows:
        out.append("| " + " | ".join(str(c) for c in r) + " |")
    return "\n".join(out) + "\n"


def verdict(v):
    return {"yes": "**yes**", "no": "**no**", "partly": "**partly**"}.get(v, v)
