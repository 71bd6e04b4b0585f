"""The physics verification table: every case of tests/physics/physics_cases.py run through
`plx check --simulate --trace`, with the closed-form value, the measured one and the error.

    python bench/physics.py            # every case
    python bench/physics.py --markdown # the table for docs/physics.md

The peer is the textbook: each case states its formula and tolerance."""

from __future__ import annotations

import argparse
import platform
import sys
import time
from datetime import date
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "physics"))

from physics_cases import CASES, run_model  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--markdown", action="store_true", help="print a Markdown table")
    ap.add_argument("-k", default="", help="only cases whose name contains this text")
    args = ap.parse_args()
    rows, failed = [], 0
    runs: dict[tuple[str, float], object] = {}
    t_all = time.perf_counter()
    for case in CASES:
        if args.k not in case.name:
            continue
        key = (case.model, case.duration)
        if key not in runs:
            runs[key] = run_model(case.path, case.duration)
        run = runs[key]
        measured = case.measure(run)
        err = case.error(measured)
        bad = sorted(case.must_not_report & run.codes)
        ok = err <= case.tol and not bad
        failed += not ok
        tol = f"{case.tol:g}" if case.absolute else f"{100 * case.tol:g} %"
        shown = f"{err:.3g}" if case.absolute else f"{100 * err:.3f} %"
        rows.append((case.name, case.what, f"{case.expected:.6g}", f"{measured:.6g}", shown, tol,
                     "pass" if ok else "FAIL" + (f" ({', '.join(bad)})" if bad else "")))
    head = ("case", "quantity", "closed form", "plx", "error", "tolerance", "")
    if args.markdown:
        print("| " + " | ".join(head[:-1]) + " | result |")
        print("|" + "---|" * len(head))
        for r in rows:
            print("| " + " | ".join(r) + " |")
    else:
        widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(head)]
        for r in (head, *rows):
            print("  ".join(str(x).ljust(w) for x, w in zip(r, widths)))
    print(f"\n{len(rows)} cases, {failed} outside tolerance; {time.perf_counter() - t_all:.1f} s; "
          f"{platform.python_version()}, {platform.machine()}, {date.today()}")
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
