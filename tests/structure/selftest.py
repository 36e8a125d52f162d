#!/usr/bin/env python3
"""check.py on a made-up tree with one violation of each rule, and on a clean one: it must
name exactly those (FILE:LINE: rule), and pass the clean tree."""
import os
import subprocess
import sys
import tempfile

CHECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "check.py")
REGISTRY = """#include "renderers/renderer.h"
static const renderer_impl *const registry[] = {
    &renderer_a_impl,
    &renderer_b_impl,
};
int find(const char *n) { return strcmp(n, "alpha") == 0; }
"""
CLEAN = {
    "renderers/renderer.c": REGISTRY,
    "renderers/renderer.h": "#pragma once\n",
    "renderers/a.c": 'const renderer_impl renderer_a_impl = RENDERER_IMPL(a, "alpha", "x y");\n',
    "renderers/b.c": ('#define FAMILY(R) RENDERER_IMPL(b, "beta-2", R)\n'
                      'const renderer_impl renderer_b_impl = FAMILY("reads");\n'),
    "renderers/gl/context.h": "#pragma once\n",
    "runner/trial/run.c": ('#include "runner/trial/run.h"\n#include "runner/trial/run_internal.h"\n'
                     '#include "renderers/renderer.h"\n#include "renderers/gl/context.h"\n'
                     '/* strcmp(x, "alpha") in a comment */\n'),
    "runner/trial/run.h": "#pragma once\n",
    "runner/trial/run_internal.h": '#include "run.h"\n',
    "scenes/x.c": '#include "scenes/x.h"\nint f(const char *s) { return strcmp(s, "gamma"); }\n',
    "scenes/x.h": '#include "results/y.h"\n',
    "results/y.h": "#pragma once\n",
}
BAD = dict(CLEAN)
BAD.update({
    "results/y.h": '#pragma once\n#include "scenes/x.h"\n',                  # (a) x -> y -> x
    "runner/trial/run.c": CLEAN["runner/trial/run.c"] + '#include "renderers/frame/shading.h"\n',  # (b)
    "renderers/frame/shading.h": "#pragma once\n",
    "scenes/z.c": "int g(const char *s)\n{\n    return !strncmp(s, \"beta-2\", 6);\n}\n",  # (c)
    "common/long.inc": "x\n" * 801,                                          # (d)
    "runner/manifest/m.c": '#include "runner/trial/run.h"\n',               # (e) upward
})
WANT = sorted([
    "results/y.h:2: (a)",
    "runner/trial/run.c:6: (b)",
    "scenes/z.c:3: (c)",
    "common/long.inc:801: (d)",
    "runner/manifest/m.c:1: (e)",
])


def run(tree):
    with tempfile.TemporaryDirectory() as root:
        for path, text in tree.items():
            os.makedirs(os.path.join(root, os.path.dirname(path)), exist_ok=True)
            with open(os.path.join(root, path), "w") as f:
                f.write(text)
        p = subprocess.run([sys.executable, CHECK, root], capture_output=True, text=True)
        return p.returncode, p.stdout.splitlines()


rc, lines = run(CLEAN)
if rc != 0 or lines:
    sys.exit(f"FAIL: the clean tree: rc {rc}: {lines}")
rc, lines = run(BAD)
got = sorted(" ".join(l.split(" ")[:2]) for l in lines)
if rc != 1 or got != WANT:
    sys.exit(f"FAIL: the bad tree: rc {rc}\n  got  {got}\n  want {WANT}\n" + "\n".join(lines))
print("structure selftest: ok")
