"""What the signal hook costs: the BoxTruck stepped for 4 s by `check --simulate`'s loop without a
controller (the peer), with a no-op controller (mj_step1 / mj_step2 per step), and by `plx test`'s
scenario (inputs and expectations read every step).  Prints wall seconds, best of 3.

    python bench/signals.py
"""

from __future__ import annotations

import time
from pathlib import Path

from plxtools.check.api import prepare
from plxtools.check.mujoco.simulate import simulate_compiled
from plxtools.check.testrun import run_scenario

REPO = Path(__file__).resolve().parent.parent
MODEL = REPO / "examples" / "boxtruck" / "boxtruck.openplx"
SCENARIO = REPO / "examples" / "boxtruck" / "drive.scenario.toml"


def best(f, n: int = 3) -> float:
    out = []
    for _ in range(n):
        t = time.perf_counter()
        f()
        out.append(time.perf_counter() - t)
    return min(out)


def main() -> None:
    prep = prepare(MODEL)
    plain = best(lambda: simulate_compiled(prep.compiled, 4.0))
    noop = best(lambda: simulate_compiled(prep.compiled, 4.0, controller=lambda t, m, d: None))
    scen = best(lambda: run_scenario(SCENARIO).wall_s)
    print("BoxTruck, 4 s simulated (2000 steps of 2 ms), best of 3:")
    print(f"  check --simulate loop, no controller (peer): {plain:.3f} s")
    print(f"  with a no-op controller (step1/step2):       {noop:.3f} s  ({noop / plain:.2f}x)")
    print(f"  plx test drive.scenario.toml, whole run:     {scen:.3f} s  (load, check, compile, run, report)")


if __name__ == "__main__":
    main()
