#!/usr/bin/env bash
# The README is a user's guide that must stay true (issue 24):
#  - every ```yaml block of README.md that is a whole manifest (it has the `shadesweep:`
#    schema key; fragments such as the file-scene example have not) validates;
#  - every repository path that README.md, docs/*.md and docs/results/*.md name exists:
#    tokens that start with a top-level entry of the source tree (scripts/, experiments/,
#    docs/, tests/, runner/, ...; `build*/` and `out/` are outputs, never checked),
#    anywhere in the text, and every relative link target (from the file's folder);
#    README.md's own #anchors must name one of its headings;
#  - `meson install` of this build into a temporary destdir gives a program that runs:
#    `version`, `validate`, `report --help`, with the report package, the papers'
#    tables, the image module and the bash completion installed beside it.
. "$(dirname "$0")/lib.sh"
cd "$T"

# 1. the README's manifests
"$PYTHON" - "$SOURCE_ROOT/README.md" "$T/manifests" <<'PY'
import os, re, sys
readme, out = sys.argv[1], sys.argv[2]
os.makedirs(out)
blocks = re.findall(r"^```yaml\n(.*?)^```", open(readme).read(), re.S | re.M)
n = 0
for b in blocks:
    if re.search(r"^shadesweep:", b, re.M):
        n += 1
        open(os.path.join(out, "readme-%d.yaml" % n), "w").write(b)
if n == 0:
    sys.exit("FAIL: README.md has no ```yaml manifest (a block with `shadesweep: 1`)")
PY
for m in "$T"/manifests/*.yaml; do
  "$SHADESWEEP" validate "$m" >validate.txt 2>&1 ||
    fail "README.md's manifest $(basename "$m") is invalid: $(cat validate.txt)"
done

# 2. the paths and links the README and the docs name
"$PYTHON" - "$SOURCE_ROOT" <<'PY' || fail "README.md or docs/ name paths that do not exist (above)"
import glob, os, re, sys
root = sys.argv[1]
# top-level entries of the source tree; build folders and outputs are not sources
tops = sorted(e for e in os.listdir(root)
              if not e.startswith(("build", "out", ".git")) and e not in ("subprojects",))
dirs = [e for e in tops if os.path.isdir(os.path.join(root, e))]
token = re.compile(r"(?<![\w./~$-])((?:%s)/[\w./*<>{}$@-]*)" % "|".join(map(re.escape, dirs)))
link = re.compile(r"\]\(([^)\s]+)\)")
skip = re.compile(r"[*<>{}$@]|\.\.\.")
# named on purpose though they are not in the tree
examples = {
    "scenes/a.obj",   # the user's scene file in a quoted `run --resume` message
}

def slug(h):
    h = re.sub(r"[^\w\- ]", "", h.strip().lower())
    return h.replace(" ", "-")

files = [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "docs", "*.md"))) \
    + sorted(glob.glob(os.path.join(root, "docs", "results", "*.md")))
bad = []
for f in files:
    text = open(f, encoding="utf-8").read()
    rel = os.path.relpath(f, root)
    anchors = {slug(m) for m in re.findall(r"^#+ (.*)$", text, re.M)}
    for m in token.finditer(text):
        p = m.group(1).rstrip(".,:;)'\"`")
        if skip.search(p) or p in examples:
            continue
        if not os.path.exists(os.path.join(root, p)):
            line = text.count("\n", 0, m.start()) + 1
            bad.append("%s:%d: %s does not exist" % (rel, line, p))
    for m in link.finditer(text):
        target = m.group(1)
        if re.match(r"[a-z]+:", target):
            continue
        path, _, anchor = target.partition("#")
        line = text.count("\n", 0, m.start()) + 1
        if not path:
            if rel == "README.md" and anchor not in anchors:
                bad.append("%s:%d: no heading for #%s" % (rel, line, anchor))
            continue
        if not os.path.exists(os.path.join(os.path.dirname(f), path)):
            bad.append("%s:%d: link %s does not exist" % (rel, line, path))
for b in bad:
    print("FAIL: " + b, file=sys.stderr)
sys.exit(1 if bad else 0)
PY

# 3. the installed program
build=${SHADESWEEP_BUILD_ROOT:-${SHADESWEEP%/runner/shadesweep}}
[ -f "$build/build.ninja" ] || fail "no build folder at $build"
meson install -C "$build" --no-rebuild --destdir "$T/dest" --quiet >install.txt 2>&1 ||
  fail "meson install: $(cat install.txt)"
exe=$(find "$T/dest" -path '*/bin/shadesweep' -type f | head -1)
[ -n "$exe" ] || fail "meson install put no bin/shadesweep under the destdir"
prefix=${exe%/bin/shadesweep}
for f in share/shadesweep/python/shadesweep_report/__main__.py share/shadesweep/reference/s003_exp1.csv \
         share/bash-completion/completions/shadesweep; do
  [ -f "$prefix/$f" ] || fail "meson install left out $f"
done
# the image module (common/image_codec.h), where the program looks for it: BINDIR/../LIBDIR
[ -n "$(find "$prefix" -path '*/lib*/shadesweep/shadesweep-image.so' -type f)" ] ||
  fail "meson install left out the image module shadesweep-image.so"
cd /   # nowhere near the source tree
"$exe" version | grep -q '^shadesweep ' || fail "installed shadesweep version"
"$exe" validate "$SOURCE_ROOT/experiments/smoke.yaml" >"$T/validate.txt" 2>&1 ||
  fail "installed shadesweep validate: $(cat "$T/validate.txt")"
"$exe" report --help >"$T/report.txt" 2>&1 || fail "installed shadesweep report --help: $(cat "$T/report.txt")"
grep -q 'usage: shadesweep report' "$T/report.txt" || fail "installed report --help: $(cat "$T/report.txt")"
# the installed report is the installed package (found beside the program), not the source tree's
# (a stand-in interpreter prints the PYTHONPATH the program gives it)
printf '#!/bin/sh\necho "$PYTHONPATH"\n' >"$T/py.sh"; chmod +x "$T/py.sh"
pp=$(env -u SHADESWEEP_PYDIR -u PYTHONPATH SHADESWEEP_PYTHON="$T/py.sh" "$exe" report x)
[ "$(cd "$pp" && pwd -P)" = "$(cd "$prefix/share/shadesweep/python" && pwd -P)" ] ||
  fail "the installed report runs the package at $pp, not the installed one"
echo "readme: $(ls "$T"/manifests | wc -l) manifest(s) valid, paths exist, install runs"
