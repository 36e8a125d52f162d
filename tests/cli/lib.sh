# Shared by the CLI tests: strict mode, a scratch folder, and failure reporting.
set -euo pipefail
: "${SHADESWEEP:?run through meson test}"
: "${SOURCE_ROOT:?run through meson test}"
T=$(mktemp -d /tmp/shadesweep-test.XXXXXX)
# device profiles (shadesweep probe) cached here, never in the user's cache; Mesa's
# shader cache stays where it was (it is under XDG_CACHE_HOME too): a cold one a test
# would compile every shader again
export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}}"
export XDG_CACHE_HOME="$T/cache"
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
# tree DIR: every file and link under DIR with its checksum or its target (what
# "untouched" means to the tests of output folders)
tree() {
  (cd "$1" && find . \( -type f -o -type l \) -print0 | sort -z |
    while IFS= read -r -d '' f; do
      if [ -L "$f" ]; then echo "$f -> $(readlink "$f")"; else md5sum "$f"; fi
    done)
}
# expect RC MESSAGE CMD...: exit status RC and MESSAGE (a fixed string) on stderr
expect() {
  local want=$1 msg=$2; shift 2
  set +e
  "$@" >"$T/cmd.out" 2>"$T/cmd.err"; local rc=$?
  set -e
  [ $rc -eq "$want" ] || fail "$*: exit $rc, want $want: $(cat "$T/cmd.err")"
  grep -qF -- "$msg" "$T/cmd.err" || fail "$*: no '$msg' in: $(cat "$T/cmd.err")"
}
