"""The import graph of plxtools: circles between modules, imports written inside functions, and
constants the server reads from the model or check layers (issue 38).

    python dev/import_graph.py                 # every circle, then the counts
    python dev/import_graph.py --inside check  # only circles among modules of plxtools.check

An import is an edge wherever it is written (at the top of a module or inside a function): a
function-level import hides a route from readers, not from this graph. A circle is a strongly
connected component of more than one module (Tarjan). tests/test_layers.py runs it.
"""

from __future__ import annotations

import argparse
import ast
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "plxtools"


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def modules() -> dict[str, Path]:
    return {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def imports_of(path: Path, known: dict[str, Path]):
    """(imported module, names imported from it, written inside a function?) for each import."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    me = module_name(path)
    package = me if path.name == "__init__.py" else me.rsplit(".", 1)[0]

    def visit(node, inside: bool):
        for child in ast.iter_child_nodes(node):
            deeper = inside or isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda))
            if isinstance(child, ast.Import):
                for a in child.names:
                    yield a.name, (), inside
            elif isinstance(child, ast.ImportFrom):
                base = child.module or ""
                if child.level:
                    up = package.split(".")[: len(package.split(".")) - child.level + 1]
                    base = ".".join(up + ([base] if base else []))
                names = tuple(a.name for a in child.names)
                # `from plxtools.check import aftersim` imports the module plxtools.check.aftersim
                subs = [f"{base}.{n}" for n in names if f"{base}.{n}" in known]
                if subs:
                    for s in subs:
                        yield s, (), inside
                    rest = tuple(n for n in names if f"{base}.{n}" not in known)
                    if rest:
                        yield base, rest, inside
                else:
                    yield base, names, inside
            else:
                yield from visit(child, deeper)

    yield from visit(tree, False)


def graph() -> tuple[dict[str, set[str]], list[tuple[str, str, tuple[str, ...], bool]]]:
    known = modules()
    edges: dict[str, set[str]] = {m: set() for m in known}
    rows = []
    for m, path in known.items():
        for target, names, inside in imports_of(path, known):
            rows.append((m, target, names, inside))
            if target in known and target != m:
                edges[m].add(target)
    return edges, rows


def circles(edges: dict[str, set[str]], inside: str | None = None) -> list[list[str]]:
    """Strongly connected components of more than one module (restricted to a package if given)."""
    if inside:
        keep = {m for m in edges if m == inside or m.startswith(inside + ".")}
        edges = {m: {t for t in ts if t in keep} for m, ts in edges.items() if m in keep}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []
    counter = [0]
    sys.setrecursionlimit(10000)

    def strong(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(edges):
        if v not in index:
            strong(v)
    return sorted(out)


def constants_read(rows, source: str, targets: tuple[str, ...]) -> list[str]:
    """`from <target> import NAME` (an UPPER_CASE name) written in a module of `source`."""
    return sorted(f"{m} <- {t}.{n}" for m, t, names, _inside in rows
                  if (m == source or m.startswith(source + "."))
                  and any(t == x or t.startswith(x + ".") for x in targets)
                  for n in names if n.isupper() and len(n) > 1)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--inside", help="only circles among the modules of this package (plxtools.check)")
    ap.add_argument("--root", type=Path, help="another checkout (to count main's, for a before/after)")
    args = ap.parse_args(argv)
    if args.root is not None:
        global ROOT, PACKAGE
        ROOT, PACKAGE = args.root.resolve(), args.root.resolve() / "plxtools"
    edges, rows = graph()
    inside = args.inside and (args.inside if args.inside.startswith("plxtools") else f"plxtools.{args.inside}")
    found = circles(edges, inside)
    for comp in found:
        print("circle:", " <-> ".join(comp))
    internal = [r for r in rows if r[1].startswith("plxtools")]
    print(f"modules: {len(edges)}")
    print(f"imports of plxtools modules: {len(internal)}, written inside functions: "
          f"{sum(1 for r in internal if r[3])}")
    print(f"all imports: {len(rows)}, written inside functions: {sum(1 for r in rows if r[3])}")
    print(f"circles{' inside ' + inside if inside else ''}: {len(found)}")
    for line in constants_read(rows, "plxtools.lsp", ("plxtools.model", "plxtools.check")):
        print("lsp reads a constant:", line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
