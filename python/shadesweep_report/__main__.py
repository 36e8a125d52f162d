"""python3 -m shadesweep_report: what `shadesweep report` runs."""
import os
import sys

from .cli import main
from .loading import ME


def run():
    """main, with whatever escapes it as one line and exit 2 (a report of bad input
    or a bug, never a traceback; SHADESWEEP_REPORT_TRACEBACK=1 shows where)."""
    try:
        return main(sys.argv)
    except KeyboardInterrupt:
        print(f"{ME}: interrupted", file=sys.stderr)
        return 130
    except Exception as e:  # noqa: BLE001 - the last net: one line, exit 2
        if os.environ.get("SHADESWEEP_REPORT_TRACEBACK") == "1":
            raise
        where = f"{e.filename}: " if isinstance(e, OSError) and e.filename else ""
        what = (e.strerror if isinstance(e, OSError) and e.strerror else str(e)).splitlines()
        print(f"{ME}: {where}{what[0] if what else ''} ({e.__class__.__name__}; a bug if the "
              "input is shadesweep's own)", file=sys.stderr)
        return 2


sys.exit(run())
