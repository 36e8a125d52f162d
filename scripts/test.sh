#!/usr/bin/env bash
# Set-up if needed, build, and run the whole suite twice: the normal build, and a
# build with AddressSanitizer + UndefinedBehaviorSanitizer. Ends with one line
# "N passed, N failed" (", N skipped" when any test skipped).
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
. scripts/say.sh   # on a terminal: what it is doing
say "test: checking the packages it needs (scripts/setup.sh)"
scripts/setup.sh || exit 1

# GL tests run on Mesa's llvmpipe, in debug contexts (tests/meson.build sets that).
export LIBGL_ALWAYS_SOFTWARE=1
export MESA_DEBUG=silent

status=0
logs=()
run_suite() {   # name builddir [meson setup options...]
  local name=$1 dir=$2; shift 2
  rm -f "$dir/meson-logs/testlog.json"   # a stale log must not count
  say "test: building the $name build ($dir)"
  if ! scripts/build.sh "$dir" "$@"; then
    echo "test: $name build failed" >&2
    status=1
    return
  fi
  echo "== $name: meson test" >&2
  meson test -C "$dir" --print-errorlogs --num-processes 2 >&2 || status=1
}

run_suite plain build
logs+=("build/meson-logs/testlog.json")
# The sanitizer build is optimised (-O2 -g, as the fuzz build): its checks are the same,
# and the suite runs in about half the time of an -O0 build, which CI's limit needs.
(
  export ASAN_OPTIONS=abort_on_error=0:detect_leaks=1:strict_string_checks=1
  export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
  run_suite sanitizers build-asan -Db_sanitize=address,undefined -Db_lundef=false \
    -Dbuildtype=debugoptimized
  exit $status
) || status=1
logs+=("build-asan/meson-logs/testlog.json")

# The manifest parser, then the scene loader, under libFuzzer (scripts/fuzz.sh; the
# README's reliability section has the long run). Seed 1337, from the seeds alone, a
# fixed number of inputs: every run of a commit starts with the same inputs, which a
# random time-bound run (SHADESWEEP_FUZZ_SEED= empty) does not. Counted as one test.
mkdir -p build-fuzz
fuzz_log=build-fuzz/ci-result.json
say "test: running the fuzzers (scripts/fuzz.sh, ${SHADESWEEP_FUZZ_SECONDS:-120} s)"
if FUZZ_SEED=${SHADESWEEP_FUZZ_SEED-1337} scripts/fuzz.sh "${SHADESWEEP_FUZZ_SECONDS:-120}" >&2; then
  echo '{"name": "fuzz-manifest", "result": "OK"}' > "$fuzz_log"
else
  echo '{"name": "fuzz-manifest", "result": "FAIL"}' > "$fuzz_log"
  status=1
fi
logs+=("$fuzz_log")

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
