"""How long `plx check --simulate --timeout T` takes on a heap of overlapping bodies (issue 33).

N unit boxes all at the origin: every pair overlaps, the worst case of the initial-overlap check
and of MuJoCo's contacts. Prints, per N, the wall time of the whole command against the limit
asked for (the peer compared: the limit itself), the peak memory of the process, and the A109
message that stopped it.

    python bench/overlap_timeout.py --bodies 100 300 1000 --timeout 20
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time


def heap(n: int) -> str:
    lines = ["Scene is Physics3D.System:"]
    for i in range(n):
        lines += [f"    b{i} is Physics3D.Bodies.RigidBody:", "        inertia.mass: 1",
                  "        g is Physics3D.Geometries.Box:", "            size: {1, 1, 1}"]
    return "\n".join(lines) + "\n"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bodies", type=int, nargs="+", default=[100, 300, 1000])
    ap.add_argument("--timeout", type=float, default=20.0)
    ap.add_argument("--duration", type=float, default=0.5)
    args = ap.parse_args()
    print(f"{'bodies':>6} {'limit s':>8} {'wall s':>8} {'over %':>7} {'peak MB':>8}  stopped by")
    with tempfile.TemporaryDirectory() as d:
        for n in args.bodies:
            f = os.path.join(d, f"heap{n}.openplx")
            with open(f, "w") as fh:
                fh.write(heap(n))
            t0 = time.perf_counter()
            r = subprocess.run([sys.executable, "-m", "plxtools", "check", "--simulate", "--duration",
                                str(args.duration), "--timeout", str(args.timeout), "--output-format", "json", f],
                               capture_output=True, text=True)
            wall = time.perf_counter() - t0
            peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024  # the largest child so far
            try:
                diags = json.loads(r.stdout)["diagnostics"]
                a109 = next((x["message"] for x in diags if x["code"] == "A109"), "(finished within the limit)")
            except (ValueError, KeyError):
                a109 = f"exit {r.returncode}: {r.stderr.strip()[-200:]}"
            print(f"{n:>6} {args.timeout:>8g} {wall:>8.1f} {100 * (wall / args.timeout - 1):>6.0f}% {peak:>8.0f}  "
                  f"{a109[:110]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
