#!/usr/bin/env python3
"""The product code's structure (issue 40), over runner/ renderers/ scenes/ results/ common/:
  (a) no include circle between files (a .c/.cpp, its .h and its _internal.h are one node);
  (b) runner/ includes nothing of renderers/ but RUNNER_MAY_INCLUDE;
  (c) no renderer's name (read from the registry, renderers/renderer.c) as a string
      literal in a strcmp/strncmp call outside the registry;
  (d) no product file over MAX_LINES lines;
  (e) runner/'s folders include one way, each only from those RUNNER_FOLDERS lets it
      (runner/meson.build links them as static libraries in that order).
Prints every violation as FILE:LINE: RULE and exits 1 if there is any.
Usage: check.py [SOURCE_ROOT] (default: two folders above this file)."""
import fnmatch
import os
import re
import sys

PRODUCT_DIRS = ("runner", "renderers", "scenes", "results", "common")
EXTENSIONS = (".c", ".h", ".cpp", ".def", ".inc")
REGISTRY = "renderers/renderer.c"
# What runner/ may include from renderers/ (fnmatch patterns, from the source root).
# the interface, the GL context, and the renderers' key tables (runner/manifest/params.def
# includes them into the one table of keys)
# and the device probe's one entry (runner/cli/probe.c, issue 38)
RUNNER_MAY_INCLUDE = ("renderers/renderer.h", "renderers/gl/context*.h", "renderers/keys.def",
                      "renderers/keys.h", "renderers/probe/probe.h")
MAX_LINES = 800
# runner/'s folders, each with the folders it may include from (runner/*/meson.build)
RUNNER_FOLDERS = {
    "manifest": (),
    "plan": ("manifest",),
    "folder": ("manifest",),
    "answer": ("folder", "plan", "manifest"),
    "trial": ("folder", "plan", "manifest"),
    "history": ("folder", "manifest"),
    "cli": ("history", "answer", "trial", "folder", "plan", "manifest"),
}

INCLUDE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*"([^"]+)"', re.M)
STRING = re.compile(r'"(?:[^"\\\n]|\\.)*"')
NAME = re.compile(r"^[a-z][a-z0-9]*(?:-[a-z0-9]+)*$")


