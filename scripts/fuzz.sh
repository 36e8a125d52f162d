#!/usr/bin/env bash
# Fuzzes the manifest parser (tests/fuzz/fuzz_manifest.c) and the scene-file loader
# (tests/fuzz/fuzz_scene.c) with libFuzzer for a bounded time, one core each: side by
# side where there are two cores, else one after the other.
#   scripts/fuzz.sh [SECONDS]   default 60: the parser SECONDS, the scene loader as long
#                               side by side, half that one after the other
#   scripts/fuzz.sh --build     builds the targets only (scripts/test.sh builds them
#                               while the plain build's tests run)
# Exit status: 0 nothing found; 1 a finding (crash, sanitizer report, leak, timeout, out
# of memory, broken contract): the input is saved under FUZZ_BUILD/findings/ and the line
# to reproduce it is printed; 2 cannot build. Environment: FUZZ_BUILD (default
# build-fuzz), FUZZ_RSS_MB (memory limit, default 2048), FUZZ_TIMEOUT (seconds per input,
# default 10), FUZZ_ARGS (more libFuzzer flags), FUZZ_SCENE_SECONDS, and FUZZ_SEED for a
# seeded run (below, where it is read). The build, the seeds and the dictionary: below.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"

build_only=false
if [ "${1:-}" = --build ]; then build_only=true; shift; fi
secs=${1:-60}
case $secs in '' | *[!0-9]*) echo "usage: scripts/fuzz.sh [--build] [SECONDS]" >&2; exit 2 ;; esac
build=${FUZZ_BUILD:-build-fuzz}
rss_mb=${FUZZ_RSS_MB:-2048}
per_input=${FUZZ_TIMEOUT:-10}

for tool in clang clang++ meson ninja; do
  command -v "$tool" >/dev/null || {
    echo "fuzz: $tool not found (scripts/setup.sh installs it)" >&2
    exit 2
  }
done
# libFuzzer's runtime is a separate Debian package from clang (libclang-rt-14-dev).
if ! echo 'int LLVMFuzzerTestOneInput(const char *d, unsigned long n) { (void)d; return (int)n * 0; }' |
    clang -x c - -fsanitize=fuzzer -o /dev/null 2>/dev/null; then
  echo "fuzz: clang cannot link -fsanitize=fuzzer: libFuzzer missing (Debian: libclang-rt-14-dev)" >&2
  exit 2
fi

# Built with clang in its own folder: ASan + UBSan (any report aborts), coverage
# instrumentation on all C code, the target linked with -fsanitize=fuzzer.
if [ ! -f "$build/build.ninja" ]; then
  echo "fuzz: configuring $build (clang, ASan+UBSan, libFuzzer)" >&2
  instr='-fsanitize=fuzzer-no-link -fno-sanitize-recover=undefined'
  setup_log=$(mktemp)
  # through ccache where it is installed, as scripts/build.sh's builds
  cc=clang cxx=clang++
  if command -v ccache >/dev/null; then cc="ccache clang" cxx="ccache clang++"; fi
  if ! CC=$cc CXX=$cxx meson setup "$build" \
      -Dbuildtype=debugoptimized -Db_sanitize=address,undefined -Db_lundef=false \
      -Dc_args="$instr" -Dcpp_args="$instr" >"$setup_log" 2>&1; then
    cat "$setup_log" >&2
    rm -f "$setup_log"
    echo "fuzz: meson setup failed" >&2
    exit 2
  fi
  rm -f "$setup_log"
fi
# the image module too: the scene loader decodes embedded textures through it
export CCACHE_BASEDIR=$root CCACHE_NOHASHDIR=true
if ! ninja -C "$build" tests/fuzz/fuzz_manifest tests/fuzz/fuzz_scene common/shadesweep-image.so \
    >"$build/fuzz-build.log" 2>&1; then
  cat "$build/fuzz-build.log" >&2
  echo "fuzz: build failed" >&2
  exit 2
fi
$build_only && exit 0

