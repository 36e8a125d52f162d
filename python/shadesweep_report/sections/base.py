"""What every section shares: its text, its claims, CI overlap."""
from ..text import md_table, verdict


class Section:
    def __init__(self, exp, ref, plots):
        self.e = exp
        self.ref = ref
        self.plots = plots
        self.out = []
        self.claims = []

    def w(self, text=""):
        self.out.append(text)

    def claim(self, text, paper, ours, v):
        self.claims.append((text, paper, ours, v))

    def claims_table(self):
        if not self.claims:
            return
        self.w("Claims, computed from the paper's numbers and from ours:\n")
        self.w(md_table(["claim", "paper", "ours", "reproduced"],
                        [(c, p, o, verdict(v)) for c, p, o, v in self.claims]))

    def text(self):
        return "\n".join(self.out)


def ci_overlap(a, b):
    """Whether two (mean, ci) intervals overlap; False when either has no CI."""
    (ma, ca), (mb, cb) = a, b
    if None in (ma, mb, ca, cb):
        return False
    return abs(ma - mb) <= ca + cb
