#!/usr/bin/env bash
# GPU clocks from NVML into each trial's meta.yaml (issue 38, item 3; common/nvml.h):
# with tests/unit/nvml_standin.c standing in for libnvidia-ml.so.1 (its path is the
# argument), every trial's meta.yaml has a clocks: block with the scripted values, the
# throttle bits by name and an unreadable quantity's NVML message, and the sweep prints
# no line about clocks; without a library (this machine) no trial's meta.yaml has the
# block and the sweep says so in exactly one line, whatever its number of trials.
# summary.csv's sm_clock_mhz holds each trial's median SM clock, and `compare` flags the
# runs (folders) and rounds (--exe) whose clocks differ by more than 2%, with GPU time at
# BASE's clock beside the raw ratio; without clocks it says nothing of them.
. "$(dirname "$0")/lib.sh"
need_gl
STANDIN=${1:?the stand-in library}
cd "$T"
cat >tiny.yaml <<'YAML'
shadesweep: 1
name: tiny
scene: shapes
renderers: [null]
resolution: 16x16
trials: 2
warmup: {frames: 0}
duration: {frames: 3}
clock: fixed
outputs: {seconds: false}
YAML

SHADESWEEP_NVML_LIBRARY="$STANDIN" STANDIN_NVML_SM=1755 STANDIN_NVML_MEM=1593 \
  STANDIN_NVML_POWER=287500 STANDIN_NVML_TEMP=58 STANDIN_NVML_THROTTLE=0x21 \
  STANDIN_NVML_NAMES="NVIDIA Stand-in" "$SHADESWEEP" run -o with tiny.yaml >with.out 2>with.err ||
  fail "run with the stand-in: $(cat with.err)"
! grep -q '^clocks:' with.err || fail "a device, yet a line on clocks: $(cat with.err)"
SHADESWEEP_NVML_LIBRARY="$STANDIN" STANDIN_NVML_POWER='!3' \
  "$SHADESWEEP" run -o nopower tiny.yaml >nopower.out 2>nopower.err ||
  fail "run without power: $(cat nopower.err)"
SHADESWEEP_NVML_LIBRARY="$T/no/libnvidia-ml.so.1" \
  "$SHADESWEEP" run -o without tiny.yaml >without.out 2>without.err ||
  fail "run without NVML: $(cat without.err)"
[ "$(grep -c '^clocks: ' without.err)" -eq 1 ] &&
  grep -qx "clocks: not recorded: $T/no/libnvidia-ml.so.1 cannot be loaded (no NVIDIA driver)" \
    without.err || fail "no NVML: want one line: $(cat without.err)"

"$PYTHON" - <<'PY' || fail "meta.yaml"
import glob, yaml
def meta(folder):
    found = glob.glob(folder + "/runs/*/meta.yaml")
    assert len(found) == 1, found
    m = yaml.safe_load(open(found[0]))
    assert "clocks" not in m, "the run's own: each trial's is in trials"
    assert [t["trial"] for t in m["trials"]] == [1, 2], m["trials"]
    return m
for t in meta("with")["trials"]:
    c = t["clocks"]
    assert c["source"] == "nvml" and c["device"] == "NVIDIA Stand-in", c
    assert c["uuid"] == "GPU-00000000-stand-in" and c["matched_by"] == "none", c   # llvmpipe
    assert c["interval_ms"] == 100 and c["samples"] >= 2, c   # the start and the end
    for k in ("start", "end"):
        assert c[k] == {"sm_mhz": 1755, "mem_mhz": 1593, "power_w": 287.5, "temp_c": 58,
                        "throttle": ["gpu_idle", "sw_thermal_slowdown"]}, (k, c[k])
    assert c["median"] == {"sm_mhz": 1755, "mem_mhz": 1593, "power_w": 287.5,
                           "temp_c": 58}, c["median"]
    assert c["throttle_seen"] == ["gpu_idle", "sw_thermal_slowdown"], c
    assert c["unread"] == [], c