# With two cores the targets run side by side (below), the scene loader for as long as
# the parser; on one core one after the other, the scene loader for half as long.
if [ "$(nproc)" -ge 2 ]; then default_scene=$secs; else default_scene=$((secs / 2)); fi
scene_secs=${FUZZ_SCENE_SECONDS:-$default_scene}
case $scene_secs in '' | *[!0-9]*) echo "fuzz: FUZZ_SCENE_SECONDS: not a number" >&2; exit 2 ;; esac
# Seeds: every file under tests/data/ (read in place) and experiments/ (copied: below),
# plus what earlier runs found, kept in FUZZ_BUILD/corpus (scenes: tests/fuzz/scene_seeds/ and
# FUZZ_BUILD/corpus-scene). Dictionary: tests/fuzz/yaml.dict.
findings="$build/findings"
corpus=$build/corpus corpus_scene=$build/corpus-scene
flags=() scene_flags=() launch=() rss_limit=$rss_mb
# FUZZ_SEED=N makes a seeded run (scripts/test.sh, CI): libFuzzer's random seed is N,
# each target starts from the seeds alone (the corpus of earlier runs is left out; what
# this run finds goes to FUZZ_BUILD/corpus-seed*, emptied first) and stops after
# FUZZ_RUNS executions (manifest, default 15000) and FUZZ_SCENE_RUNS (scenes, default
# 2000), with address randomisation and libFuzzer's RSS watchdog thread off
# (FUZZ_RSS_MB then bounds each allocation, not the total). SECONDS is then only a
# limit: where it cuts a target short, the script says so. Runs of the same build start
# with the same inputs and part after some thousand (heap addresses among the values
# the fuzzer compares): closer to repeatable than a random run, not yet repeatable.
seed=${FUZZ_SEED:-}
if [ -n "$seed" ]; then
  runs=${FUZZ_RUNS:-15000} scene_runs=${FUZZ_SCENE_RUNS:-2000}
  for v in "$seed" "$runs" "$scene_runs"; do
    case $v in '' | *[!0-9]*) echo "fuzz: FUZZ_SEED, FUZZ_RUNS, FUZZ_SCENE_RUNS: not a number" >&2; exit 2 ;; esac
  done
  corpus=$build/corpus-seed corpus_scene=$build/corpus-scene-seed
  rm -rf "$corpus" "$corpus_scene"
  flags=(-seed="$seed" -runs="$runs")
  scene_flags=(-seed="$seed" -runs="$scene_runs")
  # Off here, as they made the same seed keep other inputs from run to run: libFuzzer's
  # RSS watchdog, a thread whose allocations land inside an input's malloc count (an
  # extra leak-check run), and address-space randomisation (it changed the scene
  # target's coverage of its very seeds). Left on: libFuzzer's use of compared values
  # (-use_cmp), one of its strongest guides, though their operands hold heap addresses
  # that differ from run to run (off, 6,000 manifest inputs were the same on every run
  # here, 15,000 were not).
  rss_limit=0
  if setarch "$(uname -m)" -R true 2>/dev/null; then
    launch=(setarch "$(uname -m)" -R)
  else
    echo "fuzz: setarch -R is not permitted here: address randomisation stays on, and a" \
      "seeded run may keep other inputs than elsewhere" >&2
  fi
fi
mkdir -p "$corpus" "$corpus_scene" "$findings"

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:strict_string_checks=1}
# The scene target without strict_string_checks: assimp 5.2's OBJ importer (not ours, and
# not built with ASan) hands strtol a line that is not NUL-terminated (an OBJ of one line
# "p 1 2 3 4 5 6 7"), which the strict check reports as a read to the string's end, though
# strtol stops at the line's end inside the buffer. Without it ASan still checks the bytes
# strtol does read; our own string code keeps the strict check in the manifest target,
# the replays of both targets' seeds and every test of the sanitizer build.
scene_asan=${ASAN_OPTIONS//strict_string_checks=1/strict_string_checks=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
# Libraries linked in but never used by the target (Mesa, LLVM) may leak at exit.
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/tests/lsan.supp:print_suppressions=0}

