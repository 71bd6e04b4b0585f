"""Parser throughput on the official bundle corpus, next to lark's bare LALR work as the floor.

The floor is lark's LALR parser alone on the same pre-tokenised logical lines, building lark's
default tree (no AST, no lexing, no indentation handling). Run: python bench/parse_bench.py
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import bundle_files, count_lines, machine, table  # noqa: E402


def best(fn, runs=5) -> float:
    times = []
    for _ in range(runs):
        t = time.process_time()
        fn()
        times.append(time.process_time() - t)
    return min(times)


def main() -> None:
    from lark import Lark

    from plxtools.syntax import parse_text
    from plxtools.syntax.lexer import lex
    from plxtools.syntax.parser import _PassThrough

    files = bundle_files()
    texts = [p.read_text(encoding="utf-8") for p in files]
    lines = count_lines(files)
    chars = sum(len(t) for t in texts)
    grammar = (Path(__import__("plxtools.syntax.parser", fromlist=["x"]).__file__).with_name("openplx.lark")).read_text()
    bare = Lark(grammar, parser="lalr", lexer=_PassThrough, maybe_placeholders=True)
    logical = [line.tokens for t in texts for line in lex(t).lines if line.error is None]

    t_full = best(lambda: [parse_text(t) for t in texts])
    t_lex = best(lambda: [lex(t) for t in texts])
    t_bare = best(lambda: [bare.parse(toks) for toks in logical])
    rows = [
        ("plxtools parse (lex + LALR + AST)", f"{t_full * 1000:.0f}", f"{lines / t_full:,.0f}", f"{chars / t_full / 1e6:.2f}"),
        ("  of which: our lexer", f"{t_lex * 1000:.0f}", f"{lines / t_lex:,.0f}", ""),
        ("floor: lark LALR alone, lark trees", f"{t_bare * 1000:.0f}", f"{lines / t_bare:,.0f}", f"{chars / t_bare / 1e6:.2f}"),
    ]
    print(f"Parsing {len(files)} bundle files, {lines:,} lines, {chars:,} chars ({machine()}); best of 5, CPU time")
    print(table(rows, ("run", "ms", "lines/s", "MB/s")))


if __name__ == "__main__":
    main()
