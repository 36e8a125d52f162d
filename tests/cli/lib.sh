# Shared by the CLI tests: strict mode, a scratch folder, and failure reporting.
set -euo pipefail
: "${SHADESWEEP:?run through meson test}"
: "${SOURCE_ROOT:?run through meson test}"
T=$(mktemp -d /tmp/shadesweep-test.XXXXXX)
trap 'rm -rf "$T"' EXIT
# Debian's python3 (scripts/setup.sh installs it with python3-yaml), not whatever is on PATH.
PYTHON=/usr/bin/python3
fail() { echo "FAIL: $*" >&2; exit 1; }
# Skip (77) when no EGL display can be had at all: the GL parts cannot run here.
need_gl() {
  if ! "$SHADESWEEP" info >"$T/info.txt" 2>&1; then
    echo "SKIP: no GL context: $(cat "$T/info.txt")" >&2
    exit 77
  fi
}
