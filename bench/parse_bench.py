"""Parser throughput next to lark's bare LALR work as the floor, on the official bundles and on
the generated user corpus (10k lines in files of 112 lines, bench/corpus.py).

The floor is lark's LALR parser alone on the same pre-tokenised logical lines, building lark's
default tree (no AST, no lexing, no indentation handling); `x floor` is our parse over it.
Run: python bench/parse_bench.py

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
    """Least CPU time of `runs` calls, with the cyclic collector off as `plx lint` runs (every row
    alike; what a run built is freed and collected between runs, outside the timing)."""
    import gc

    times = []
    for _ in range(runs):
        gc.collect()
        gc.disable()
        try:
            t = time.process_time()
            fn()
            times.append(time.process_time() - t)
        finally:
            gc.enable()
    return min(times)


def measure(name: str, texts: list[str], lines: int) -> list[tuple]:
    """Rows for one corpus: our parse, our lexer alone, and lark's LALR floor on the same tokens."""
    from lark import Lark

    from plxtools.syntax import parse_text
    from plxtools.syntax.lexer import lex
    from plxtools.syntax.lalr import PassThrough as _PassThrough

    chars = sum(len(t) for t in texts)
    grammar = (Path(__import__("plxtools.syntax.parser", fromlist=["x"]).__file__).with_name("openplx.lark")).read_text()
    bare = Lark(grammar, parser="lalr", lexer=_PassThrough, maybe_placeholders=True)
    logical = [line.tokens for t in texts for line in lex(t).lines if line.error is None]

    t_full = best(lambda: [parse_text(t) for t in texts])
    t_lex = best(lambda: [lex(t) for t in texts])
    t_bare = best(lambda: [bare.parse(toks) for toks in logical])
    return [
        (f"{name}: plxtools parse (lex + fast path or LALR + AST)", f"{t_full * 1000:.0f}", f"{lines / t_full:,.0f}",
         f"{chars / t_full / 1e6:.2f}", f"{t_full / t_bare:.2f}"),
        (f"{name}:   of which our lexer", f"{t_lex * 1000:.0f}", f"{lines / t_lex:,.0f}", "", ""),
        (f"{name}: floor, lark LALR alone, lark trees", f"{t_bare * 1000:.0f}", f"{lines / t_bare:,.0f}",
         f"{chars / t_bare / 1e6:.2f}", "1.00"),
    ]


def main() -> None:
    import tempfile

    import corpus

    files = bundle_files()
    texts = [p.read_text(encoding="utf-8") for p in files]
    rows = measure(f"{len(files)} bundle files", texts, count_lines(files))
    with tempfile.TemporaryDirectory() as tmp:
        user = corpus.openplx_files(Path(tmp), 10_000)
        rows += measure(f"{len(user)} generated user files", [p.read_text() for p in user], count_lines(user))
    print(f"Parsing the official bundles and the generated 10k-line user corpus (bench/corpus.py) ({machine()}); "
          "best of 5, CPU time, cyclic GC off as in plx lint")
    print(table(rows, ("run", "ms", "lines/s", "MB/s", "x floor")))


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
