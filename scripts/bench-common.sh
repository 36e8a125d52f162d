# Sourced by the benchmark scripts (scripts/bench-*.sh) after they set $root: the
# packages and the build they run on, llvmpipe unless the caller names a driver, and
# bench_table, which runs the script's table code (python on standard input) with the
# helpers of python/shadesweep_report/bench.py importable.
"$root/scripts/setup.sh"
"$root/scripts/build.sh" "$root/build"
export LIBGL_ALWAYS_SOFTWARE=${LIBGL_ALWAYS_SOFTWARE-1}
bench_table() {
  PYTHONPATH="$root/python${PYTHONPATH:+:$PYTHONPATH}" /usr/bin/python3 - "$@"
}
