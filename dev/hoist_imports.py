"""Move function-level imports of plxtools modules to the top of their module where nothing is lost
(issue 38): re-runnable after a merge, then review the diff and run the tests.

    python dev/hoist_imports.py      # rewrites plxtools/ in place; prints the modules it changed

An import moves only when (dev/import_graph.py) its module and the imported one are in no import
circle, the imported one brings no MuJoCo, numpy, pygls or lsprotocol the module does not already
load at its top, no test patches the imported name (PATCHED, from `monkeypatch.setattr` in
tests/), no comment on or above it gives a reason to stay (REASON), and the function keeps a body.
Start-critical modules are left alone (SKIP_SOURCES, and model/, syntax/, config, envpath below
rules, where `plx lint` and `plx fmt` start).
"""

from __future__ import annotations

import ast
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import import_graph as g  # noqa: E402

HEAVY = ("mujoco", "numpy", "pygls", "lsprotocol", "scipy", "PIL", "matplotlib", "pyglet", "moderngl", "glfw")
PATCHED = {"steps", "_mark_pinned", "layout_tree", "_owned_by_lint", "RACY_NS", "holds", "read_bytes", "write", "Workspace"}
SKIP_SOURCES = ("plxtools.model", "plxtools.syntax", "plxtools.config", "plxtools.envpath",
                "plxtools.rules.registry", "plxtools.model.completeness", "plxtools.cli", "plxtools.__main__", "plxtools.fmt", "plxtools.docgen", "plxtools.lint.cli",
                "plxtools.bundles_cli", "plxtools.check.cli", "plxtools.runmode", "plxtools.runmemo", "plxtools.view")
REASON = re.compile(r"lazy|start|import time|not at the top|circular|cycle|cost|only when|only if|heavy|slow|mujoco|numpy|pygls", re.I)

known = g.modules()
edges, rows = g.graph()
sccs = g.circles(edges)
scc_of = {m: i for i, c in enumerate(sccs) for m in c}

# top-level closure of heavy third-party modules
top: dict[str, set[str]] = {m: set() for m in known}
heavy_direct: dict[str, set[str]] = {m: set() for m in known}
for m, t, names, inside in rows:
    if inside: continue
    if t in known: top[m].add(t)
    elif t.split(".")[0] in HEAVY: heavy_direct[m].add(t.split(".")[0])
memo = {}
def heavy(m, seen=None):
    if m in memo: return memo[m]
    seen = seen or set()
    if m in seen: return set()
    seen.add(m)
    out = set(heavy_direct.get(m, ()))
    for t in top.get(m, ()):
        out |= heavy(t, seen)
    # a package's __init__ is imported along with its submodule
    memo[m] = out
    return out
def heavy_of_import(t):
    out = set(heavy(t))
    parts = t.split(".")
    for i in range(1, len(parts)):
        p = ".".join(parts[:i])
        if p in known: out |= heavy(p)
    return out

moved_total = 0
for m, path in known.items():
    if m.startswith(SKIP_SOURCES): continue
    src = path.read_text()
    tree = ast.parse(src)
    lines = src.splitlines(keepends=True)
    globals_defined = set()
    for n in tree.body:
        if isinstance(n, (ast.FunctionDef, ast.ClassDef, ast.AsyncFunctionDef)): globals_defined.add(n.name)
        elif isinstance(n, ast.Assign):
            for t in n.targets:
                for x in ast.walk(t):
                    if isinstance(x, ast.Name): globals_defined.add(x.id)
        elif isinstance(n, (ast.Import, ast.ImportFrom)):
            for a in n.names: globals_defined.add((a.asname or a.name).split(".")[0])
    top_imports = {ast.get_source_segment(src, n).strip() for n in tree.body if isinstance(n, (ast.Import, ast.ImportFrom))}
    package = m if path.name == "__init__.py" else m.rsplit(".", 1)[0]
    to_remove = []
    to_add = []
    for fn in ast.walk(tree):
        if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)): continue
        for st in fn.body:
            if not isinstance(st, (ast.Import, ast.ImportFrom)): continue
            if isinstance(st, ast.Import): continue  # `import x.y`: keep (rare for plxtools)
            if st.level: continue
            mod = st.module or ""
            if not mod.startswith("plxtools"): continue
            targets = [f"{mod}.{a.name}" if f"{mod}.{a.name}" in known else mod for a in st.names]
            if any(t not in known for t in targets): continue
            if any(t == m or (t in scc_of and scc_of.get(t) == scc_of.get(m)) for t in targets): continue
            if any(heavy_of_import(t) - heavy(m) for t in targets): continue
            if any(a.name in PATCHED for a in st.names): continue
            local = [a.asname or a.name for a in st.names]
            text = ast.get_source_segment(src, st).strip()
            if any(n in globals_defined for n in local) and text not in top_imports: continue
            ctx = lines[st.lineno - 1] + (lines[st.lineno - 2] if st.lineno > 1 else "")
            if "#" in ctx and REASON.search(ctx): continue
            if len(fn.body) == 1 or (len(fn.body) == 2 and isinstance(fn.body[0], ast.Expr) and isinstance(fn.body[0].value, ast.Constant)):
                continue  # the function would be empty
            to_remove.append((st.lineno, st.end_lineno))
            if text not in top_imports:
                to_add.append(text)
                top_imports.add(text)
                for n in local: globals_defined.add(n)
    if not to_remove: continue
    for a, b in sorted(to_remove, reverse=True):
        del lines[a - 1:b]
        # a blank line left doubled after the import: drop one
        if a - 1 < len(lines) and lines[a - 1].strip() == "" and a - 2 >= 0 and lines[a - 2].strip() == "" :
            del lines[a - 1]
        elif a - 1 < len(lines) and lines[a - 1].strip() == "" and a - 2 >= 0 and lines[a - 2].rstrip().endswith('"""') is False and lines[a-2].strip().startswith("def "):
            del lines[a - 1]
    new = "".join(lines)
    t2 = ast.parse(new)
    tops = [n for n in t2.body if isinstance(n, (ast.Import, ast.ImportFrom))]
    ls = new.splitlines(keepends=True)
    at = tops[-1].end_lineno if tops else 0
    ls[at:at] = [x + "\n" for x in sorted(set(to_add))]
    path.write_text("".join(ls))
    moved_total += len(to_remove)
    print(m, len(to_remove))
print("moved", moved_total)
