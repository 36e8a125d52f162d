#!/usr/bin/env bash
# Installs the Debian packages shadesweep needs to build, run and test, when any is
# missing. Quiet when nothing needs installing. Safe to run any number of times.
set -euo pipefail
. "$(dirname "$0")/say.sh"

packages=(
  meson ninja-build pkg-config gcc g++
  ccache                                              # rebuilds of unchanged files (scripts/build.sh)
  libegl-dev libegl-mesa0 libgl-dev libgl1-mesa-dri   # EGL, GL headers, Mesa llvmpipe
  libosmesa6-dev                                      # the second backend
  libyaml-dev libopenimageio-dev
  libassimp-dev assimp-testmodels                    # file scenes (glTF 2.0, OBJ); their tests
  libcmocka-dev libcglm-dev                           # tests; cglm is the math oracle
  python3 python3-yaml python3-matplotlib             # end-to-end test checks; scripts/report
  python3-numpy                                       # the independent shading-model check
  python3-pandas                                      # tests/cli/tidy_pandas.sh: the files for scripts
  clang libclang-rt-14-dev                            # the manifest fuzzer (libFuzzer)
  valgrind                                            # meson test --setup=valgrind
  libsqlite3-dev libpq-dev                            # `history`: SQLite (default), PostgreSQL client
  postgresql                                          # tests/cli/history.sh's server
  time util-linux                                     # scripts/bench-measure.sh: /usr/bin/time, taskset
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [ "$status" = installed ] || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "setup: installing packages (apt-get): ${missing[*]}" >&2
sudo=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  sudo=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
say "setup: updating the package lists (apt-get update)"
"${sudo[@]}" apt-get update -qq >&2
say "setup: installing ${#missing[@]} packages (apt-get install)"
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
say "setup: done"
