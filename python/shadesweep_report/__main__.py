"""python3 -m shadesweep_report: what `shadesweep report` runs."""
import sys

from .cli import main

sys.exit(main(sys.argv))
