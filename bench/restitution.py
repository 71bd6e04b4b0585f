"""Restitution table: the rebound speed ratio of drops (0.05-5 m) and head-on impacts (mass ratios
1-10) for e in {0, 0.2, 0.5, 0.8, 1} at several time steps, through plxtools' Python API.

    python bench/restitution.py              # plain table
    python bench/restitution.py --markdown   # the table in docs/physics.md

The peer is the impact law: the normal speed after an impact is e times the speed before it.
A cell is marked * where it is more than 3 % off e and the A137 note is a warning naming a slower
speed than that impact's; ! where it is off without such a warning (a failure)."""

from __future__ import annotations

import argparse
import platform
import re
import sys
import time
from datetime import date
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "physics"))

from impacts import drop, head_on, within  # noqa: E402

ES = (0.0, 0.2, 0.5, 0.8, 1.0)
HEIGHTS = (0.05, 0.2, 1.0, 3.0, 5.0)
MASS_RATIOS = (1.0, 3.0, 10.0)
STEPS = (0.0005, 0.001, 0.002, 0.005)


def warned_below(notes: list) -> float:
    for n in notes:
        m = re.search(r"slower than ([0-9.e+-]+) m/s", n.message)
        if n.severity == "warning" and m:
            return float(m.group(1))
    return 0.0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--markdown", action="store_true")
    ap.add_argument("--steps", default=",".join(str(s) for s in STEPS), help="time steps, comma-separated")
    args = ap.parse_args()
    steps = [float(s) for s in args.steps.split(",")]
    head = ["h (s)", "e"] + [f"drop {h:g} m" for h in HEIGHTS] + [f"head-on 1:{m:g}" for m in MASS_RATIOS]
    rows, bad, marked, t0 = [], 0, 0, time.perf_counter()
    for h in steps:
        for e in ES:
            row = [f"{h:g}", f"{e:g}"]
            for H in HEIGHTS:
                got = drop(e, H, h)
                mark = ""
                if not within(e, got["ratio"]):
                    ok = got["speed"] < warned_below(got["notes"])
                    mark = "*" if ok else "!"
                    bad += not ok
                    marked += ok
                row.append(f"{got['ratio']:.3f}{mark}")
            for m in MASS_RATIOS:
                got = head_on(e, m, h)
                ok = within(e, got["ratio"])
                bad += not ok
                row.append(f"{got['ratio']:.3f}" + ("" if ok else "!"))
            rows.append(row)
    if args.markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
        for r in rows:
            print("| " + " | ".join(r) + " |")
    else:
        w = [max(len(x), *(len(r[i]) for r in rows)) for i, x in enumerate(head)]
        for r in (head, *rows):
            print("  ".join(x.ljust(k) for x, k in zip(r, w)))
    print(f"\n{len(rows) * (len(HEIGHTS) + len(MASS_RATIOS))} impacts: {marked} more than 3 % off e with an A137 "
          f"warning (*), {bad} off without one (!); {time.perf_counter() - t0:.1f} s; "
          f"{platform.python_version()}, {date.today()}")
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
