#!/usr/bin/env bash
# GPU clocks from NVML into each trial's meta.yaml (issue 38, item 3; common/nvml.h):
# with tests/unit/nvml_standin.c standing in for libnvidia-ml.so.1 (its path is the
# argument), every trial's meta.yaml has a clocks: block with the scripted values, the
# throttle bits by name and an unreadable quantity's NVML message, and the sweep prints
# no line about clocks; without a library (this machine) no trial's meta.yaml has the
# block and the sweep says so in exactly one line, whatever its number of trials.
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
echo ok
