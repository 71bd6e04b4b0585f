"""Fuzzing campaign for the parser, `plx lint` and `plx fmt` on mutated official bundle files.

Each case takes a bundle file and applies 1-4 random edits (insert a piece of OpenPLX or a hostile
character, delete a span, duplicate or re-indent a line, swap line breaks for \\r or \\r\\n). Then:

- parse and lint (the public API, `analyse_tree`) must not raise, and every position must be
  inside the text and agree with the line index;
- if the mutant has no syntax error, `format_text` must accept it (or refuse it with a reason,
  counted separately), and its output must: parse without errors, have the same tokens under an
  independent tokenizer, report the same lint results (suppressions applied, layout codes aside),
  and format to itself.

The budget is fixed: `--cases N` (default 3000) with `--seed S` (default 1), so a run is
reproducible. Failing inputs are written to `--out` (default: not written). Run:

    python bench/fuzz_syntax_fmt.py --cases 3000 --seed 1 --out /tmp/fuzz-failures
"""

from __future__ import annotations

import argparse
import random
import sys
import time
import traceback
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from _common import bundle_files, machine  # noqa: E402

PIECES = [
    "chassis", "this.x", "axis", " is ", " becomes ", ":", ".", ",", "(", ")", "[", "]", "{", "}", "+", "-",
    "*", "/", "->", "1", "2.5", "1e308", "9" * 4301, '"s"', '"""', '"', "`a.b`", "``", "# c",
    "  # plx: ignore[N003]", "# plx: ignore", "# plx: fmt: off\n", "# plx: fmt: on\n", "\t", "\n", "\r",
    "\r\n", "\f", "\u2028", "é", "=", "fn f(a: Real,\n", "const ", "with ", "\n    x is Real: 1\n",
]


def mutate(text: str, rnd: random.Random) -> str:
    for _ in range(rnd.randint(1, 4)):
        n = len(text)
        at = rnd.randint(0, n)
        op = rnd.random()
        if op < 0.45:
            text = text[:at] + rnd.choice(PIECES) + text[at:]
        elif op < 0.65:
            text = text[:at] + text[at + rnd.randint(1, 8):]
        elif op < 0.8:
            lines = text.split("\n")
            i = rnd.randrange(len(lines))
            lines.insert(i, lines[i])
            text = "\n".join(lines)
        elif op < 0.92:
            lines = text.split("\n")
            i = rnd.randrange(len(lines))
            lines[i] = " " * rnd.choice([1, 2, 3, 4, 5, 8]) + lines[i].lstrip(" ")
            text = "\n".join(lines)
        else:
            text = text.replace("\n", rnd.choice(["\r", "\r\n"]))
    return text


def check_positions(tree) -> str | None:
    text, index = tree.text, tree.index
    for d in tree.diagnostics:
        for p in (d.span.start, d.span.end):
            if not 0 <= p.offset <= len(text) or (p.line, p.column) != tuple(index.pos(p.offset))[1:]:
                return f"bad position {p} for {d.code}"
    return None


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=3000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", type=Path)
    args = ap.parse_args()

    from plxtools.config import Config
    from plxtools.fmt import format_text
    from plxtools.rules.analysis import analyse_tree
    from plxtools.syntax import parse_text
    from tests.fmt.helpers import lint_signature, oracle_tokens

    texts = [p.read_text(encoding="utf-8-sig") for p in bundle_files()]
    rnd = random.Random(args.seed)
    tally: Counter[str] = Counter()
    failures: list[tuple[str, str]] = []
    cfg = Config()
    t0 = time.perf_counter()
    for case in range(args.cases):
        text = mutate(rnd.choice(texts), rnd)
        problem = None
        try:
            tree = parse_text(text)
            problem = check_positions(tree)
            analyse_tree(tree, cfg)
            tally["linted"] += 1
            if not tree.has_errors and problem is None:
                result = format_text(text)
                if result.text is None:
                    tally["fmt refused (" + (result.internal_error or "syntax").split(" (")[0] + ")"] += 1
                else:
                    tally["formatted"] += 1
                    out = result.text
                    again = parse_text(out)
                    if again.has_errors:
                        problem = "fmt output does not parse"
                    elif oracle_tokens(text) != oracle_tokens(out):
                        problem = "fmt changed the tokens"
                    elif lint_signature(text) != lint_signature(out):
                        problem = "fmt changed the lint results"
                    elif format_text(out).text != out:
                        problem = "fmt is not idempotent"
        except Exception:  # noqa: BLE001 - any exception is a finding
            problem = "raised: " + traceback.format_exc(limit=3)
        if problem:
            failures.append((problem, text))
            if args.out:
                args.out.mkdir(parents=True, exist_ok=True)
                (args.out / f"case{case}.openplx").write_text(text)
                (args.out / f"case{case}.txt").write_text(problem)
    elapsed = time.perf_counter() - t0
    print(f"fuzz_syntax_fmt: {args.cases} mutants of {len(texts)} bundle files, seed {args.seed}, "
          f"{elapsed:.0f} s ({machine()})")
    for k, v in sorted(tally.items()):
        print(f"  {k}: {v}")
    print(f"  failures: {len(failures)}")
    for problem, _ in failures[:10]:
        print("   -", problem.strip().splitlines()[-1])
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
