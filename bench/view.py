"""plx view's speed next to MuJoCo's own viewer, in a virtual display (needs xvfb, xdotool, imagemagick).

    python bench/view.py [--runs 3]

Prints, for the viewer example truck (examples/viewer/truck.openplx) on a warm cache:
- time to window: from starting the command to a window whose picture is a drawn scene (hundreds
  of colours), for `plx view` and for `python -m mujoco.viewer --mjcf` on the model plx exports,
  run in turn, with the ratio of each pair and the CPU each process had used by then;
- reload: from saving an edit to the window showing the new scene (`plx view`; MuJoCo's viewer
  does not watch files);
- stepping: simulated seconds per wall second of the session's stepping alone, and the CPU
  seconds of `plx check --simulate` with and without `--video` (GIF, MP4), run in turn.
Software OpenGL (llvmpipe, as under Xvfb) draws far slower than a GPU: the window numbers are an
upper bound for a desktop.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from tests.view.xvfb_session import ViewInXvfb, missing_tools  # noqa: E402


def _cpu(pid: int) -> float:
    """CPU seconds (user + system, all threads: llvmpipe's too) the process has used so far."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _drawn(v: ViewInXvfb, shot: Path, seconds: float = 60, unlike=None, cpu: list | None = None) -> float:
    """Seconds from the command's start until the window shows a drawn scene (unlike ``unlike``)."""
    import numpy as np

    end = time.perf_counter() + seconds
    while time.perf_counter() < end:
        try:
            img = v.screenshot(shot)
        except subprocess.CalledProcessError:  # the window was replaced while starting: find it again
            v.window = v._find_window() or v.window
            continue
        t = time.perf_counter()
        used = _cpu(v.proc.pid)
        if len(np.unique(img.reshape(-1, 3), axis=0)) > 100 and (
                unlike is None or np.abs(img.astype(int) - unlike.astype(int)).mean() > 0.5):
            if cpu is not None:
                cpu.append(used)
            return t
        time.sleep(0.05)
    raise RuntimeError(f"the window never showed the scene (window {v.window}; last picture {shot}); "
                       f"plx said: {v.stderr()[-600:]}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    if missing_tools():
        print(f"needs {', '.join(missing_tools())}", file=sys.stderr)
        return 2
    env = dict(os.environ)
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for f in (REPO / "examples" / "viewer").iterdir():
            shutil.copy(f, work / f.name)
        model = work / "truck.openplx"
        xml = work / "truck.xml"
        subprocess.run([sys.executable, "-m", "plxtools", "check", "--export-mjcf", str(xml), str(model)],
                       check=True, capture_output=True, env=env)  # also warms plx's cache
        plx_open, mj_open, reloads, ratios, plx_cpu, mj_cpu = [], [], [], [], [], []
        for _ in range(args.runs):
            with ViewInXvfb([model.name], work) as v:
                plx_open.append(_drawn(v, work / "s.png", cpu=plx_cpu) - v.started)
                v.wait_for("loaded Scene")
                time.sleep(0.5)
                before = v.screenshot(work / "before.png")
                text = model.read_text()
                t0 = time.perf_counter()
                model.write_text(text.replace("position.z: 1.1", "position.z: 2.6"))
                reloads.append(_drawn(v, work / "r.png", unlike=before) - t0)
                model.write_text(text)
            with ViewInXvfb(["--mjcf", str(xml)], work, command=[sys.executable, "-m", "mujoco.viewer"]) as v:
                mj_open.append(_drawn(v, work / "m.png", cpu=mj_cpu) - v.started)
            ratios.append(plx_open[-1] / mj_open[-1])  # the pair's ratio: both ran at about the same load

    from plxtools.view.session import ViewSession

    s = ViewSession(str(REPO / "examples" / "viewer" / "truck.openplx"))
    s.load()
    t = time.perf_counter()
    while time.perf_counter() - t < 1.0:
        s.sim.step(0.1)
    stepping = s.sim.time / (time.perf_counter() - t)

    def run_check(*extra: str) -> float:
        """CPU seconds (user + system) of the whole process: a loaded machine stretches wall time."""
        proc = subprocess.Popen([sys.executable, "-m", "plxtools", "check", "--simulate", "--duration", "4", *extra,
                                 "--model", "DrivingScene", str(REPO / "examples" / "viewer" / "truck.openplx")],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
        _, status, usage = os.wait4(proc.pid, 0)
        proc.returncode = os.waitstatus_to_exitcode(status)
        if proc.returncode != 0:
            raise RuntimeError(f"plx check {' '.join(extra)} exited with {proc.returncode}")
        return usage.ru_utime + usage.ru_stime

    with tempfile.TemporaryDirectory() as tmp:
        plain, gif, mp4 = [], [], []
        for _ in range(args.runs):  # in turn, so that a change in the machine's load hits all three
            plain.append(run_check())
            gif.append(run_check("--video", str(Path(tmp) / "a.gif")))
            mp4.append(run_check("--video", str(Path(tmp) / "a.mp4")))

    med = statistics.median
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores (a shared machine inflates every time below)")
    print(f"time to window (median of {args.runs}): plx view {med(plx_open):.2f} s; "
          f"MuJoCo's viewer on the exported MJCF {med(mj_open):.2f} s; ratio of the pairs {med(ratios):.2f}x "
          f"(each {', '.join(f'{r:.2f}' for r in ratios)})")
    print(f"CPU used by then (median of {args.runs}; a loaded machine stretches wall time, not this): "
          f"plx view {med(plx_cpu):.2f} s; MuJoCo's viewer {med(mj_cpu):.2f} s ({med(plx_cpu) / med(mj_cpu):.2f}x)")
    print(f"saved edit on screen (median of {args.runs}): plx view {med(reloads):.2f} s "
          f"(MuJoCo's viewer: no file watching)")
    print(f"stepping the truck without drawing: {stepping:.1f} simulated s per wall s")
    plain_s, gif_s, mp4_s = med(plain), med(gif), med(mp4)
    print(f"plx check --simulate, 4 s simulated, CPU (median of {args.runs}): {plain_s:.2f} s; with --video "
          f"GIF {gif_s:.2f} s ({gif_s / plain_s:.1f}x), MP4 {mp4_s:.2f} s ({mp4_s / plain_s:.1f}x) (25 fps, 640x480)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
