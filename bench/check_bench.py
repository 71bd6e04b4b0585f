"""Benchmark: `plx check --simulate` on the BoxTruck next to bare MuJoCo running the same model.

    python bench/check_bench.py [--runs 7] [--duration 5]

Measured (wall clock, median of --runs runs, each a fresh process unless said otherwise):

1. ``plx check --simulate examples/boxtruck/boxtruck.openplx --duration 5``: the whole tool, from
   process start to exit: load the bundles, lint, instantiate, SNAP, checks, import MuJoCo, compile,
   simulate 2,500 steps with monitoring, report.
2. The floor, the peer being bare MuJoCo on the MJCF that plx exports for the same scene:
   a. in process: ``mujoco.MjModel.from_xml_path`` + ``mj_step`` x 2,500 (no Python start);
   b. as a subprocess: Python start + ``import mujoco`` + the same load and steps.

Goal (design.md): well under 2 s, and within 3x of the floor.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
MODEL = REPO / "examples" / "boxtruck" / "boxtruck.openplx"

FLOOR_SCRIPT = """
import sys, mujoco
m = mujoco.MjModel.from_xml_path(sys.argv[1])
d = mujoco.MjData(m)
if m.nkey:
    mujoco.mj_resetDataKeyframe(m, d, 0)
mujoco.mj_step(m, d, nstep=int(sys.argv[2]))
print(d.time)
"""


def plx_command() -> list[str]:
    exe = shutil.which("plx")
    if exe and Path(exe).resolve().parent == Path(sys.executable).resolve().parent:
        return [exe]
    return [sys.executable, "-m", "plxtools"]


def wall(cmd: list[str], runs: int, env: dict | None = None) -> list[float]:
    out = []
    for _ in range(runs):
        t = time.perf_counter()
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, cwd=REPO)
        out.append(time.perf_counter() - t)
        if r.returncode not in (0, 1):
            raise SystemExit(f"{' '.join(cmd)} failed ({r.returncode}):\n{r.stderr.decode()}")
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=7, help="runs per measurement (median reported; >= 5)")
    ap.add_argument("--duration", type=float, default=5.0, help="simulated seconds (default 5)")
    args = ap.parse_args()
    runs = max(5, args.runs)
    env = dict(os.environ, NO_COLOR="1")
    plx = plx_command()
    import mujoco

    with tempfile.TemporaryDirectory() as tmp:
        xml = Path(tmp) / "boxtruck.xml"
        r = subprocess.run([*plx, "check", "--export-mjcf", str(xml), "--output-format", "json", str(MODEL)],
                           capture_output=True, text=True, env=env, cwd=REPO)
        if not xml.is_file():
            raise SystemExit(f"export failed:\n{r.stdout}\n{r.stderr}")
        model = mujoco.MjModel.from_xml_path(str(xml))
        steps = int(round(args.duration / model.opt.timestep))

        check_cmd = [*plx, "check", "--simulate", "--duration", f"{args.duration:g}", "--output-format", "json",
                     str(MODEL)]
        warm = subprocess.run(check_cmd, capture_output=True, text=True, env=env, cwd=REPO)  # warm caches
        doc = json.loads(warm.stdout)
        sim = next(iter(doc["simulation"].values()))
        assert sim["steps"] == steps, (sim["steps"], steps)
        floor_cmd = [sys.executable, "-c", FLOOR_SCRIPT, str(xml), str(steps)]
        wall(floor_cmd, 1, env)  # warm

        # interleave the two subprocess measurements so machine load affects both alike
        t_check, t_floor_proc = [], []
        for _ in range(runs):
            t_check += wall(check_cmd, 1, env)
            t_floor_proc += wall(floor_cmd, 1, env)

        t_floor = []
        for _ in range(runs):
            t = time.perf_counter()
            m = mujoco.MjModel.from_xml_path(str(xml))
            d = mujoco.MjData(m)
            if m.nkey:
                mujoco.mj_resetDataKeyframe(m, d, 0)
            mujoco.mj_step(m, d, nstep=steps)
            t_floor.append(time.perf_counter() - t)

    med = statistics.median
    check, floor_proc, floor = med(t_check), med(t_floor_proc), med(t_floor)
    rows = [
        ("plx check --simulate (whole tool, fresh process)", check, min(t_check)),
        ("  of which: simulation loop inside plx (monitored)", sim["wall_time_s"], sim["wall_time_s"]),
        (f"bare MuJoCo {mujoco.__version__}: python + import mujoco + load MJCF + {steps} steps", floor_proc,
         min(t_floor_proc)),
        (f"bare MuJoCo {mujoco.__version__}: load MJCF + {steps} steps (in process)", floor, min(t_floor)),
    ]
    print(f"BoxTruck, {args.duration:g} s simulated = {steps} steps of {model.opt.timestep:g} s; "
          f"median of {runs} runs; {os.cpu_count()} CPUs; Python {sys.version.split()[0]}")
    print()
    w = max(len(r[0]) for r in rows)
    print(f"| {'measurement':<{w}} | median s | min s |")
    print(f"|{'-' * (w + 2)}|---------:|------:|")
    for name, m_, mn in rows:
        print(f"| {name:<{w}} | {m_:8.3f} | {mn:5.3f} |")
    print()
    print(f"plx / floor with Python start and import mujoco: {check / floor_proc:.2f}x "
          f"(goal: within 3x) -> {'OK' if check <= 3 * floor_proc else 'MISSED'}")
    print(f"plx / bare in-process load + steps: {check / floor:.1f}x (Python start, bundle loading, lint and "
          f"assembly have no counterpart there)")
    print(f"plx wall: {check:.3f} s (goal: well under 2 s) -> {'OK' if check < 2.0 else 'MISSED'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
