"""Regenerate the pictures of docs/view.md (needs xvfb, xdotool and imagemagick):

    python scripts/view_screenshots.py
    plx check --video docs/assets/truck-driving.gif --duration 4 --fps 12 --model DrivingScene examples/viewer/truck.openplx

The first opens `plx view` on the viewer example in a virtual display, drives it with the key table
for a moment and saves the window; then presses G (collision geometry) and saves it again.
"""

from __future__ import annotations

import shutil
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from tests.view.xvfb_session import ViewInXvfb, missing_tools  # noqa: E402


def main() -> int:
    if missing_tools():
        print(f"needs {', '.join(missing_tools())} (apt-get install xvfb xdotool imagemagick)", file=sys.stderr)
        return 2
    out = REPO / "docs" / "assets"
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for f in (REPO / "examples" / "viewer").iterdir():
            shutil.copy(f, work / f.name)
        with ViewInXvfb(["truck.openplx", "--keys", "truck.keys.toml"], work, size="1100x700") as v:
            v.wait_for("loaded Scene")
            time.sleep(1.5)
            v.xdotool("keydown", "Up")
            time.sleep(2.0)
            v.screenshot(out / "view-truck.png")
            v.xdotool("keyup", "Up")
            time.sleep(0.5)
            v.xdotool("key", "g")
            time.sleep(1.0)
            v.screenshot(out / "view-collision.png")
    print(f"wrote {out / 'view-truck.png'} and {out / 'view-collision.png'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
