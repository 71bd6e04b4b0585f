"""The numbers of issue 28's before/after table: lines, modules, longest function, complexity, homes."""

from __future__ import annotations

import ast
import re
import sys
from collections import defaultdict
from pathlib import Path

ROOT = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent)
PACKAGE = ROOT / "plxtools"


def main() -> None:
    from radon.complexity import cc_visit

    files = sorted(PACKAGE.rglob("*.py"))
    lines = {f: len(f.read_text(encoding="utf-8").splitlines()) for f in files}
    longest = (0, "")
    for f in files:
        for node in ast.walk(ast.parse(f.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                n = node.end_lineno - node.lineno + 1
                if n > longest[0]:
                    longest = (n, f"{f.relative_to(ROOT)}:{node.name}")
    cc: dict[str, int] = {}

    def walk(blocks, where):
        for b in blocks:
            cc[f"{where}:{getattr(b, 'fullname', b.name)}"] = b.complexity
            walk(getattr(b, "closures", []), where)
            walk(getattr(b, "methods", []), where)

    for f in files:
        walk(cc_visit(f.read_text(encoding="utf-8")), f.relative_to(ROOT).as_posix())
    worst = max(cc.items(), key=lambda kv: kv[1])
    catalog = PACKAGE / "rules" / "catalog"
    where = defaultdict(set)
    for f in files:
        if catalog in f.parents:
            continue
        for code in re.findall(r"""["']([A-Z]\d{3})["']""", f.read_text(encoding="utf-8")):
            where[code].add(f)
    lsp = {f.relative_to(ROOT).as_posix(): lines[f] for f in files if (PACKAGE / "lsp") in f.parents}
    print(f"python lines in plxtools/      {sum(lines.values()):>8,}")
    print(f"modules                        {len(files):>8}")
    print(f"modules in check/ (flat)       {len([f for f in files if f.parent == PACKAGE / 'check']):>8}")
    print(f"longest function (lines)       {longest[0]:>8}  {longest[1]}")
    print(f"highest complexity (radon)     {worst[1]:>8}  {worst[0]}")
    print(f"functions above complexity 25  {sum(1 for v in cc.values() if v > 25):>8}")
    print(f"largest lsp module (lines)     {max(lsp.values()):>8}  {max(lsp, key=lsp.get)}")
    print(f"codes written in >1 module     {sum(1 for v in where.values() if len(v) > 1):>8}")


if __name__ == "__main__":
    main()
