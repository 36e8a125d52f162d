"""Plots (matplotlib, Agg), written into OUTDIR/plots/."""
import os



class Plots:
    def __init__(self, folder):
        self.folder = folder
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
        path = os.path.join(self.folder, name)
        fig.tight_layout()
        try:
            os.makedirs(self.folder, exist_ok=True)
            fig.savefig(path, dpi=110)
        except OSError as e:
            from .loading import die
            die(f"{path}: cannot write the plot: {e.strerror or e}")
        self.plt.close(fig)
        self.made.append(name)
        return f"![{name}](plots/{name})\n"


PLOT_NAMES = ["s003-exp2_fps_time.png", "s003-exp2_frametime_time.png",
              "s003-exp2_frametime_lights.png", "s000-resolution_frametime.png",
              "s000-drawcalls.png", "gbuffer-error_pareto.png",
              "gbuffer-error_bandwidth.png", "renderers-tiled_frametime_lights.png",
              "aa-translucency_error_time.png"]
COLORS = {"deferred": "tab:blue", "forward-spml": "tab:orange", "forward-mpml": "tab:red"}
