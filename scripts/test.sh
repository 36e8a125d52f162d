#!/usr/bin/env bash
# Set-up if needed, build, and test in tiers (tests/meson.build's suites; README's
# "Install" says which command runs which). With no option (CI): the plain build's
# quick, full and slow tiers two at a time, less the suite `asan` (the ASan + UBSan and
# fuzz builds made meanwhile at the lowest priority), then its timing tier alone; the
# sanitizer build's suite `asan` (unit, GL, fuzz replay, the CLI tests that parse or do
# I/O); the seeded fuzzers. Each test runs once: where the sanitizer build runs it, only
# there (tests/meson.build says why).
#   --quick   the quick tier on the plain build only (a developer's few minutes)
#   --plain   every tier on the plain build only (no sanitizers, no fuzzers)
# Ends with one line "N passed, N failed" (", N skipped" when any test skipped).
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
mode=ci
case ${1:-} in
  '') ;;
  --quick) mode=quick ;;
  --plain) mode=plain ;;
  *) echo "usage: scripts/test.sh [--quick | --plain]" >&2; exit 2 ;;
esac
. scripts/say.sh   # on a terminal: what it is doing
say "test: checking the packages it needs (scripts/setup.sh)"
scripts/setup.sh || exit 1

# GL tests run on Mesa's llvmpipe, in debug contexts (tests/meson.build sets that).
export LIBGL_ALWAYS_SOFTWARE=1
export MESA_DEBUG=silent

status=0
logs=()
build() {   # name builddir [meson setup options...]
  local name=$1 dir=$2; shift 2
  rm -f "$dir"/meson-logs/testlog*.json   # a stale log must not count
  say "test: building the $name build ($dir)"
  scripts/build.sh "$dir" "$@" && return 0
  echo "test: $name build failed" >&2
  logs+=("$dir/meson-logs/missing-$name.json")   # counted as one failure
  status=1
  return 1
}
tier() {   # builddir logname processes suite... [-suite...]: meson test over those
  local dir=$1 log=$2 procs=$3; shift 3   # suites, less the tests of any -suite
  local suites=() s
  for s in "$@"; do
    case $s in -*) suites+=(--no-suite "${s#-}") ;; *) suites+=(--suite "$s") ;; esac
  done
  echo "== $dir: meson test ${*} ($procs at a time)" >&2
  meson test -C "$dir" --print-errorlogs --num-processes "$procs" --logbase "$log" \
    "${suites[@]}" >&2 || status=1
  logs+=("$dir/meson-logs/$log.json")
}

sanitize_opts=(-Db_sanitize=address,undefined -Db_lundef=false -Dbuildtype=debugoptimized)
bg=
if build plain build; then
  if [ $mode = ci ]; then
    # The sanitizer and fuzz builds, at the lowest priority, while the plain build's tests
    # run: the tests go first, and the CPU they leave (a test waiting, the last test
    # alone) is no longer idle. Measured: the plain tiers ~2.5 min longer, the builds ~6
    # min shorter after them. Their outcome is read below, after `wait`.
    bgdir=$(mktemp -d)
    rm -f build-asan/meson-logs/testlog*.json
    ( nice -n 19 scripts/build.sh build-asan "${sanitize_opts[@]}" >"$bgdir/asan.log" 2>&1
      echo $? >"$bgdir/asan.rc"
      nice -n 19 scripts/fuzz.sh --build >"$bgdir/fuzz.log" 2>&1
      echo $? >"$bgdir/fuzz.rc" ) &
    bg=$!
    say "test: building the sanitizer and fuzz builds in the background (nice 19)"
  fi
  if [ $mode = quick ]; then
    tier build testlog-quick 2 quick
  else
    if [ $mode = ci ]; then
      # the suite asan runs under the sanitizers below: the same code and assertions at
      # -O2, memory and undefined behaviour checked too
      tier build testlog-main 2 quick full slow -asan
    else
      tier build testlog-main 2 quick full slow
    fi
    if [ -n "$bg" ]; then wait "$bg"; bg=waited; fi
    # Assertions on measured time, one test at a time on an otherwise idle machine.
    tier build testlog-timing 1 timing
  fi
fi
if [ $mode = ci ]; then
  if [ -n "$bg" ]; then
    [ "$bg" = waited ] || wait "$bg"
  else   # the plain build failed: the others in the foreground
    bgdir=$(mktemp -d)
    scripts/build.sh build-asan "${sanitize_opts[@]}" >"$bgdir/asan.log" 2>&1; echo $? >"$bgdir/asan.rc"
    scripts/fuzz.sh --build >"$bgdir/fuzz.log" 2>&1; echo $? >"$bgdir/fuzz.rc"
  fi
  # The sanitizer build is optimised (-O2 -g, as the fuzz build): its checks are the
  # same, at about half the time of an -O0 build. It runs the suite `asan` only:
  # tests/meson.build says which tests and why.
  if [ "$(cat "$bgdir/asan.rc" 2>/dev/null)" = 0 ]; then
    # (tests/meson.build's test environment says the same, and why the last one)
    export ASAN_OPTIONS=abort_on_error=0:detect_leaks=1:strict_string_checks=1:intercept_tls_get_addr=0
    export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
    tier build-asan testlog-asan 2 asan
    unset ASAN_OPTIONS UBSAN_OPTIONS
  else
    cat "$bgdir/asan.log" >&2
    echo "test: sanitizers build failed" >&2
    logs+=("build-asan/meson-logs/missing-sanitizers.json")   # counted as one failure
    status=1
  fi

  # The manifest parser and the scene loader under libFuzzer (scripts/fuzz.sh; the
  # README's reliability section has the long run). Seed 1337, from the seeds alone, a
  # fixed number of inputs: every run of a commit starts with the same inputs, which a
  # random time-bound run (SHADESWEEP_FUZZ_SEED= empty) does not. Counted as one test.
  mkdir -p build-fuzz
  fuzz_log=build-fuzz/ci-result.json
  say "test: running the fuzzers (scripts/fuzz.sh, ${SHADESWEEP_FUZZ_SECONDS:-120} s)"
  if [ "$(cat "$bgdir/fuzz.rc" 2>/dev/null)" != 0 ]; then
    cat "$bgdir/fuzz.log" >&2
    echo '{"name": "fuzz-manifest", "result": "FAIL"}' > "$fuzz_log"
    status=1
  elif FUZZ_SEED=${SHADESWEEP_FUZZ_SEED-1337} scripts/fuzz.sh "${SHADESWEEP_FUZZ_SECONDS:-120}" >&2; then
    echo '{"name": "fuzz-manifest", "result": "OK"}' > "$fuzz_log"
  else
    echo '{"name": "fuzz-manifest", "result": "FAIL"}' > "$fuzz_log"
    status=1
  fi
  logs+=("$fuzz_log")
  rm -rf "$bgdir"
fi

/usr/bin/python3 - "${logs[@]}" <<'PY'
import json, sys, os
passed = failed = skipped = 0
for path in sys.argv[1:]:
    if not os.path.exists(path):
        failed += 1
        continue
    with open(path) as f:
        for line in f:
            if not line.strip():
                continue
            r = json.loads(line).get("result", "")
            if r in ("OK", "EXPECTEDFAIL"):
                passed += 1
            elif r == "SKIP":
                skipped += 1
            else:
                failed += 1
line = f"{passed} passed, {failed} failed"
if skipped:
    line += f", {skipped} skipped"
print(line)
sys.exit(1 if failed else 0)
PY
py=$?
[ $py -ne 0 ] && status=1
exit $status
