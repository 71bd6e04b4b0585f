"""Parser throughput on the official bundle corpus, next to lark's bare LALR work as the floor.

The floor is lark's LALR parser alone on the same pre-tokenised logical lines, building lark's
default tree (no AST, no lexing, no indentation handling). Run: python bench/parse_bench.py

`--scaling` instead parses and formats one generated file (valid OpenPLX, models of a few
attributes each) at 1k, 10k and 100k lines (`--max 1000000` adds 1M), each size in a fresh
process, and prints CPU seconds, lines per second and the growth factor per 10x lines (10 is
linear). Run: python bench/parse_bench.py --scaling [--max 1000000]
"""

from __future__ import annotations

import subprocess
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


BLOCK = (
    "Part{i} is Physics3D.Bodies.RigidBody:\n"
    "    inertia.mass: {i}.5\n"
    "    geometry is Physics3D.Geometries.Box:\n"
    "        size: Math.Vec3.from_xyz(0.{i}, 1.0, 2.0 * 3)\n"
    "    hook is Physics3D.Interactions.MateConnector:\n"
    "        position: [1, 2,\n"
    "            3]  # a comment\n"
    "\n"
)


def generated(lines: int) -> str:
    per = BLOCK.count("\n")
    return "".join(BLOCK.format(i=i) for i in range(lines // per))


def one_size(lines: int) -> None:
    """In a fresh process: CPU seconds to parse, and to format, a generated file of `lines` lines."""
    from plxtools.fmt import format_text
    from plxtools.syntax import parse_text

    text = generated(lines)
    t = time.process_time()
    tree = parse_text(text)
    parse_s = time.process_time() - t
    assert not tree.diagnostics
    del tree
    t = time.process_time()
    result = format_text(text)
    fmt_s = time.process_time() - t
    assert result.ok, result.internal_error
    print(f"{text.count(chr(10))} {parse_s:.3f} {fmt_s:.3f}")


def scaling(max_lines: int) -> None:
    sizes = [s for s in (1_000, 10_000, 100_000, 1_000_000) if s <= max_lines]
    rows = []
    prev = None
    for n in sizes:
        out = subprocess.run([sys.executable, __file__, "--one", str(n)], capture_output=True, text=True, check=True)
        lines, p, f = out.stdout.split()
        lines, p, f = int(lines), float(p), float(f)
        grow = "" if prev is None else f"{p / prev[0]:.1f} / {f / prev[1]:.1f}"
        rows.append((f"{lines:,}", f"{p:.2f}", f"{lines / p:,.0f}", f"{f:.2f}", f"{lines / f:,.0f}", grow))
        print(f"  {lines:,} lines: parse {p:.2f} s, fmt {f:.2f} s", file=sys.stderr, flush=True)
        prev = (p, f)
    print(f"One generated file per size ({machine()}); CPU seconds, fresh process per size")
    print(table(rows, ("lines", "parse s", "parse lines/s", "fmt s", "fmt lines/s", "x per 10x (parse / fmt)")))


if __name__ == "__main__":
    if "--one" in sys.argv:
        one_size(int(sys.argv[sys.argv.index("--one") + 1]))
    elif "--scaling" in sys.argv:
        scaling(int(sys.argv[sys.argv.index("--max") + 1]) if "--max" in sys.argv else 100_000)
    else:
        main()