# fuzz TARGET SECONDS CORPUS [SEEDS / FLAGS...]: 0, or 1 on a finding
fuzz() {
  local target=$1 t=$2 corpus=$3 stamp="$build/$1.started" log="$build/$1.log" rc
  shift 3
  [ "$t" -gt 0 ] || return 0
  touch "$stamp"
  local want
  want=$(printf '%s\n' "$@" | sed -n 's/^-runs=//p')
  echo "fuzz: $target ${want:+$want runs (seed $seed), at most }${t}s, one core, ${rss_mb} MB, ${per_input}s per input" >&2
  set +e
  # shellcheck disable=SC2086  # FUZZ_ARGS is a list of flags
  ${launch[@]+"${launch[@]}"} "$build/tests/fuzz/$target" \
    -max_total_time="$t" -rss_limit_mb="$rss_limit" -malloc_limit_mb="$rss_mb" \
    -timeout="$per_input" -error_exitcode=1 -timeout_exitcode=1 \
    -artifact_prefix="$findings/$target-" -print_final_stats=1 \
    ${FUZZ_ARGS:-} \
    "$corpus" "$@" 2>&1 | tee "$log" | grep -E --line-buffered \
    '^(INFO: seed corpus|#[0-9]+[[:space:]]+(INITED|DONE|pulse)|stat::|==[0-9]+==|SUMMARY|fuzz_(manifest|scene):|artifact_prefix|Test unit written|Done [0-9]+ runs)' >&2
  rc=${PIPESTATUS[0]}
  set -e
  if [ "$rc" -ne 0 ]; then
    echo "fuzz: FINDING in $target (libFuzzer exit $rc); full log: $log" >&2
    find "$findings" -type f -newer "$stamp" | while read -r f; do
      echo "fuzz: reproduce with: $build/tests/fuzz/$target $f" >&2
    done
    return 1
  fi
  echo "fuzz: $target: nothing found; corpus $(find "$corpus" -type f | wc -l) files in $corpus" >&2
  local ran
  ran=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  if [ -n "$want" ] && [ "${ran:-0}" -lt "$want" ]; then
    echo "fuzz: $target: the ${t}s limit stopped it after ${ran:-0} of $want runs: not the full seeded run" >&2
  fi
}

# experiments/ as seeds, but modern-culling.yaml: its plan (204 runs, a third over a glTF
# file) takes longer than an input may under ASan; tests/data/good/blocks.yaml seeds the
# sweep of blocks
exp_seeds=$build/seeds-experiments
rm -rf "$exp_seeds"
mkdir -p "$exp_seeds"
for f in experiments/*.yaml; do
  [ "$f" = experiments/modern-culling.yaml ] || cp "$f" "$exp_seeds/"
done
status=0
if [ "$(nproc)" -ge 2 ]; then
  # Two cores: the two targets at once, one core each (each run is single-threaded).
  fuzz fuzz_manifest "$secs" "$corpus" ${flags[@]+"${flags[@]}"} -dict=tests/fuzz/yaml.dict \
    tests/data "$exp_seeds" &
  manifest_pid=$!
  ASAN_OPTIONS=$scene_asan fuzz fuzz_scene "$scene_secs" "$corpus_scene" \
    ${scene_flags[@]+"${scene_flags[@]}"} tests/fuzz/scene_seeds &
  scene_pid=$!
  wait "$manifest_pid" || status=1
  wait "$scene_pid" || status=1
else
  fuzz fuzz_manifest "$secs" "$corpus" ${flags[@]+"${flags[@]}"} -dict=tests/fuzz/yaml.dict \
    tests/data "$exp_seeds" || status=1
  ASAN_OPTIONS=$scene_asan fuzz fuzz_scene "$scene_secs" "$corpus_scene" \
    ${scene_flags[@]+"${scene_flags[@]}"} tests/fuzz/scene_seeds || status=1
fi
exit $status
