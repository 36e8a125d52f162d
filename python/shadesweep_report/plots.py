"""Plots (matplotlib, Agg), written into OUTDIR/plots/ (reached from OUTDIR's descriptor:
never through a link, outfiles.py)."""
import io
import os
import re

from .outfiles import open_subdir, write_atomic


def plot_file_name(name):
    """A plot's file name from names in result files (an experiment's): letters, digits,
    '.', '-' and '_' only, so that it stays a name inside plots/."""
    return re.sub(r"[^A-Za-z0-9._-]", "_", name).lstrip(".") or "plot"


class Plots:
    def __init__(self, out_fd, outdir):
        self.out_fd = out_fd
        self.folder = os.path.join(outdir, "plots")
        self.fd = None   # plots/, made at the first plot
        self.made = []
        self.error = None
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
            self.plt = plt
        except Exception as e:  # noqa: BLE001 - any import failure means no plots
            self.plt = None
            self.error = f"matplotlib could not be loaded ({e.__class__.__name__}: {e})"

    def save(self, fig, name):
        name = plot_file_name(name)
        path = os.path.join(self.folder, name)
        fig.tight_layout()
        if self.fd is None:
            self.fd = open_subdir(self.out_fd, "plots", self.folder, create=True)
        buf = io.BytesIO()   # encoded here, written atomically (write_atomic)
        fig.savefig(buf, dpi=110, format="png")
        write_atomic(self.fd, name, buf.getvalue(), path)
        self.plt.close(fig)
        self.made.append(name)
        return f"![{name}](plots/{name})\n"


def paper_vs_ours(axes, paper_title, ours_title, xlabel, ylabel):
    """Titles, axis labels, grid and legend of a (paper, ours) pair of axes."""
    axes[0].set_title(paper_title)
    axes[1].set_title(ours_title)
    for ax in axes:
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)


PLOT_NAMES = ["s003-exp2_fps_time.png", "s003-exp2_frametime_time.png",
              "s003-exp2_frametime_lights.png", "s000-resolution_frametime.png",
              "s000-drawcalls.png", "gbuffer-error_pareto.png",
              "gbuffer-error_bandwidth.png", "renderers-tiled_frametime_lights.png",
              "aa-translucency_error_time.png"]
COLORS = {"deferred": "tab:blue", "forward-spml": "tab:orange", "forward-mpml": "tab:red"}
# One colour and marker per renderer, the same in every plot; a renderer not named here
# (a new one) and every further line get the next unused pair, in name order.
STYLES = {"deferred": ("tab:blue", "o"), "forward-spml": ("tab:orange", "s"),
          "forward-mpml": ("tab:red", "^"), "forward-plus": ("tab:green", "D"),
          "clustered": ("tab:purple", "v"), "tiled-deferred": ("tab:brown", "P"),
          "deferred-lighting": ("teal", "X"), "null": ("tab:gray", "x")}
_SPARE = [("tab:pink", "*"), ("tab:olive", "h"), ("tab:cyan", "<"), ("black", ">"),
          ("gold", "p"), ("navy", "d"), ("lime", "8"), ("maroon", "H")]


def styles(labels, renderer_of):
    """{label: (colour, marker)}, distinct for every label: a label of one renderer alone
    takes the renderer's pair; the others the spare pairs in order (cycling, with dashes
    past the spares)."""
    out, used, spare = {}, set(), 0
    by_ren = {}
    for lab in labels:
        by_ren.setdefault(renderer_of(lab), []).append(lab)
    for lab in sorted(labels):
        ren = renderer_of(lab)
        pair = STYLES.get(ren) if len(by_ren[ren]) == 1 else None
        if pair is None or pair in used:
            pair = _SPARE[spare % len(_SPARE)]
            spare += 1
        used.add(pair)
        out[lab] = pair + ("-" if spare <= len(_SPARE) else "--",)
    return out
