"""Run `plx view` in a virtual X server (Debian's xvfb), send keys with xdotool, take screenshots with
ImageMagick's `import`: the real viewer window, as a user sees it. Used by test_window_xvfb.py and by
scripts/view_screenshots.py (the pictures in docs/view.md)."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

TOOLS = ("Xvfb", "xdotool", "import")


def missing_tools() -> list[str]:
    return [t for t in TOOLS if shutil.which(t) is None]


class ViewInXvfb:
    """``plx view ARGS`` on a fresh virtual display; use as a context manager."""

    def __init__(self, args: list[str], workdir: Path, size: str = "1280x800", command: list[str] | None = None):
        self.command = command or [sys.executable, "-m", "plxtools", "view"]
        self.args = args
        self.workdir = workdir
        self.size = size
        self.log = workdir / "plx-view.log"

    def __enter__(self) -> "ViewInXvfb":
        for n in range(90, 190):
            if not Path(f"/tmp/.X{n}-lock").exists() and not Path(f"/tmp/.X11-unix/X{n}").exists():
                break
        self.display = f":{n}"
        self.xvfb = subprocess.Popen(["Xvfb", self.display, "-screen", "0", f"{self.size}x24", "-nolisten", "tcp"],
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.env = dict(os.environ, DISPLAY=self.display)
        self._wait(lambda: subprocess.run(["xdotool", "getmouselocation"], env=self.env,
                                          capture_output=True).returncode == 0, 10, "Xvfb did not start")
        self.started = time.perf_counter()
        self.proc = subprocess.Popen([*self.command, *self.args], cwd=self.workdir,
                                     env=self.env, stdout=subprocess.DEVNULL, stderr=open(self.log, "w"))
        self.window = self._wait(self._find_window, 60, "no MuJoCo window appeared")
        geo = subprocess.run(["xdotool", "getwindowgeometry", "--shell", self.window], env=self.env,
                             capture_output=True, text=True).stdout
        vals = dict(line.split("=") for line in geo.split())
        self.x, self.y, self.w, self.h = (int(vals[k]) for k in ("X", "Y", "WIDTH", "HEIGHT"))
        self.xdotool("mousemove", str(self.x + self.w // 2), str(self.y + self.h // 2))
        return self

    def __exit__(self, *exc) -> None:
        for p in (self.proc, self.xvfb):
            if p.poll() is None:
                p.send_signal(signal.SIGTERM)
                try:
                    p.wait(10)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()

    def _find_window(self) -> str | None:
        if self.proc.poll() is not None:
            raise AssertionError(f"{self.command[-1]} exited with {self.proc.returncode}: {self.stderr()}")
        r = subprocess.run(["xdotool", "search", "--onlyvisible", "--name", "MuJoCo"], env=self.env, capture_output=True, text=True)
        return r.stdout.split()[0] if r.returncode == 0 and r.stdout.split() else None

    def _wait(self, what, seconds: float, message: str):
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            got = what()
            if got:
                return got
            time.sleep(0.1)
        raise AssertionError(f"{message} within {seconds} s; plx view said: {self.stderr()}")

    def wait_for(self, text: str, count: int = 1, seconds: float = 30) -> None:
        self._wait(lambda: self.stderr().count(text) >= count, seconds, f"{text!r} x{count} not printed")

    def stderr(self) -> str:
        return self.log.read_text() if self.log.exists() else ""

    def xdotool(self, *args: str) -> None:
        subprocess.run(["xdotool", *args], env=self.env, check=True)

    def screenshot(self, path: Path, window_only: bool = True):
        """Save the window (or the whole screen) and return it as an (H, W, 3) array."""
        import numpy as np
        from PIL import Image

        target = self.window if window_only else "root"
        subprocess.run(["import", "-window", target, str(path)], env=self.env, check=True)
        with Image.open(path) as im:
            return np.asarray(im.convert("RGB"))
