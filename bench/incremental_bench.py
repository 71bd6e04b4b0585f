"""What re-parsing a document after one keystroke costs in the editor (plxtools/syntax/incremental.py)
against a full parse of the same text, on a generated 20,000-line document: a keystroke at the end
(nothing moves), in the middle (half the chunks move) and at the top (every chunk moves). Moved
chunks are copied, never changed in place, so a tree a reader still holds stays valid.

    python bench/incremental_bench.py [--lines 20000]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from parse_bench import generated  # noqa: E402


def median(xs: list[float]) -> float:
    xs = sorted(xs)
    return xs[len(xs) // 2]


def main() -> None:
    from plxtools.syntax import parse_text
    from plxtools.syntax.incremental import IncrementalParser

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lines", type=int, default=20_000)
    ap.add_argument("--runs", type=int, default=7)
    args = ap.parse_args()
    text = generated(args.lines)
    full = []
    for _ in range(3):
        t = time.perf_counter()
        parse_text(text, "doc.openplx")
        full.append(time.perf_counter() - t)
    print(f"{text.count(chr(10)):,} lines; full parse (the peer): {1e3 * median(full):.1f} ms")
    for where, pos in (("end", len(text) - 1), ("middle", text.index("\nPart", len(text) // 2) + 1), ("top", 0)):
        parser = IncrementalParser()
        parser.parse(text, "doc.openplx")
        cur, times = text, []
        for i in range(args.runs):
            cur = cur[:pos] + "# k\n" + cur[pos:] if i % 2 == 0 else cur[:pos] + cur[pos + 4:]
            t = time.perf_counter()
            parser.parse(cur, "doc.openplx")
            times.append(time.perf_counter() - t)
        print(f"keystroke at the {where:6}: {1e3 * median(times):7.1f} ms  ({median(full) / median(times):.1f}x faster "
              f"than a full parse)")


if __name__ == "__main__":
    main()
