"""shadesweep_report: the papers' tables beside ours (`shadesweep report DIR...`).

DIR holds one or more shadesweep output folders (each with plan.csv and summary.csv,
at any depth up to three). For every experiment the report knows (the `experiment`
column of summary.csv, also with a "-smoke" suffix) it writes, into OUTDIR/report.md,
the paper's table and ours in the same shape, the paper's claims computed for the
paper's numbers and for ours with a verdict (yes / partly / no), and plots into
OUTDIR/plots/. The papers' numbers come from results/reference/*.csv.

Modules: stats (numbers and statistics), text (markdown), reference (the papers'
tables), loading (output folders: CSVs, meta.yaml, sweep.yaml), plots, sections (one
module per paper section), cli (the command line and the report's frame); bench holds
what the README's benchmark scripts (scripts/bench-*.sh) share and is not the report's.
"""
