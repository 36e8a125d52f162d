#!/usr/bin/env bash
# An independent check of the shading model (issue 13): a plane lit by one light per
# case (directional, point 1/d^2, spot, and grid point lights with linear-range,
# quadratic and windowed attenuation), seen by a glTF camera, rendered by every
# renderer; each screenshot is compared with seed 000 appendix D's Phong model evaluated on its own in
# numpy (shading_model.py: the formulas, the project's mappings it relies on, and the
# tolerance: max 1/255, RMSE 0.5/255 per case and renderer); and the env-* cases, the
# plane under the environment light with no lights (issue 36; max 3/255, RMSE 2/255).
. "$(dirname "$0")/lib.sh"
need_gl
"$PYTHON" -c "import numpy" 2>/dev/null ||
  { echo "SKIP: python3-numpy is not installed (scripts/setup.sh installs it)" >&2; exit 77; }
cd "$T"
PY="$SOURCE_ROOT/tests/cli/shading_model.py"
"$PYTHON" "$PY" gen . || fail "shading_model.py gen"
for c in directional point spot maps linear-range quadratic windowed \
         pbr-directional pbr-point pbr-spot pbr-maps pbr-linear-range pbr-quadratic \
         pbr-windowed env-phong env-pbr env-metal; do
  "$SHADESWEEP" run --debug-gl "$c.yaml" -o "out-$c" >"run-$c.txt" 2>&1 ||
    fail "run $c.yaml: $(tail -5 "run-$c.txt")"
done
"$PYTHON" "$PY" check . || fail "the renderers disagree with the shading model (above)"
