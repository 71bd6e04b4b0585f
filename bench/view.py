"""plx view's speed next to MuJoCo's own viewer, in a virtual display (needs xvfb, xdotool, imagemagick).

    python bench/view.py [--runs 3]

Prints, for the viewer example truck (examples/viewer/truck.openplx) on a warm cache:
- time to window: from starting the command to a window whose picture is a drawn scene (hundreds
  of colours), for `plx view` and for `python -m mujoco.viewer --mjcf` on the model plx exports;
- reload: from saving an edit to the window showing the new scene (`plx view`; MuJoCo's viewer
  does not watch files);
- stepping: simulated seconds per wall second of the session's stepping alone, and `plx check
  --simulate` with and without `--video` per simulated second.
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


def _drawn(v: ViewInXvfb, shot: Path, seconds: float = 60, unlike=None) -> float:
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
        last = img
        if len(np.unique(img.reshape(-1, 3), axis=0)) > 100 and (
                unlike is None or np.abs(img.astype(int) - unlike.astype(int)).mean() > 0.5):
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
        plx_open, mj_open, reloads = [], [], []
        for _ in range(args.runs):
            with ViewInXvfb([model.name], work) as v:
                plx_open.append(_drawn(v, work / "s.png") - v.started)
                v.wait_for("loaded Scene")
                time.sleep(0.5)
                before = v.screenshot(work / "before.png")
                text = model.read_text()
                t0 = time.perf_counter()
                model.write_text(text.replace("position.z: 1.1", "position.z: 2.6"))
                reloads.append(_drawn(v, work / "r.png", unlike=before) - t0)
                model.write_text(text)
            with ViewInXvfb(["--mjcf", str(xml)], work, command=[sys.executable, "-m", "mujoco.viewer"]) as v:
                mj_open.append(_drawn(v, work / "m.png") - v.started)

    from plxtools.view.session import ViewSession

    s = ViewSession(str(REPO / "examples" / "viewer" / "truck.openplx"))
    s.load()
    t = time.perf_counter()
    while time.perf_counter() - t < 1.0:
        s.sim.step(0.1)
    stepping = s.sim.time / (time.perf_counter() - t)

    def run_check(*extra: str) -> float:
        t = time.perf_counter()
        subprocess.run([sys.executable, "-m", "plxtools", "check", "--simulate", "--duration", "4", *extra,
                        "--model", "DrivingScene", str(REPO / "examples" / "viewer" / "truck.openplx")],
                       check=True, capture_output=True, env=env)
        return time.perf_counter() - t

    with tempfile.TemporaryDirectory() as tmp:
        plain = min(run_check() for _ in range(2))
        gif = min(run_check("--video", str(Path(tmp) / "a.gif")) for _ in range(2))
        mp4 = min(run_check("--video", str(Path(tmp) / "a.mp4")) for _ in range(2))

    med = statistics.median
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores (a shared machine inflates every time below)")
    print(f"time to window (median of {args.runs}): plx view {med(plx_open):.2f} s; "
          f"MuJoCo's viewer on the exported MJCF {med(mj_open):.2f} s")
    print(f"saved edit on screen (median of {args.runs}): plx view {med(reloads):.2f} s "
          f"(MuJoCo's viewer: no file watching)")
    print(f"stepping the truck without drawing: {stepping:.1f} simulated s per wall s")
    print(f"plx check --simulate, 4 s simulated: {plain:.2f} s; with --video GIF {gif:.2f} s, MP4 {mp4:.2f} s "
          f"(25 fps, 640x480; per simulated second {plain / 4:.2f} / {gif / 4:.2f} / {mp4 / 4:.2f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
