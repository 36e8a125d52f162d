#!/usr/bin/env bash
# Fuzzes the manifest parser (tests/fuzz/fuzz_manifest.c) with libFuzzer for a
# bounded time, on one core.
#
#   scripts/fuzz.sh [SECONDS]        default 60
#
# Builds with clang in its own folder (FUZZ_BUILD, default build-fuzz): ASan +
# UBSan (any report aborts), coverage instrumentation on all C code, the target
# linked with -fsanitize=fuzzer. Seeds: every file under tests/data/ and
# experiments/ (read in place), plus what earlier runs found, kept in
# FUZZ_BUILD/corpus. Dictionary: tests/fuzz/yaml.dict.
#
# Exit status: 0 nothing found; 1 a finding (crash, sanitizer report, leak,
# timeout, out of memory, broken contract): the input is saved under
# FUZZ_BUILD/findings/ and the line to reproduce it is printed; 2 cannot build.
#
# Environment: FUZZ_BUILD, FUZZ_RSS_MB (memory limit, default 2048),
# FUZZ_TIMEOUT (seconds per input, default 10), FUZZ_ARGS (more libFuzzer flags).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"

secs=${1:-60}
case $secs in '' | *[!0-9]*) echo "usage: scripts/fuzz.sh [SECONDS]" >&2; exit 2 ;; esac
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

if [ ! -f "$build/build.ninja" ]; then
  echo "fuzz: configuring $build (clang, ASan+UBSan, libFuzzer)" >&2
  instr='-fsanitize=fuzzer-no-link -fno-sanitize-recover=undefined'
  setup_log=$(mktemp)
  if ! CC=clang CXX=clang++ meson setup "$build" \
      -Dbuildtype=debugoptimized -Db_sanitize=address,undefined -Db_lundef=false \
      -Dc_args="$instr" -Dcpp_args="$instr" >"$setup_log" 2>&1; then
    cat "$setup_log" >&2
    rm -f "$setup_log"
    echo "fuzz: meson setup failed" >&2
    exit 2
  fi
  rm -f "$setup_log"
fi
if ! ninja -C "$build" tests/fuzz/fuzz_manifest >"$build/fuzz-build.log" 2>&1; then
  cat "$build/fuzz-build.log" >&2
  echo "fuzz: build failed" >&2
  exit 2
fi

corpus="$build/corpus"
findings="$build/findings"
mkdir -p "$corpus" "$findings"
stamp="$build/fuzz.started"
touch "$stamp"

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
# Libraries linked in but never used by the target (Mesa, LLVM) may leak at exit.
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/tests/lsan.supp:print_suppressions=0}

echo "fuzz: fuzz_manifest for ${secs}s, one core, ${rss_mb} MB, ${per_input}s per input" >&2
log="$build/fuzz.log"
set +e
# shellcheck disable=SC2086  # FUZZ_ARGS is a list of flags
"$build/tests/fuzz/fuzz_manifest" \
  -max_total_time="$secs" -rss_limit_mb="$rss_mb" -malloc_limit_mb="$rss_mb" \
  -timeout="$per_input" -error_exitcode=1 -timeout_exitcode=1 \
  -dict=tests/fuzz/yaml.dict -artifact_prefix="$findings/" -print_final_stats=1 \
  ${FUZZ_ARGS:-} \
  "$corpus" tests/data experiments 2>&1 | tee "$log" | grep -E --line-buffered \
  '^(INFO: seed corpus|#[0-9]+[[:space:]]+(INITED|DONE|pulse)|stat::|==[0-9]+==|SUMMARY|fuzz_manifest:|artifact_prefix|Test unit written|Done [0-9]+ runs)' >&2
rc=${PIPESTATUS[0]}
set -e

if [ "$rc" -ne 0 ]; then
  echo "fuzz: FINDING (libFuzzer exit $rc); full log: $log" >&2
  find "$findings" -type f -newer "$stamp" | while read -r f; do
    echo "fuzz: reproduce with: $build/tests/fuzz/fuzz_manifest $f" >&2
  done
  exit 1
fi
echo "fuzz: nothing found; corpus $(find "$corpus" -type f | wc -l) files in $corpus" >&2