def strip_comments(text):
    """text with every comment blanked (newlines kept, so line numbers hold)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(text[i:j + 1])
            i = j + 1
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def line_of(text, pos):
    return text.count("\n", 0, pos) + 1


def product_files(root):
    for top in PRODUCT_DIRS:
        for folder, dirs, names in os.walk(os.path.join(root, top)):
            dirs.sort()
            for name in sorted(names):
                if name.endswith(EXTENSIONS):
                    yield os.path.relpath(os.path.join(folder, name), root).replace(os.sep, "/")


def node(path):
    """A .c/.cpp, its .h and its X_internal.h (X's private half) are one node."""
    base, ext = os.path.splitext(path)
    if ext not in (".c", ".h", ".cpp"):
        return path
    return base[:-len("_internal")] if base.endswith("_internal") else base


def runner_folder(path):
    """The runner/ folder a file is in ("" outside runner/'s folders)."""
    parts = path.split("/")
    return parts[1] if len(parts) > 2 and parts[0] == "runner" else ""


def resolve(root, including, target, files):
    """The product file an #include "target" names, or None (system, generated)."""
    for cand in (os.path.join(os.path.dirname(including), target), target):
        cand = os.path.normpath(cand).replace(os.sep, "/")
        if cand in files:
            return cand
    return None


def renderer_names(root, sources):
    """The .name of every impl that the registry array of renderers/renderer.c lists."""
    reg = sources.get(REGISTRY)
    if reg is None:
        return []
    # the registry: a list of R(x) lines naming renderer_x_impl, or an array of &impl
    m = re.search(r"#\s*define\s+RENDERER_REGISTRY\(R\)((?:.*\\\n)*.*)", reg)
    if m:
        symbols = ["renderer_%s_impl" % x for x in re.findall(r"\bR\((\w+)\)", m.group(1))]
    else:
        m = re.search(r"registry\[\]\s*=\s*\{(.*?)\};", reg, re.S)
        symbols = re.findall(r"&\s*(\w+)", m.group(1)) if m else []
    names = []
    for sym in symbols:
        for path, text in sources.items():
            d = re.search(r"\b" + sym + r"\s*=\s*(\w+\s*\(|\{)", text)
            if not d:
                continue
            body = text[d.end():d.end() + 2000]
            macro = d.group(1).rstrip("( \t\n")
            if macro not in ("{", "RENDERER_IMPL"):   # a family's own macro: its #define
                md = re.search(r"#\s*define\s+" + macro + r"\s*\(", text)
                if md:
                    body = text[md.end():md.end() + 2000]
            field = re.search(r'\.name\s*=\s*"([^"]+)"', body)
            if field:
                names.append(field.group(1))
            else:
                lit = [s[1:-1] for s in STRING.findall(body) if NAME.match(s[1:-1])]
                if lit:
                    names.append(lit[0])
            break
    return names


def call_args(text, start):
    """The text between the '(' at start and its matching ')'."""
    depth, i = 0, start
    while i < len(text):
        if text[i] == '"':
            i = STRING.match(text, i).end() if STRING.match(text, i) else i + 1
            continue
        if text[i] == "(":
            depth += 1
        elif text[i] == ")":
            depth -= 1
            if depth == 0:
                return text[start + 1:i]
        i += 1
    return text[start + 1:]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", ".."))
    files = list(product_files(root))
    fileset = set(files)
    raw, code = {}, {}
    for f in files:
        with open(os.path.join(root, f), encoding="utf-8", errors="replace") as h:
            raw[f] = h.read()
        code[f] = strip_comments(raw[f])
    problems = []

    # (a) and (b): the include graph
    edges = {}   # node -> {node: (file, line)}
    for f in files:
        for m in INCLUDE.finditer(code[f]):
            target, line = m.group(1), line_of(code[f], m.start())
            dest = resolve(root, f, target, fileset)
            if f.startswith("runner/") and (dest or target).startswith("renderers/") \
                    and not any(fnmatch.fnmatch(dest or target, p) for p in RUNNER_MAY_INCLUDE):
                problems.append(f"{f}:{line}: (b) runner/ includes {dest or target} "
                                f"(runner/ may include of renderers/ only "
                                f"{', '.join(RUNNER_MAY_INCLUDE)})")
            if dest and node(dest) != node(f):
                edges.setdefault(node(f), {}).setdefault(node(dest), (f, line))
            src_dir, dst_dir = runner_folder(f), runner_folder(dest or "")
            if src_dir and dst_dir and dst_dir != src_dir \
                    and dst_dir not in RUNNER_FOLDERS.get(src_dir, ()):
                problems.append(f"{f}:{line}: (e) runner/{src_dir}/ includes {dest} "
                                f"(runner/{src_dir}/ may include from "
                                f"{', '.join(RUNNER_FOLDERS.get(src_dir, ())) or 'no other folder'})")
    for cycle, comp in circles(edges):
        where = edges[cycle[0]][cycle[1]]
        steps = " -> ".join(cycle + [cycle[0]])
        more = f" (one of the circles among {', '.join(comp)})" if len(comp) > len(cycle) else ""
        problems.append(f"{where[0]}:{where[1]}: (a) include circle: {steps}{more}")

    # (c): renderer names in string comparisons outside the registry
    names = renderer_names(root, code)
    if not names:   # rule (c) would hold vacuously: the registry's form changed
        problems.append(f"{REGISTRY}:1: (c) no renderer name found in the registry")
    if not names:
        problems.append(f"{REGISTRY}:1: (c) no renderer names read from the registry")
    for f in files:
        if f == REGISTRY:
            continue
        for m in re.finditer(r"\bstrn?cmp\s*\(", code[f]):
            args = call_args(code[f], m.end() - 1)
            for s in STRING.findall(args):
                if s[1:-1] in names:
                    problems.append(f"{f}:{line_of(code[f], m.start())}: (c) the renderer "
                                    f"name {s} compared outside the registry ({REGISTRY})")

    # (d): file length
    for f in files:
        n = raw[f].count("\n") + (0 if raw[f].endswith("\n") or not raw[f] else 1)
        if n > MAX_LINES:
            problems.append(f"{f}:{n}: (d) {n} lines, over {MAX_LINES}")

    for p in problems:
        print(p)
    print(f"structure: {len(files)} files, {len(names)} renderer names, "
          f"{len(problems)} violation(s)", file=sys.stderr)
    return 1 if problems else 0


def circles(edges):
    """(a cycle, its component) for every strongly connected component of more than
    one node (Tarjan's algorithm, iterative); the cycle is a shortest one."""
    index, low, on, stack, comps, counter = {}, {}, set(), [], [], [0]
    nodes = sorted(set(edges) | {d for e in edges.values() for d in e})
    for start in nodes:
        if start in index:
            continue
        work = [(start, iter(sorted(edges.get(start, {}))))]
        index[start] = low[start] = counter[0]; counter[0] += 1
        stack.append(start); on.add(start)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = counter[0]; counter[0] += 1
                    stack.append(w); on.add(w)
                    work.append((w, iter(sorted(edges.get(w, {})))))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop(); on.discard(w); comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    comps.append(sorted(comp))
    out = []
    for comp in comps:   # a shortest cycle through the component's first node
        members, first = set(comp), comp[0]
        prev, frontier = {first: None}, [first]
        found = None
        while frontier and not found:
            nxt = []
            for v in frontier:
                for w in sorted(edges.get(v, {})):
                    if w == first:
                        found = v
                        break
                    if w in members and w not in prev:
                        prev[w] = v
                        nxt.append(w)
                if found:
                    break
            frontier = nxt
        path, v = [], found
        while v is not None:
            path.append(v)
            v = prev[v]
        out.append((path[::-1], comp))
    return out


if __name__ == "__main__":
    sys.exit(main())
