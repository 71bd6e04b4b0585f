"""`plx lint` throughput and one-file latency, side by side with flake8 in the same run.

Peer: flake8 (pyflakes + pycodestyle) on standard-library Python files of about the same number
of lines. Both run as real subprocesses with a warm cache; CPU time is the child's user+sys.
Also: `plx lint` on inheritance chains of 1,000 to 3,000 models (issue 14, item 9: every walk over
a chain is linear, so the time grows with the chain, not its square).
Run:  python bench/lint_bench.py          (everything)
      python bench/lint_bench.py chains   (the inheritance chains only)
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import bundle_files, bundle_root, count_lines, machine, median_of, python_corpus, table, tool  # noqa: E402

REPO = Path(__file__).resolve().parent.parent


def main() -> None:
    plx, flake8 = tool("plx"), tool("flake8")
    openplx = bundle_files()
    n_plx = count_lines(openplx)
    py = python_corpus(n_plx)
    n_py = count_lines(py)
    runs = 5
    median_of([plx, "lint", "--exit-zero", str(bundle_root())], 1)  # warm the bundle cache
    w_plx, c_plx = median_of([plx, "lint", "--exit-zero", str(bundle_root())], runs)
    w_cold, c_cold = median_of([plx, "lint", "--exit-zero", "--no-cache", str(bundle_root())], runs)
    w_f8, c_f8 = median_of([flake8, "--exit-zero", *map(str, py)], runs)
    one_plx = REPO / "examples" / "boxtruck" / "boxtruck.openplx"
    one_py = min(py, key=lambda p: abs(count_lines([p]) - 120))
    w1_plx, _ = median_of([plx, "lint", "--exit-zero", str(one_plx)], 10)
    w1_f8, _ = median_of([flake8, "--exit-zero", str(one_py)], 10)
    rows = [
        ("plx lint (465 bundle files)", n_plx, f"{w_plx:.3f}", f"{c_plx:.3f}", f"{n_plx / c_plx:,.0f}"),
        ("plx lint --no-cache (re-parse all)", n_plx, f"{w_cold:.3f}", f"{c_cold:.3f}", f"{n_plx / c_cold:,.0f}"),
        (f"flake8 ({len(py)} stdlib files)", n_py, f"{w_f8:.3f}", f"{c_f8:.3f}", f"{n_py / c_f8:,.0f}"),
    ]
    print(f"Lint throughput ({machine()}), median of {runs} runs, warm cache")
    print(table(rows, ("run", "lines", "wall s", "CPU s", "lines/CPU-s")))
    print()
    print("One file, wall time (median of 10)")
    print(table([
        (f"plx lint {one_plx.name}", count_lines([one_plx]), f"{w1_plx * 1000:.0f} ms"),
        (f"flake8 {one_py.name}", count_lines([one_py]), f"{w1_f8 * 1000:.0f} ms"),
    ], ("run", "lines", "wall")))
    ratio = (n_plx / c_plx) / (n_py / c_f8)
    print(f"\nplx lint per CPU-second: {ratio:.2f}x flake8's; one-file: {w1_plx / w1_f8:.2f}x flake8's wall time")


def chains() -> None:
    """Wall time of `plx lint` on `A0 is Physics3D.System`, `A1 is A0`, ... chains."""
    plx = tool("plx")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in (1000, 2000, 3000):
            path = Path(tmp) / f"chain_{n}.openplx"
            path.write_text("A0 is Physics3D.System\n" + "".join(f"A{i} is A{i - 1}\n" for i in range(1, n)))
            median_of([plx, "lint", "--exit-zero", str(path)], 1)  # warm the bundle cache
            w, c = median_of([plx, "lint", "--exit-zero", str(path)], 3)
            rows.append((f"chain of {n} models", n, f"{w:.2f}", f"{c:.2f}"))
    print(f"Inheritance chains ({machine()}), median of 3 runs")
    print(table(rows, ("run", "models", "wall s", "CPU s")))


if __name__ == "__main__":
    if sys.argv[1:] == ["chains"]:
        chains()
    else:
        main()
        print()
        chains()