for t in meta("nopower")["trials"]:
    c = t["clocks"]
    assert c["start"]["power_w"] is None and c["median"]["power_w"] is None, c
    assert c["start"]["sm_mhz"] == 1980, c
    assert c["start"]["throttle"] == ["gpu_idle", "sw_power_cap"], c
    assert c["unread"] == ["nvmlDeviceGetPowerUsage: Not Supported"], c
plain, with_ = meta("without"), meta("with")
assert all("clocks" not in t for t in plain["trials"]), plain["trials"]
# otherwise the same keys, in the same order, as with the stand-in
assert list(plain) == list(with_), (list(plain), list(with_))
assert [list(t) for t in plain["trials"]] == \
    [[k for k in t if k != "clocks"] for t in with_["trials"]], plain["trials"]
PY

# compare: two folders at 1980 and 1755 MHz (-11.4%); --exe, paired, at 1700 against 1980
cat >gpu.yaml <<'YAML'
shadesweep: 1
name: gpu
scene: shapes
renderers: [forward-spml]
resolution: 16x16
trials: 3
warmup: {frames: 0}
duration: {frames: 2}
clock: fixed
lights: {count: 2}
outputs: {seconds: false, frames: false}
YAML
export SHADESWEEP_NVML_LIBRARY="$STANDIN"
for c in 1980 1755; do
  STANDIN_NVML_SM=$c "$SHADESWEEP" run -o "g$c" gpu.yaml >/dev/null 2>"g$c.err" ||
    fail "run at $c MHz: $(cat "g$c.err")"
done
"$SHADESWEEP" compare g1980 g1755 >cmp.md 2>cmp.err; rc=$?
[ $rc -le 1 ] || fail "compare exited $rc: $(cat cmp.err)"
"$SHADESWEEP" compare --json g1980 g1755 >cmp.json 2>/dev/null
grep -q '^\*\*GPU clocks\*\* (NVML, each trial.s median SM clock): 1 of 1 run ran at clocks more than 2% apart' cmp.md ||
  fail "compare names no clocks apart: $(cat cmp.md)"
grep -q '| 1980 | 1755 | .* | \*\*-11.4%\*\* |$' cmp.md || fail "clock row: $(grep -A3 'GPU clocks' cmp.md)"
printf '#!/bin/sh\nSTANDIN_NVML_SM=1700 exec "%s" "$@"\n' "$SHADESWEEP" >other.sh
chmod +x other.sh
STANDIN_NVML_SM=1980 "$SHADESWEEP" compare --exe ./other.sh -o exe gpu.yaml >exe.md 2>exe.err ||
  [ $? -eq 1 ] || fail "compare --exe: $(tail -3 exe.err)"
grep -q 'rounds 1, 2, 3 |$' exe.md || fail "compare --exe flags no rounds: $(grep -A4 'GPU clocks' exe.md)"
unset SHADESWEEP_NVML_LIBRARY
"$SHADESWEEP" compare without without >none.md 2>/dev/null
! grep -q "GPU clocks" none.md || fail "clocks named without clocks: $(cat none.md)"
"$PYTHON" - <<'PY' || fail "summary.csv's sm_clock_mhz, or compare's JSON"
import csv, json
for folder, want in (("g1980", "1980.0"), ("g1755", "1755.0"), ("without", "")):
    rows = [r for r in csv.DictReader(open(folder + "/summary.csv")) if r["trial"]]
    assert rows and all(r["sm_clock_mhz"] == want for r in rows), (folder, rows)
r = json.load(open("cmp.json"))["runs"][0]
assert r["base_sm_mhz"] == 1980 and r["new_sm_mhz"] == 1755 and r["clocks_apart"] == 1, r
# the same clock in every trial: at BASE's clock is the raw GPU ratio x 1755 / 1980
assert r["gpu_ratio"] > 0 and abs(r["gpu_ratio_at_base_clock"] / r["gpu_ratio"] - 1755 / 1980) < 1e-9, r
PY
echo ok
