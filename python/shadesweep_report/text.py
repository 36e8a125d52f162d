"""Markdown: numbers as the tables print them, tables, verdicts."""
import math



_MD = {"\\": "\\\\", "|": "\\|", "`": "\\`", "&": "&amp;", "<": "&lt;", ">": "&gt;",
       "\n": " ", "\r": " "}


def md(s):
    """Text from a result file as Markdown shows it, never as markup: `\\` `|` and
    backticks escaped, `&` `<` `>` as entities, line ends as spaces (runner's
    results/mdtext.c does the same for summary.md)."""
    return "".join(_MD.get(c, c) for c in s)


def md_values(v):
    """Every string in v (a row, a parsed YAML or JSON document) through md()."""
    if isinstance(v, str):
        return md(v)
    if isinstance(v, dict):
        return {k: md_values(x) for k, x in v.items()}
    if isinstance(v, list):
        return [md_values(x) for x in v]
    return v


def code(path):
    """A folder's path as a code span; escaped text instead when a backtick, `|` or a
    line end in it would break the span or the table around it."""
    return f"`{path}`" if not any(c in path for c in "`|\n\r") else md(path)


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
